#include <strata/core/error.h>
#include <strata/io/input_file.h>
#include <strata/io/msh_counts.h>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <array>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

namespace strata {
namespace {

/// A file mapped read-only (nothing copied, however large the mesh); empty if it cannot be.
class MappedFile {
public:
    explicit MappedFile(const std::string& path) {
        const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0) return;
        struct stat st {};
        if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
            void* p = ::mmap(nullptr, static_cast<std::size_t>(st.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
            if (p != MAP_FAILED) {
                data_ = static_cast<const char*>(p);
                size_ = static_cast<std::size_t>(st.st_size);
            }
        }
        ::close(fd);
    }
    ~MappedFile() {
        if (data_) ::munmap(const_cast<char*>(data_), size_);
    }
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;

    std::string_view view() const { return {data_, size_}; }

private:
    const char* data_ = nullptr;
    std::size_t size_ = 0;
};

/// What the `$MeshFormat` section says about the encoding.
struct MshFormat {
    bool v4 = false;            // 4.1 (else 2.x)
    bool binary = false;        // file-type 1
    bool swapped = false;       // binary, written on a machine of the other endianness
    std::size_t data_size = 8;  // bytes of a size_t (4.1 binary counts and tags)
};

bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

/// The next white-space separated token of \p s (consumed).
std::string_view token(std::string_view& s) {
    std::size_t i = 0;
    while (i < s.size() && is_space(s[i])) ++i;
    std::size_t j = i;
    while (j < s.size() && !is_space(s[j])) ++j;
    const std::string_view t = s.substr(i, j - i);
    s.remove_prefix(j);
    return t;
}

std::optional<std::uint64_t> count(std::string_view t) {
    std::uint64_t v = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || ec != std::errc() || end != t.data() + t.size()) return std::nullopt;
    return v;
}

/// The rest of \p s after its current line.
std::string_view next_line(std::string_view s) {
    const std::size_t nl = s.find('\n');
    return nl == std::string_view::npos ? std::string_view{} : s.substr(nl + 1);
}

/// The format of a file whose `$MeshFormat` line \p s starts at; none for a version other than
/// 4.1 and 2.x, or a header that does not parse (Gmsh then says what is wrong).
std::optional<MshFormat> read_format(std::string_view s) {
    s = next_line(s);
    const std::string_view version = token(s);
    const std::optional<std::uint64_t> type = count(token(s)), size = count(token(s));
    if (!type || !size || *type > 1 || (*size != 4 && *size != 8)) return std::nullopt;
    MshFormat f;
    if (version == "4.1")
        f.v4 = true;
    else if (version.substr(0, 2) != "2.")
        return std::nullopt;
    f.binary = *type == 1;
    f.data_size = static_cast<std::size_t>(*size);
    if (f.binary) {  // the int 1, in the writer's byte order, on the line after
        s = next_line(s);
        if (s.size() < 4) return std::nullopt;
        std::uint32_t one = 0;
        std::memcpy(&one, s.data(), 4);
        if (one != 1 && one != 0x01000000u) return std::nullopt;
        f.swapped = one != 1;
    }
    return f;
}

/// The text just after the line "<name>" (a section's first line), or none.
std::optional<std::string_view> section(std::string_view text, std::string_view name) {
    for (std::size_t at = text.find(name); at != std::string_view::npos; at = text.find(name, at + 1)) {
        if (at > 0 && text[at - 1] != '\n') continue;
        std::string_view rest = text.substr(at + name.size());
        if (!rest.empty() && rest.front() == '\r') rest.remove_prefix(1);
        if (rest.empty() || rest.front() != '\n') continue;  // "$NodesX", "$ElementsData"
        return rest.substr(1);
    }
    return std::nullopt;
}

/// The unsigned integer of \p f's data size at \p p, in the machine's byte order.
std::uint64_t load_unsigned(const char* p, const MshFormat& f) {
    if (f.data_size == 8) {
        std::uint64_t v = 0;
        std::memcpy(&v, p, sizeof v);
        return f.swapped ? __builtin_bswap64(v) : v;
    }
    std::uint32_t w = 0;
    std::memcpy(&w, p, sizeof w);
    return f.swapped ? __builtin_bswap32(w) : w;
}

/// The values of a section header: 4.1's numEntityBlocks, numNodes|numElements, minTag, maxTag
/// (text, or binary of the data size), 2.x's one count as the second; none if they do not parse.
std::optional<std::array<std::uint64_t, 4>> header_values(std::string_view s, const MshFormat& f) {
    std::array<std::uint64_t, 4> v{};
    if (!f.v4) {
        const std::optional<std::uint64_t> n = count(token(s));
        if (!n) return std::nullopt;
        v[1] = *n;
        return v;
    }
    for (std::uint64_t& x : v) {
        if (!f.binary) {
            const std::optional<std::uint64_t> n = count(token(s));
            if (!n) return std::nullopt;
            x = *n;
            continue;
        }
        if (s.size() < f.data_size) return std::nullopt;
        x = load_unsigned(s.data(), f);
        s.remove_prefix(f.data_size);
    }
    return v;
}

/// InputError if \p what (a section header at \p header) claims more items than \p file_size
/// bytes hold at \p min_bytes each.
void check_claim(const std::string& path, std::optional<std::string_view> header, const MshFormat& f, const char* what,
                 std::uint64_t min_bytes, std::size_t file_size) {
    if (!header) return;
    const std::optional<std::array<std::uint64_t, 4>> values = header_values(*header, f);
    if (!values) return;
    const std::uint64_t n = (*values)[1];
    if (n > file_size / min_bytes)
        throw InputError("'" + path + "' claims " + std::to_string(n) + " " + what + "s but the file has only " +
                         std::to_string(file_size) + " bytes (" + (f.binary ? "a binary" : "an ASCII") + " MSH " +
                         (f.v4 ? "4.1 " : "2 ") + what + " takes at least " + std::to_string(min_bytes) +
                         "): it is truncated or damaged; write it again");
    // Gmsh 4.8's MSH 4.1 reader looks the elements' nodes up by an int: a larger tag crashed it.
    if (f.v4 && std::string_view(what) == "node" && (*values)[3] > std::numeric_limits<int>::max())
        throw InputError("'" + path + "': its node tags reach " + std::to_string((*values)[3]) + ", beyond the " +
                         std::to_string(std::numeric_limits<int>::max()) +
                         " Gmsh reads; number the nodes from 1 again (Gmsh: Mesh.Renumber) and write it again");
}

}  // namespace

