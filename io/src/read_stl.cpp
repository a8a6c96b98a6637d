// STL reader, ASCII and binary. The whole file is read into memory once and parsed in
// place (std::from_chars, no streams): a million ASCII facets (~200 MB) take about a second,
// most of it reading and scanning the text; binary is a straight copy.

#include <strata/core/error.h>
#include <strata/io/input_file.h>
#include <strata/io/read_surface.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <new>
#include <string>
#include <string_view>

namespace strata {
namespace {

constexpr std::size_t kBinaryHeader = 84;  // 80-byte comment + uint32 facet count
constexpr std::size_t kBinaryFacet = 50;   // normal + 3 vertices (12 float32) + uint16 attribute

/// Index overflow guard: STL stores 3 unmerged nodes per facet, so 32-bit indices end at
/// ~715 M facets.
void check_capacity(const std::string& path, std::size_t facets) {
    if (facets * 3 > static_cast<std::size_t>(std::numeric_limits<Index>::max()))
        throw InputError("'" + path + "': " + std::to_string(facets) +
                         " facets exceed the 32-bit node index range; rebuild Strata with "
                         "-DSTRATA_INDEX64=ON");
}

void add_facet(SurfaceMesh& mesh, const Vec3 (&v)[3], Index patch) {
    const Index first = mesh.num_points();
    for (const Vec3& p : v) mesh.points.push_back(p);
    const Index nodes[3] = {first, first + 1, first + 2};
    mesh.add_face(nodes, 3, patch);
}

// ---------------------------------------------------------------------------------------
// Binary

std::uint32_t load_u32le(const char* p) {
    std::uint32_t v;
    std::memcpy(&v, p, 4);
    if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap32(v);
    return v;
}

float load_f32le(const char* p) {
    std::uint32_t bits = load_u32le(p);
    return std::bit_cast<float>(bits);
}

SurfaceMesh parse_binary(const std::string& path, std::string_view data) {
    const std::size_t n = load_u32le(data.data() + 80);
    if (n == 0) throw InputError("'" + path + "': binary STL holds no facets");
    check_capacity(path, n);
    SurfaceMesh mesh;
    mesh.patches.push_back({patch_word(std::filesystem::path(path).stem().string(), 0), PatchKind::Wall});
    mesh.points.reserve(3 * n);
    mesh.face_nodes.reserve(3 * n);
    mesh.face_offsets.reserve(n + 1);
    mesh.face_patch.reserve(n);
    const char* p = data.data() + kBinaryHeader;
    for (std::size_t f = 0; f < n; ++f, p += kBinaryFacet) {
        Vec3 v[3];
        for (int k = 0; k < 3; ++k) {
            // Skip the stored normal (first 12 bytes): orientation comes from the node order.
            const char* q = p + 12 + 12 * k;
            v[k] = Vec3(load_f32le(q), load_f32le(q + 4), load_f32le(q + 8));
            if (!v[k].allFinite())
                throw InputError("'" + path + "': facet " + std::to_string(f + 1) + " (of " + std::to_string(n) +
                                 "): vertex " + std::to_string(k + 1) +
                                 " has a non-finite coordinate; the file is corrupt");
        }
        add_facet(mesh, v, 0);
    }
    return mesh;
}

// ---------------------------------------------------------------------------------------
// ASCII

bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

/// Token separator for the hot loops: whitespace and any other control character, one compare.
bool is_separator(char c) {
    return static_cast<unsigned char>(c) <= ' ';
}

bool iequals(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        char x = a[i], y = b[i];
        if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
        if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
        if (x != y) return false;
    }
    return true;
}

std::string_view trim(std::string_view s) {
    while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
    while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
    return s;
}

/// Whitespace-separated tokens over the buffer, with the line number of the last token for
/// error messages.
class AsciiParser {
public:
    AsciiParser(const std::string& path, std::string_view text) : path_(path), text_(text) {}

    /// Next token, or an empty view at the end of the file.
    std::string_view next() {
        skip_space();
        const std::size_t start = pos_;
        while (pos_ < text_.size() && !is_separator(text_[pos_])) ++pos_;
        token_start_ = start;
        token_line_ = line_;
        return text_.substr(start, pos_ - start);
    }

    /// Rest of the current line (after the last token), trimmed; consumes it.
    std::string_view rest_of_line() {
        const std::size_t start = pos_;
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        return trim(text_.substr(start, pos_ - start));
    }

    void expect(std::string_view keyword, std::string_view what) {
        std::string_view t = next();
        if (!iequals(t, keyword)) fail_found(what);
    }

    double number(std::string_view what) {
        std::string_view t = next();
        std::string_view digits = t;
        if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);  // from_chars rejects '+'
        double v = 0.0;
        auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
        if (t.empty() || ec != std::errc() || end != digits.data() + digits.size()) fail_found(what);
        if (!std::isfinite(v)) fail("non-finite coordinate '" + std::string(t) + "'; the file is corrupt");
        return v;
    }

    bool at_end() {
        skip_space();
        return pos_ >= text_.size();
    }

    /// "file: line N: expected WHAT, found '...'" about the last token read.
    [[noreturn]] void fail_found(std::string_view what) const {
        if (token_start_ >= text_.size())
            fail_at(line_, "expected " + std::string(what) + ", found the end of the file (truncated?)");
        std::size_t e = token_start_;
        while (e < text_.size() && text_[e] != '\n') ++e;
        std::string_view found = trim(text_.substr(token_start_, e - token_start_));
        std::string shown(found.substr(0, 40));
        if (found.size() > 40) shown += "...";
        fail_at(token_line_, "expected " + std::string(what) + ", found '" + shown + "'");
    }

