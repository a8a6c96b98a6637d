// Reading a Gmsh .geo script more than once in one process, and refusing one that reaches
// outside Gmsh's model: geo_script.h.

#include <strata/io/geo_script.h>

#include <strata/core/error.h>
#include <strata/io/files.h>

#include <gmsh.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <utility>
#include <vector>

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

/// A token of a .geo script as Gmsh 4.8's lexer (Parser/Gmsh.l) reads it.
struct GeoToken {
    enum Kind { Word, String, Other } kind = Other;
    std::string text;  ///< the word, the string's contents, or the symbol (">>" and ">=" as one)
    int line = 0;
};

/// The tokens of a script's text, one by one: comments (// to the end of the line, /* to */)
/// dropped, a string ("..." or '...', up to the next same quote: Gmsh knows no escapes, and a
/// string may span lines) one token, a number one Other token.
class GeoLexer {
public:
    explicit GeoLexer(const std::string& text) : text_(text) {}

    /// The next token into \p t; false at the end of the text.
    bool next(GeoToken& t) {
        const std::size_t n = text_.size();
        while (i_ < n) {
            const char c = text_[i_];
            const char after = i_ + 1 < n ? text_[i_ + 1] : '\0';
            if (c == '/' && after == '/') {
                skip_to(std::min(text_.find('\n', i_), n));
            } else if (c == '/' && after == '*') {
                const std::size_t end = text_.find("*/", i_ + 2);
                skip_to(end == std::string::npos ? n : end + 2);
            } else if (std::isspace(static_cast<unsigned char>(c)) != 0) {
                skip_to(i_ + 1);
            } else {
                t.line = line_;
                read_token(t);
                return true;
            }
        }
        return false;
    }

private:
    void skip_to(std::size_t end) {
        for (; i_ < end; ++i_) line_ += text_[i_] == '\n' ? 1 : 0;
    }
    bool digit(std::size_t k) const {
        return k < text_.size() && std::isdigit(static_cast<unsigned char>(text_[k])) != 0;
    }
    /// The token at i_ (not a space or a comment).
    void read_token(GeoToken& t) {
        const std::size_t n = text_.size(), start = i_;
        const char c = text_[i_];
        if (c == '"' || c == '\'') {
            const std::size_t end = std::min(text_.find(c, i_ + 1), n);
            t = {GeoToken::String, text_.substr(i_ + 1, end - i_ - 1), line_};
            skip_to(std::min(end + 1, n));
        } else if (ident_char(c) && !digit(i_)) {
            while (i_ < n && ident_char(text_[i_])) ++i_;
            t = {GeoToken::Word, text_.substr(start, i_ - start), line_};
        } else if (digit(i_) || (c == '.' && digit(i_ + 1))) {
            while (digit(i_)) ++i_;
            if (i_ < n && text_[i_] == '.') ++i_;
            while (digit(i_)) ++i_;
            const std::size_t sign = i_ + 1 < n && (text_[i_ + 1] == '+' || text_[i_ + 1] == '-') ? i_ + 2 : i_ + 1;
            if (i_ < n && (text_[i_] == 'e' || text_[i_] == 'E') && digit(sign)) {
                i_ = sign;
                while (digit(i_)) ++i_;
            }
            t = {GeoToken::Other, "0", line_};
        } else {
            const char after = i_ + 1 < n ? text_[i_ + 1] : '\0';
            const std::size_t size = c == '>' && (after == '>' || after == '=') ? 2 : 1;
            t = {GeoToken::Other, text_.substr(i_, size), line_};
            i_ += size;
        }
    }

    const std::string& text_;
    std::size_t i_ = 0;
    int line_ = 1;
};