void check_msh_counts(const std::string& path) {
    const MappedFile file(path);
    const std::string_view text = file.view();
    if (text.empty() && !read_input_head(path, 1).empty()) return;  // not mapped: Gmsh alone reads it
    std::string_view start = text;
    if (start.substr(0, 3) == "\xEF\xBB\xBF") start.remove_prefix(3);
    while (!start.empty() && is_space(start.front())) start.remove_prefix(1);
    if (start.empty() || start.front() != '$') {
        throw InputError("'" + path + "' is not an MSH file: it " + describe_content(text.substr(0, 4096)) +
                         "; write the mesh again as MSH 4.1 or 2.2, or give the file the extension of its format");
    }
    if (start.substr(0, 11) != "$MeshFormat") return;
    const std::optional<MshFormat> format = read_format(start);
    if (!format) return;
    const MshFormat& f = *format;
    const std::optional<std::string_view> nodes = section(start, "$Nodes");
    const std::uint64_t per_node = !f.binary ? 8 : f.v4 ? 24 + f.data_size : 28;
    check_claim(path, nodes, f, "node", per_node, text.size());
    const std::optional<std::string_view> elements = section(nodes ? *nodes : start, "$Elements");
    const std::uint64_t per_element = !f.binary ? (f.v4 ? 4 : 8) : f.v4 ? 2 * f.data_size : 8;
    check_claim(path, elements, f, "element", per_element, text.size());
}

}  // namespace strata