    [[noreturn]] void fail(const std::string& message) const { fail_at(token_line_, message); }

private:
    [[noreturn]] void fail_at(std::size_t line, const std::string& message) const {
        throw InputError("'" + path_ + "': line " + std::to_string(line) + ": " + message);
    }

    void skip_space() {
        while (pos_ < text_.size() && is_separator(text_[pos_])) {
            if (text_[pos_] == '\n') ++line_;
            ++pos_;
        }
    }

    const std::string& path_;
    std::string_view text_;
    std::size_t pos_ = 0;
    std::size_t line_ = 1;
    std::size_t token_start_ = 0;
    std::size_t token_line_ = 1;
};

SurfaceMesh parse_ascii(const std::string& path, std::string_view text) {
    SurfaceMesh mesh;
    // A facet takes 150-250 bytes of text; reserving from the size avoids most regrowth of
    // large arrays without a counting pass over the text.
    const std::size_t estimate = text.size() / 256 + 1;
    mesh.points.reserve(3 * estimate);
    mesh.face_nodes.reserve(3 * estimate);
    mesh.face_offsets.reserve(estimate + 1);
    mesh.face_patch.reserve(estimate);
    AsciiParser in(path, text);
    std::size_t facets = 0;
    while (!in.at_end()) {
        in.expect("solid", "'solid NAME'");
        std::string name(in.rest_of_line());
        const Index patch = static_cast<Index>(mesh.patches.size());
        // A solid's name as every format writes it ("Wing Body.001 (left)" is Wing_Body.001_left).
        mesh.patches.push_back({name.empty() ? std::string("wall") : patch_word(name, mesh.patches.size()),
                                PatchKind::Wall});
        for (;;) {
            std::string_view t = in.next();
            if (iequals(t, "endsolid")) {
                in.rest_of_line();  // the repeated name, if any
                break;
            }
            if (!iequals(t, "facet")) in.fail_found("'facet normal nx ny nz' or 'endsolid'");
            in.expect("normal", "'facet normal nx ny nz'");
            for (int k = 0; k < 3; ++k) in.number("'facet normal nx ny nz'");
            in.expect("outer", "'outer loop'");
            in.expect("loop", "'outer loop'");
            Vec3 v[3];
            for (Vec3& p : v) {
                in.expect("vertex", "'vertex x y z'");
                for (int k = 0; k < 3; ++k) p[k] = in.number("'vertex x y z'");
            }
            in.expect("endloop", "'endloop' (only triangular facets are supported)");
            in.expect("endfacet", "'endfacet'");
            check_capacity(path, ++facets);
            add_facet(mesh, v, patch);
        }
    }
    if (facets == 0) throw InputError("'" + path + "': ASCII STL holds no facets");
    return mesh;
}

/// A binary STL may start with "solid" too, so the size decides first (read_stl). A file that
/// starts with "solid" but has the wrong size for binary is ASCII unless its first 512 bytes
/// hold control characters: a truncated binary file with a "solid" header has them in its
/// facet count and floats, and is then reported as truncated rather than as bad text.
bool looks_ascii(std::string_view data) {
    std::string_view t = data;
    if (t.substr(0, 3) == "\xEF\xBB\xBF") t.remove_prefix(3);  // UTF-8 byte-order mark
    t = trim(t.substr(0, 512));
    if (t.size() < 5 || !iequals(t.substr(0, 5), "solid")) return false;
    for (char c : data.substr(0, 512)) {
        unsigned char u = static_cast<unsigned char>(c);
        if (u < 0x20 && !is_space(c)) return false;
    }
    return true;
}

/// The STL in \p data (read_stl_bytes without its memory guard).
SurfaceMesh parse_stl(std::string_view data, const std::string& source) {
    if (data.size() >= kBinaryHeader) {
        const std::size_t n = load_u32le(data.data() + 80);
        if (data.size() == kBinaryHeader + kBinaryFacet * n) return parse_binary(source, data);
    }
    if (looks_ascii(data)) {
        std::string_view text = data;
        if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
        return parse_ascii(source, text);
    }
    if (data.size() < kBinaryHeader)
        throw InputError("'" + source + "': not an STL file: " + std::to_string(data.size()) +
                         " bytes, too short for binary STL (84-byte header) and it does not "
                         "begin with 'solid'");
    const std::size_t n = load_u32le(data.data() + 80);
    const std::size_t whole = (data.size() - kBinaryHeader) / kBinaryFacet;
    throw InputError("'" + source + "': binary STL header announces " + std::to_string(n) + " facets, so 84+50*" +
                     std::to_string(n) + " = " + std::to_string(kBinaryHeader + kBinaryFacet * n) +
                     " bytes expected, but the file has " + std::to_string(data.size()) + " (" + std::to_string(whole) +
                     " whole facets); the file is truncated or not an STL file");
}

}  // namespace

SurfaceMesh read_stl(const std::string& path) {
    // read_input: a pipe is read to its end, a device refused (its size means nothing).
    return read_stl_bytes(read_input(path), path);
}

SurfaceMesh read_stl_bytes(std::string_view data, const std::string& source) {
    try {
        return parse_stl(data, source);
    } catch (const std::bad_alloc&) {
        throw out_of_memory(source);
    }
}

}  // namespace strata