/// Commands Gmsh 4.8's grammar takes as `NAME StringExpr;` (and `Save View[i] "file";`,
/// `SendToServer View[i] "name";`), by the name it compares, and what they do.
struct GeoCommand {
    const char* name;
    const char* what;
};
constexpr GeoCommand kGeoCommands[] = {
    {"SystemCall", "runs a shell command"},
    {"System", "runs a shell command"},
    {"NonBlockingSystemCall", "runs a shell command in the background"},
    {"CreateDir", "creates a directory"},
    {"Save", "writes a file (the mesh, or a view)"},
    {"Print", "writes a file (an image, or the model in the format its name gives)"},
    {"SendToServer", "sends a view to a ONELAB server"},
};

/// Extensions Gmsh 4.8.4's Merge reads with a reader of their own, spelled as it compares them
/// (a script saved under such a name goes to that reader and is not run; ".Step", ".BREP" or
/// ".PRO" is parsed as a script); .py, .pro, .m and .exe it takes for a ONELAB client or
/// solver, which only OnelabRun (refused) would start.
const std::set<std::string>& own_reader_extensions() {
    static const std::set<std::string> extensions = {
        ".stl",  ".STL",  ".step", ".STEP", ".stp",  ".STP",  ".iges", ".IGES", ".igs",  ".IGS",  ".brep",
        ".brp",  ".BRP",  ".unv",  ".UNV",  ".vtk",  ".VTK",  ".med",  ".MED",  ".mmed", ".MMED", ".rmed",
        ".RMED", ".bdf",  ".BDF",  ".nas",  ".NAS",  ".p3d",  ".P3D",  ".mesh", ".MESH", ".ply",  ".PLY",
        ".ply2", ".PLY2", ".wrl",  ".WRL",  ".vrml", ".VRML", ".diff", ".DIFF", ".dat",  ".DAT",  ".jpg",
        ".JPG",  ".png",  ".PNG",  ".pro",  ".py",   ".PY",   ".m",    ".M",    ".exe",  ".EXE"};
    return extensions;
}

/// geo_script_hazards of \p file (read by \p read_from), appended to \p out; \p seen: the files
/// scanned so far.
void collect_hazards(const std::filesystem::path& file, const std::string& read_from, std::set<std::string>& seen,
                     std::vector<GeoHazard>& out) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path canonical = fs::weakly_canonical(file, ec);
    if (!seen.insert(ec ? file.string() : canonical.string()).second) return;
    if (!fs::is_regular_file(file, ec)) return;  // Gmsh cannot read it either
    const GeoScan scan = scan_geo_text(read_whole_file(file.string()));
    for (GeoHazard h : scan.hazards) {
        h.file = file.string();
        h.read_from = read_from;
        out.push_back(std::move(h));
    }
    for (const GeoRead& r : scan.reads) {
        // Gmsh's FixRelativePath: relative to the directory of the script that reads it.
        const fs::path target = fs::path(r.path).is_absolute() ? fs::path(r.path) : file.parent_path() / r.path;
        if (r.command == "Include" || merged_as_script(target.string()))
            collect_hazards(target, file.string() + ", line " + std::to_string(r.line), seen, out);
    }
}

}  // namespace

