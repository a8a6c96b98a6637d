// The length unit a STEP or IGES file declares: cad_units.h.

#include <strata/core/error.h>
#include <strata/io/cad_units.h>
#include <strata/io/files.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

namespace strata {
namespace {

struct Known {
    const char* name;
    double millimetres;
    std::array<const char*, 6> spellings;  ///< lower case; unused ones empty
};

constexpr std::array<Known, 10> kUnits{{
    {"mm", 1.0, {"mm", "millimetre", "millimeter", "millimetres", "millimeters", "milli"}},
    {"cm", 10.0, {"cm", "centimetre", "centimeter", "centimetres", "centimeters", "centi"}},
    {"m", 1000.0, {"m", "metre", "meter", "metres", "meters", ""}},
    {"km", 1e6, {"km", "kilometre", "kilometer", "kilometres", "kilometers", "kilo"}},
    {"in", 25.4, {"in", "inch", "inches", "", "", ""}},
    {"ft", 304.8, {"ft", "foot", "feet", "", "", ""}},
    {"mi", 1609344.0, {"mi", "mile", "miles", "", "", ""}},
    {"mil", 0.0254, {"mil", "mils", "thou", "", "", ""}},
    {"um", 1e-3, {"um", "micron", "microns", "micrometre", "micrometer", "micro"}},
    {"uin", 25.4e-6, {"uin", "microinch", "microinches", "", "", ""}},
}};

std::string lower(std::string_view s) {
    std::string out(s);
    std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
    return out;
}

std::string read_all(const std::string& path) {
    check_input_file(path);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("'" + path + "': cannot be opened for reading; check its permissions");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

bool word_char(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

/// STEP: the record (up to its ';') of the first complex or simple entity that is a
/// LENGTH_UNIT; its SI_UNIT (prefix, METRE) or CONVERSION_BASED_UNIT('NAME', ...).
std::optional<LengthUnit> step_unit(const std::string& text) {
    for (std::size_t at = text.find("LENGTH_UNIT"); at != std::string::npos; at = text.find("LENGTH_UNIT", at + 1)) {
        const std::size_t end_word = at + 11;
        if ((at > 0 && word_char(text[at - 1])) || (end_word < text.size() && word_char(text[end_word]))) continue;
        // The record: from the end of the one before (a '#' may be a reference inside it).
        const std::size_t previous = text.rfind(';', at), end = text.find(';', at);
        const std::size_t begin = previous == std::string::npos ? 0 : previous + 1;
        if (end == std::string::npos) continue;
        std::string record;
        std::copy_if(text.begin() + static_cast<std::ptrdiff_t>(begin), text.begin() + static_cast<std::ptrdiff_t>(end),
                     std::back_inserter(record), [](char c) { return !std::isspace(static_cast<unsigned char>(c)); });
        if (const std::size_t c = record.find("CONVERSION_BASED_UNIT('"); c != std::string::npos) {
            const std::size_t from = c + 23, to = record.find('\'', from);
            if (to != std::string::npos)
                if (auto u = parse_length_unit(record.substr(from, to - from))) return u;
            continue;
        }
        if (const std::size_t s = record.find("SI_UNIT("); s != std::string::npos) {
            const std::size_t close = record.find(')', s);
            const std::string args = record.substr(s + 8, close == std::string::npos ? 0 : close - s - 8);
            const std::size_t comma = args.find(',');
            if (comma == std::string::npos || args.substr(comma + 1) != ".METRE.") continue;
            const std::string prefix = args.substr(0, comma);
            if (prefix == "$") return parse_length_unit("m");
            if (prefix.size() > 2 && prefix.front() == '.' && prefix.back() == '.')
                if (auto u = parse_length_unit(prefix.substr(1, prefix.size() - 2))) return u;
        }
    }
    return std::nullopt;
}

/// IGES: the global section's parameters (columns 1-72 of the 'G' lines), split by its own
/// delimiters (parameters 1 and 2, ',' and ';' by default), Hollerith strings (nH...) read
/// whole.
std::vector<std::string> iges_global(const std::string& text) {
    std::string g;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.size() >= 73 && line[72] == 'G') g += line.substr(0, 72);
    }
    std::vector<std::string> out;
    char delim = ',', record = ';';
    std::size_t i = 0;
    while (i < g.size()) {
        while (i < g.size() && g[i] == ' ') ++i;
        std::string value;
        std::size_t j = i;
        while (j < g.size() && std::isdigit(static_cast<unsigned char>(g[j]))) ++j;
        if (j > i && j < g.size() && (g[j] == 'H' || g[j] == 'h')) {  // Hollerith: n characters after the H
            const std::size_t n = std::stoul(g.substr(i, j - i));
            value = g.substr(j + 1, n);
            i = j + 1 + n;
            while (i < g.size() && g[i] == ' ') ++i;
        } else {
            while (i < g.size() && g[i] != delim && g[i] != record) value += g[i++];
            while (!value.empty() && value.back() == ' ') value.pop_back();
        }
        out.push_back(value);
        if (out.size() == 1 && value.size() == 1) delim = value[0];
        if (out.size() == 2 && value.size() == 1) record = value[0];
        if (i >= g.size() || g[i] == record) break;
        ++i;  // the delimiter
    }
    return out;
}

std::optional<LengthUnit> iges_unit(const std::string& text) {
    const std::vector<std::string> g = iges_global(text);
    if (g.size() < 14) return std::nullopt;
    static constexpr std::array<const char*, 12> kFlag{"",  "in", "mm",  "",   "ft", "mi",
                                                       "m", "km", "mil", "um", "cm", "uin"};
    int flag = 0;
    try {
        flag = std::stoi(g[13]);
    } catch (const std::exception&) {
        return std::nullopt;
    }
    if (flag == 3) return g.size() >= 15 ? parse_length_unit(g[14]) : std::nullopt;
    if (flag < 1 || flag > 11) return std::nullopt;
    return parse_length_unit(kFlag[static_cast<std::size_t>(flag)]);
}

}  // namespace

std::optional<LengthUnit> parse_length_unit(std::string_view name) {
    const std::string n = lower(name);
    if (n.empty()) return std::nullopt;
    for (const Known& k : kUnits)
        for (const char* s : k.spellings)
            if (*s != '\0' && n == s) return LengthUnit{k.name, k.millimetres};
    if (n == "\xc2\xb5m") return LengthUnit{"um", 1e-3};  // µm
    return std::nullopt;
}

std::string_view length_unit_names() {
    return "mm, cm, m, km, in, ft, mi, mil, um, uin";
}

std::optional<LengthUnit> declared_length_unit(const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".step" || ext == ".stp") return step_unit(read_all(path));
    if (ext == ".iges" || ext == ".igs") return iges_unit(read_all(path));
    return std::nullopt;
}

}  // namespace strata
