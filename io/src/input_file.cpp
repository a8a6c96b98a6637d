#include <strata/core/error.h>
#include <strata/io/cad_content.h>
#include <strata/io/files.h>
#include <strata/io/input_file.h>

#include <sys/stat.h>
#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <new>
#include <string>
#include <utility>

namespace strata {
namespace {

using FilePtr = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

/// "STL", "STEP", ...: the format \p path's extension names, for messages ("input" if none).
std::string format_label(const std::string& path) {
    static constexpr std::array<std::pair<const char*, const char*>, 4> kAliases{
        {{".stp", "STEP"}, {".igs", "IGES"}, {".brp", "BREP"}, {".geo", "Gmsh script"}}};
    const std::string ext = lower_extension(path);
    for (const auto& [alias, name] : kAliases)
        if (ext == alias) return name;
    if (ext.size() < 2) return "input";
    std::string name = ext.substr(1);
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::toupper(c); });
    return name;
}

/// The stat of \p path (links followed), or InputError from check_input_file's own checks
/// when there is none.
struct stat status_of(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        check_input_file(path);  // its reason: no such file, permission...
        throw InputError("cannot open '" + path + "': " + std::strerror(errno));
    }
    return st;
}

FilePtr open_input(const std::string& path) {
    FilePtr f(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!f) throw InputError("cannot open '" + path + "': " + std::strerror(errno));
    return f;
}

/// The rest of \p f appended to \p data, chunk by chunk.
void read_to_end(std::FILE* f, const std::string& path, std::string& data) {
    std::array<char, 1 << 16> buf;
    std::size_t got;
    while ((got = std::fread(buf.data(), 1, buf.size(), f)) > 0) data.append(buf.data(), got);
    if (std::ferror(f)) throw InputError("cannot read '" + path + "': " + std::strerror(errno));
}

bool starts_with(std::string_view s, std::string_view prefix) {
    return s.substr(0, prefix.size()) == prefix;
}

bool istarts_with(std::string_view s, std::string_view prefix) {
    if (s.size() < prefix.size()) return false;
    return std::equal(prefix.begin(), prefix.end(), s.begin(), [](char a, char b) {
        return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
    });
}

/// The common formats a wrong file turns out to be, by the bytes it starts with.
constexpr std::array<std::pair<std::string_view, const char*>, 16> kSignatures{{
    {"\x89PNG\r\n\x1a\n", "a PNG image"},
    {"\xFF\xD8\xFF", "a JPEG image"},
    {"GIF87a", "a GIF image"},
    {"GIF89a", "a GIF image"},
    {"%PDF-", "a PDF document"},
    {"%!PS", "a PostScript document"},
    {"PK\x03\x04", "a ZIP archive (or a file format built on one)"},
    {"PK\x05\x06", "an empty ZIP archive"},
    {"\x1f\x8b", "gzip-compressed data (decompress it first)"},
    {"BZh", "bzip2-compressed data (decompress it first)"},
    {"\xFD\x37\x7A\x58\x5A", "xz-compressed data (decompress it first)"},
    {"7z\xBC\xAF\x27\x1C", "a 7-Zip archive"},
    {"Rar!\x1A\x07", "a RAR archive"},
    {"\x7F\x45LF", "a program (an ELF executable)"},
    {"$MeshFormat", "a Gmsh MSH mesh"},
    {"glTF", "a binary glTF model"},
}};

/// White space and an optional UTF-8 byte-order mark removed from the front.
std::string_view skip_blank(std::string_view s) {
    if (starts_with(s, "\xEF\xBB\xBF")) s.remove_prefix(3);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    return s;
}

/// Some of \p head as hex bytes ("89 50 4e 47 ...").
std::string hex_bytes(std::string_view head) {
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string out;
    for (std::size_t i = 0; i < std::min<std::size_t>(head.size(), 8); ++i) {
        const auto b = static_cast<unsigned char>(head[i]);
        if (i > 0) out += ' ';
        out += kDigits[b >> 4];
        out += kDigits[b & 15];
    }
    if (head.size() > 8) out += " ...";
    return out;
}

}  // namespace

InputSource check_input_source(const std::string& path) {
    const struct stat st = status_of(path);
    const std::string give = "; give the " + format_label(path) + " file itself";
    if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) throw InputError("'" + path + "' is a device, not a file" + give);
    if (S_ISSOCK(st.st_mode)) throw InputError("'" + path + "' is a socket, not a file" + give);
    if (S_ISFIFO(st.st_mode)) return InputSource::Stream;
    check_input_file(path);
    return InputSource::File;
}

void require_regular_input(const std::string& path, std::string_view reader) {
    if (check_input_source(path) == InputSource::Stream)
        throw InputError("'" + path + "' is a pipe, not a file: " + std::string(reader) +
                         " reads it by name; save it to a file and give that");
}

std::string read_input(const std::string& path) {
    const InputSource source = check_input_source(path);
    FilePtr f = open_input(path);
    std::string data;
    try {
        if (source == InputSource::File) {
            // One read of the known size (no regrowth of a 100+ MB buffer); read_to_end takes
            // what a file that grew since holds more.
            struct stat st {};
            if (::fstat(::fileno(f.get()), &st) == 0 && S_ISREG(st.st_mode)) {
                data.resize(static_cast<std::size_t>(st.st_size));
                data.resize(std::fread(data.data(), 1, data.size(), f.get()));
            }
        }
        read_to_end(f.get(), path, data);
    } catch (const std::bad_alloc&) {
        throw out_of_memory(path);
    } catch (const std::length_error&) {
        throw out_of_memory(path);
    }
    return data;
}

std::string read_input_head(const std::string& path, std::size_t n) {
    FilePtr f = open_input(path);
    std::string head(n, '\0');
    head.resize(std::fread(head.data(), 1, n, f.get()));
    if (std::ferror(f.get())) throw InputError("cannot read '" + path + "': " + std::strerror(errno));
    return head;
}

InputError out_of_memory(const std::string& path) {
    return InputError("not enough memory to read '" + path +
                      "' (what it holds, or claims to hold, does not fit in this machine's memory); if the file is "
                      "damaged, write it again; if it is that large, use a machine with more memory");
}

std::string describe_content(std::string_view head) {
    if (head.empty()) return "is empty";
    for (const auto& [signature, name] : kSignatures)
        if (starts_with(head, signature)) return "looks like " + std::string(name);
    const std::string_view text = skip_blank(head);
    if (holds_cad_content(head, CadContent::Step)) return "looks like a STEP file";
    if (holds_cad_content(head, CadContent::Iges)) return "looks like an IGES file";
    if (holds_cad_content(head, CadContent::Brep)) return "looks like an OpenCASCADE BREP file";
    if (istarts_with(text, "<!doctype html") || istarts_with(text, "<html"))
        return "looks like a web page (HTML): a download that saved the page, not the file?";
    if (istarts_with(text, "<?xml")) return "looks like an XML document";
    if (istarts_with(text, "solid")) return "looks like an ASCII STL mesh";
    if (text.empty()) return "holds only white space";
    const std::string_view sample = head.substr(0, 512);
    const bool binary = std::any_of(sample.begin(), sample.end(), [](char c) {
        const auto u = static_cast<unsigned char>(c);
        return (u < 0x20 && !std::isspace(u)) || u == 0x7F;
    });
    if (binary) return "starts with binary data (bytes " + hex_bytes(head) + ")";
    std::string_view line = text.substr(0, text.find_first_of("\r\n"));
    std::string shown(line.substr(0, 40));
    if (line.size() > 40) shown += "...";
    return "starts with the text '" + shown + "'";
}

}  // namespace strata