GeoScan scan_geo_text(const std::string& text) {
    // The text is read once, through a window of the token judged and the few after it (a
    // generated script of millions of points would not fit as a list of tokens).
    constexpr std::size_t kWindow = 6;
    GeoLexer lexer(text);
    std::deque<GeoToken> t;  // t[0]: the token judged
    auto fill = [&] {
        GeoToken next;
        while (t.size() < kWindow && lexer.next(next)) t.push_back(std::move(next));
    };
    auto is = [&](std::size_t k, const char* symbol) {
        return k < t.size() && t[k].kind == GeoToken::Other && t[k].text == symbol;
    };
    GeoScan scan;
    auto found = [&](int line, std::string command, std::string what) {
        scan.hazards.push_back({"", line, std::move(command), std::move(what), ""});
    };
    bool after_dot = false;                        // the token before t[0] is '.'
    int depth = 0;                                 // of parentheses
    std::vector<std::pair<int, int>> printf_open;  // each Printf in them: the depth outside its parentheses, its line
    for (fill(); !t.empty(); after_dot = is(0, "."), t.pop_front(), fill()) {
        if (is(0, "(")) ++depth;
        if (is(0, ")") && --depth >= 0 && !printf_open.empty() && depth == printf_open.back().first) {
            if (is(1, ">") || is(1, ">>"))
                found(printf_open.back().second, "Printf(...) " + t[1].text, "writes a file");
            printf_open.pop_back();
        }
        if (t[0].kind != GeoToken::Word) continue;
        const std::string& word = t[0].text;
        // A command's name starts a statement and a string expression follows it (a string, a
        // name, a function of strings): not an option (Print.Width = 800) nor a variable (Save = 1).
        const bool command = !after_dot && t.size() > 1 && (t[1].kind != GeoToken::Other || t[1].text == "(");
        if (word == "OnelabRun") {  // reserved words: whatever follows, the statement is theirs
            found(t[0].line, word, "runs a program (a ONELAB client)");
        } else if (word == "Exit") {
            found(t[0].line, word, "ends the process reading the script (Strata would stop at once, without a word)");
        } else if (word == "Printf" && is(1, "(")) {
            printf_open.emplace_back(depth, t[0].line);
        } else if (word == "Plugin" && is(1, "(") && t.size() > 5 && t[2].kind == GeoToken::Word && is(3, ")") &&
                   is(4, ".") && t[5].kind == GeoToken::Word && t[5].text == "Run") {
            found(t[0].line, "Plugin(" + t[2].text + ").Run",
                  "runs a Gmsh plugin, and plugins write files (Bubbles, HomologyComputation, ...)");
        } else if (command && (word == "Include" || word == "Merge" || word == "MergeWithBoundingBox")) {
            if (t[1].kind == GeoToken::String && is(2, ";"))
                scan.reads.push_back({t[0].line, word, t[1].text});
            else
                found(t[0].line, word,
                      "reads a file named by a string expression, which Strata cannot check before Gmsh runs it");
        } else if (command) {
            for (const GeoCommand& c : kGeoCommands)
                if (word == c.name) found(t[0].line, word, c.what);
        }
    }
    return scan;
}

bool merged_as_script(const std::string& path) {
    if (own_reader_extensions().count(std::filesystem::path(path).extension().string())) return false;
    // Gmsh reads the first line of any other file: a mesh or a view by its header, else a script.
    std::ifstream in(path, std::ios::binary);
    std::string first;
    std::getline(in, first);
    for (const char* header : {"$MeshFormat", "$Comments", "$PostFormat", "$View"})
        if (first.rfind(header, 0) == 0) return false;
    return true;
}

std::vector<GeoHazard> geo_script_hazards(const std::string& path) {
    std::vector<GeoHazard> out;
    std::set<std::string> seen;
    collect_hazards(path, "", seen, out);
    return out;
}

void check_geo_script(const std::string& path) {
    const std::vector<GeoHazard> found = geo_script_hazards(path);
    if (found.empty()) return;
    const GeoHazard& h = found.front();
    std::string message = h.file + ", line " + std::to_string(h.line) + ": `" + h.command + "` " + h.what;
    if (!h.read_from.empty()) message += " (a script read by " + h.read_from + ")";
    if (found.size() > 1) {
        constexpr std::size_t kListed = 4;
        message +=
            " (and " + std::to_string(found.size() - 1) + " more such statement" + (found.size() > 2 ? "s" : "") + ":";
        for (std::size_t i = 1; i < found.size() && i <= kListed; ++i)
            message += std::string(i > 1 ? "," : "") + (found[i].file == h.file ? "" : " " + found[i].file) + " line " +
                       std::to_string(found[i].line) + " `" + found[i].command + "`";
        message += found.size() > kListed + 1 ? ", ...)" : ")";
    }
    throw InputError(message +
                     "; a .geo file is a program: if you trust its author, give CadParams::trust_geo = true to "
                     "run it");
}

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

void merge_geo_script(const std::string& path, bool trusted) {
    if (!trusted) check_geo_script(path);
    const std::string text = read_whole_file(path);
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
