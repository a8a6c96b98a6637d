// Reading a Gmsh .geo script more than once in one process: geo_script.h.

#include <strata/io/geo_script.h>

#include <gmsh.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>

#include <unistd.h>

namespace strata {
namespace {

bool ident_char(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

/// Calls \p f(name_begin, name_end, quoted) for each name after the keyword \p keyword standing
/// as a word of its own (not part of a longer identifier), the name bare or in double quotes.
template <class F>
void for_each_named(const std::string& text, const std::string& keyword, F f) {
    for (std::size_t at = text.find(keyword); at != std::string::npos; at = text.find(keyword, at + 1)) {
        if (at > 0 && ident_char(text[at - 1])) continue;
        std::size_t p = at + keyword.size();
        if (p >= text.size() || !std::isspace(static_cast<unsigned char>(text[p]))) continue;
        while (p < text.size() && std::isspace(static_cast<unsigned char>(text[p]))) ++p;
        const bool quoted = p < text.size() && text[p] == '"';
        const std::size_t b = quoted ? p + 1 : p;
        std::size_t e = b;
        while (e < text.size() && ident_char(text[e])) ++e;
        if (e == b || (quoted && (e >= text.size() || text[e] != '"'))) continue;
        f(b, e);
    }
}

std::mutex& defined_mutex() {
    static std::mutex m;
    return m;
}
/// The Macro names this process's Gmsh holds from the scripts Strata merged.
std::set<std::string>& defined_names() {
    static std::set<std::string> names;
    return names;
}

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

std::vector<std::string> geo_macro_names(const std::string& text) {
    std::vector<std::string> out;
    for (const char* keyword : {"Macro", "Function"})
        for_each_named(text, keyword, [&](std::size_t b, std::size_t e) { out.push_back(text.substr(b, e - b)); });
    return out;
}

std::string rename_geo_macros(const std::string& text, const std::string& suffix) {
    const std::vector<std::string> names = geo_macro_names(text);
    const std::set<std::string> own(names.begin(), names.end());
    std::vector<std::size_t> ends;  // where to insert the suffix
    for (const char* keyword : {"Macro", "Function", "Call"})
        for_each_named(text, keyword, [&](std::size_t b, std::size_t e) {
            if (own.count(text.substr(b, e - b))) ends.push_back(e);
        });
    std::sort(ends.begin(), ends.end());
    std::string out;
    out.reserve(text.size() + ends.size() * suffix.size());
    std::size_t from = 0;
    for (const std::size_t e : ends) {
        out.append(text, from, e - from);
        out += suffix;
        from = e;
    }
    out.append(text, from, std::string::npos);
    return out;
}

void merge_geo_script(const std::string& path) {
    const std::string text = read_text(path);
    const std::vector<std::string> names = geo_macro_names(text);
    std::lock_guard<std::mutex> lock(defined_mutex());
    std::set<std::string>& defined = defined_names();
    bool again = false;
    for (const std::string& n : names) again |= defined.count(n) > 0;
    if (!again) {
        gmsh::merge(path);
        defined.insert(names.begin(), names.end());
        return;
    }
    static std::atomic<int> reads{0};
    const std::string suffix = "_strata" + std::to_string(::getpid()) + "_" + std::to_string(++reads);
    namespace fs = std::filesystem;
    const fs::path original(path);
    std::string name(1, '.');  // hidden
    name += original.stem().string();
    name += suffix;
    name += ".geo";
    const fs::path copy = original.parent_path() / name;
    {
        std::ofstream out(copy, std::ios::binary);
        if (!(out << rename_geo_macros(text, suffix)) || !out.flush()) {
            out.close();
            std::error_code ignored;
            fs::remove(copy, ignored);
            gmsh::merge(path);  // cannot write beside it: Gmsh says which Macro it redefines
            return;
        }
    }
    struct Remove {
        fs::path p;
        ~Remove() {
            std::error_code ignored;
            fs::remove(p, ignored);
        }
    } remove{copy};
    gmsh::merge(copy.string());
    for (const std::string& n : names) defined.insert(n + suffix);
}

}  // namespace strata
