#include <strata/core/error.h>
#include <strata/io/cad_content.h>
#include <strata/io/input_file.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <string>

namespace strata {
namespace {

constexpr std::size_t kHead = 4096;  // enough for any format's opening, and a few IGES records

bool is_blank(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

bool is_digit(char c) {
    return c >= '0' && c <= '9';
}

std::string_view without_bom(std::string_view s) {
    if (s.substr(0, 3) == "\xEF\xBB\xBF") s.remove_prefix(3);
    return s;
}

/// STEP (ISO 10303-21): the keyword `ISO-10303-21` and its `;` open the file; white space and
/// comments may come before.
bool holds_step(std::string_view s) {
    s = without_bom(s);
    for (;;) {
        while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
        if (s.substr(0, 2) != "/*") break;
        const std::size_t end = s.find("*/", 2);
        if (end == std::string_view::npos) return false;
        s.remove_prefix(end + 2);
    }
    constexpr std::string_view kKeyword = "ISO-10303-21";
    if (s.size() < kKeyword.size() || !std::equal(kKeyword.begin(), kKeyword.end(), s.begin(), [](char k, char c) {
            return k == std::toupper(static_cast<unsigned char>(c));
        }))
        return false;
    s.remove_prefix(kKeyword.size());
    while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
    return !s.empty() && s.front() == ';';
}

/// IGES: the first record (blank lines and CR line ends skipped, as OpenCASCADE does) carries
/// its section letter and sequence number: `S`, `G`, `C` or `F` (a compressed file's flag
/// section, by the standard and by some writers) or `B` (binary) in column 73, digits after
/// it; or, in a record that lost its padding, the letter and the number 1 in its last 8 columns.
bool holds_iges(std::string_view s) {
    s = without_bom(s);
    while (!s.empty() && (s.front() == '\r' || s.front() == '\n')) s.remove_prefix(1);
    std::string_view line = s.substr(0, s.find_first_of("\r\n"));
    if (line.size() > 160) return false;  // not a record of 80 columns, whatever it ends with
    while (!line.empty() && is_blank(line.back())) line.remove_suffix(1);
    const auto section = [](char c) { return c == 'S' || c == 'G' || c == 'C' || c == 'F' || c == 'B'; };
    if (line.size() >= 74 && section(line[72])) {
        std::string_view number = line.substr(73);
        while (!number.empty() && number.front() == ' ') number.remove_prefix(1);
        if (!number.empty() && std::all_of(number.begin(), number.end(), is_digit)) return true;
    }
    // A record shorter than 80 columns (its text's padding lost) still ends with the 8-column
    // field of the letter and the sequence number, 1 on a section's first record.
    if (line.size() < 8 || !section(line[line.size() - 8])) return false;
    std::string_view number = line.substr(line.size() - 7);
    while (!number.empty() && (number.front() == ' ' || number.front() == '0')) number.remove_prefix(1);
    return number == "1";
}

/// OpenCASCADE's text BREP: written by BRepTools with the DBRep header, or bare from its
/// `CASCADE Topology V1/V2/V3` line.
bool holds_brep(std::string_view s) {
    s = without_bom(s);
    while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
    if (s.substr(0, 19) == "DBRep_DrawableShape") return true;
    const std::string_view line = s.substr(0, s.find_first_of("\r\n"));
    return line.find("CASCADE Topology") != std::string_view::npos;
}

/// A CAD format: its name and the test of a file's opening bytes.
struct CadFormat {
    CadContent kind;
    const char* name;
    bool (*holds)(std::string_view head);
};

constexpr std::array<CadFormat, 3> kFormats{{
    {CadContent::Step, "STEP", holds_step},
    {CadContent::Iges, "IGES", holds_iges},
    {CadContent::Brep, "BREP", holds_brep},
}};

/// \p kind's entry of kFormats; null for a value outside the enumeration.
const CadFormat* format_of(CadContent kind) {
    for (const CadFormat& f : kFormats)
        if (f.kind == kind) return &f;
    return nullptr;
}

}  // namespace

bool holds_cad_content(std::string_view head, CadContent kind) {
    const CadFormat* format = format_of(kind);
    return format && format->holds(head);
}

void check_cad_content(const std::string& path, CadContent kind) {
    const std::string head = read_input_head(path, kHead);
    if (holds_cad_content(head, kind)) return;
    const CadFormat* format = format_of(kind);
    const std::string name = format ? format->name : "CAD";
    throw InputError("'" + path + "' is not " + (kind == CadContent::Iges ? "an " : "a ") + name + " file: it " +
                     describe_content(head) + "; export the model again as " + name +
                     ", or give the file the extension of its format (.step, .iges, .brep)");
}

}  // namespace strata
