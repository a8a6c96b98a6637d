// TetGen 1.5 (Debian's libtet), loaded privately at run time; see tetgen_library.h.
//
// Loading libtet. Debian's libgmsh 4.8 exports its own, different TetGen under the same
// names (tetgenmesh::..., 151 symbols in common with libtet). In one global symbol scope one
// of the two always binds to the other's copy, whatever the link order:
//   -lgmsh -ltet: libtet's internal calls go to Gmsh's copy, SIGSEGV in tetrahedralize
//                 (PLATFORM.md);
//   -ltet -lgmsh: Gmsh's calls go to libtet's copy, SIGSEGV in Gmsh's HXT 3D mesher
//                 (tetgenmesh::makepoint2submap from hxt_boundary_recovery; a unit sphere
//                 with Mesh.MeshSizeMax 0.25 is enough; its Delaunay mesher survives).
// So libtet is not linked at all: it is dlopen()ed with RTLD_LOCAL (its symbols stay out of
// the global scope, Gmsh keeps binding to itself) and RTLD_DEEPBIND (libtet's own references
// resolve inside libtet first, not in libgmsh). Only tetrahedralize() is looked up; tetgenio
// is header-only (inline), so nothing else of libtet is called from here.
//
// TetGen's failures. Debian's libtet 1.5.0 crashes instead of throwing: terminatetetgen(m, code)
// frees the mesh (m->freememory(), leaving its pointers dangling) and throws the int; unwinding
// then destroys that same tetgenmesh (a local of tetrahedralize), whose destructor frees it
// again: SIGSEGV in memorypool::~memorypool (reproduced with a self-intersecting boundary;
// the crash reported in SCIRun issue #1538). libtet calls terminatetetgen
// through its PLT (all 43 call sites; a JUMP_SLOT relocation in a RELRO GOT since libtet is
// linked -z now), so after loading, that one GOT slot is pointed at a replacement which only
// throws: the mesh is freed once, by the destructor, and the int reaches run(). Where no
// slot can be patched (another libtet build or architecture) load() refuses TetGen with a
// BackendError rather than risk that crash. tests/hybrid/test_tetgen_library.cpp checks the
// loader; test_tetgen_fill.cpp a self-intersecting boundary (BackendError) and TetGen with
// Gmsh's Delaunay and HXT meshers in one process, both orders.
// Debian builds libtet with its assert()s on, and one that fails (seen: "ori4 != 0" in
// scoutpoint, on a layer top with needle faces) would abort the process: libtet's
// __assert_fail slots are redirected the same way, to a replacement that throws, and run()
// reports the assertion as a BackendError.
// Left as they are: on a failure TetGen leaks a few KB of its own (arraypools local to
// recoverboundary; valgrind) and may print a line or two to stdout despite Q ("Found two
// segments intersect each other.").
//
// Caveat of RTLD_DEEPBIND: libtet resolves operator new/delete in libstdc++ even if the
// program replaces them (as AddressSanitizer does), while tetgenio's inline destructor uses
// the program's: run sanitizer builds with ASAN_OPTIONS=alloc_dealloc_mismatch=0.

#include "tetgen_library.h"

#include <strata/core/bytes.h>
#include <strata/core/child_process.h>
#include <strata/core/error.h>

#include <dlfcn.h>
#include <elf.h>
#include <link.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <csignal>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <mutex>
#include <new>
#include <sstream>
#include <string>
#include <vector>

namespace strata::tetgen {
namespace {

/// Replaces libtet's terminatetetgen: throw TetGen's exit code, leave the freeing to the
/// tetgenmesh destructor.
[[noreturn]] void throwing_terminatetetgen(tetgenmesh* /*mesh*/, int code) {
    throw code;
}

/// An assert() of TetGen's that failed: its text, for the error message.
struct FailedAssertion {
    std::string text;
};

/// Replaces __assert_fail for libtet (Debian builds it with its assertions on; one that fails
/// would abort the process): throw instead, unwinding TetGen like terminatetetgen does.
[[noreturn]] void throwing_assert_fail(const char* assertion, const char* file, unsigned int line,
                                       const char* /*function*/) {
    std::string where = file != nullptr ? file : "tetgen";
    if (const auto slash = where.rfind('/'); slash != std::string::npos) where.erase(0, slash + 1);
    throw FailedAssertion{where + ":" + std::to_string(line) + ": " + (assertion != nullptr ? assertion : "")};
}

// TetGen's trace. libtet prints through __printf_chk, puts and putchar (its verbose levels V,
// VV, VVV; with Q nothing but a stray line on some failures). Those slots are redirected too:
// outside a capture the text goes to stdout as before; during one (locate_failure) nothing is
// printed, and each line naming a boundary face or segment it is recovering updates where it
// is (Located, in memory the parent process shares, so that it survives the child's crash).
// Only touched under tetgen_mutex(), like TetGen itself.

/// The input points (ids below \p points) named by a trace line "... subface (a, b, c)." or
/// "... segment (a, b).", TetGen's VVV lines of its boundary recovery; empty otherwise.
std::vector<int> boundary_points_of(const std::string& line, int points) {
    std::vector<int> ids;
    const bool recovery = line.find("Recover ") != std::string::npos || line.find("Steiner point") != std::string::npos;
    const std::size_t open = line.find('(');
    if (!recovery || open == std::string::npos ||
        (line.find("subface (") == std::string::npos && line.find("segment (") == std::string::npos))
        return ids;
    const std::size_t close = line.find(')', open);
    if (close == std::string::npos) return ids;
    std::istringstream in(line.substr(open + 1, close - open - 1));
    std::string token;
    while (std::getline(in, token, ',')) {
        try {
            const int id = std::stoi(token);
            if (id >= 0 && id < points) ids.push_back(id);
        } catch (const std::exception&) {
            return {};
        }
    }
    return ids;
}

/// TetGen's phases, as tetrahedralize announces them when it is not quiet (no Q), and the share
/// of its run each starts at: measured on the airliner stand-in, the M6 and the sphere (the
/// refinement takes 70 to 77 % of the run, and starts at 14 to 24 % of it).
struct Phase {
    const char* announced;
    double at;
};
constexpr std::array<Phase, 7> kPhases{{{"Delaunizing vertices", 0.0},
                                        {"Creating surface mesh", 0.04},
                                        {"Recovering boundaries", 0.15},
                                        {"Removing exterior tetrahedra", 0.18},
                                        {"Recovering Delaunayness", 0.19},
                                        {"Refining mesh", 0.2},
                                        {"Optimizing mesh", 0.93}}};

/// Where TetGen's boundary recovery is: the input points of the face (3) or segment (2) it
/// named last; where that was an edge with a Steiner point of the face it named before, that
/// face.
struct Located {
    int count = 0;
    int ids[3] = {0, 0, 0};
    int face[3] = {0, 0, 0};  // the last face named with three input points
    bool has_face = false;
};

struct Trace {
    bool capturing = false;
    int points = 0;              // the input's points: ids from there on are Steiner points
    Located* located = nullptr;  // updated line by line while capturing
    std::atomic<int>* phase = nullptr;  // while capturing a run's phases: the last one it announced
    std::string line;            // the line being printed
    void add(const char* text) {
        for (const char* c = text; *c != '\0'; ++c) {
            if (*c != '\n') {
                line += *c;
                continue;
            }
            if (located != nullptr) note(boundary_points_of(line, points));
            if (phase != nullptr) note_phase();
            line.clear();
        }
    }
    void note_phase() {
        for (std::size_t i = 0; i < kPhases.size(); ++i)
            if (line.rfind(kPhases[i].announced, 0) == 0) phase->store(static_cast<int>(i), std::memory_order_relaxed);
    }
    void note(const std::vector<int>& ids) {
        if (ids.size() < 2) return;
        Located& l = *located;
        const auto in_face = [&](int id) { return std::find(l.face, l.face + 3, id) != l.face + 3; };
        if (ids.size() == 3) {
            std::copy(ids.begin(), ids.end(), l.face);
            l.has_face = true;
        }
        if (ids.size() == 2 && l.has_face && in_face(ids[0]) && in_face(ids[1])) {
            std::copy(l.face, l.face + 3, l.ids);
            l.count = 3;
        } else {
            std::copy(ids.begin(), ids.end(), l.ids);
            l.count = static_cast<int>(ids.size());
        }
    }
};
Trace& trace() {
    static Trace t;
    return t;
}

int capturing_printf_chk(int /*flag*/, const char* format, ...) {
    std::va_list args;
    va_start(args, format);
    int n = 0;
    if (!trace().capturing) {
        n = std::vprintf(format, args);
    } else {
        char buf[512];
        n = std::vsnprintf(buf, sizeof buf, format, args);
        trace().add(buf);
    }
    va_end(args);
    return n;
}

int capturing_puts(const char* text) {
    if (!trace().capturing) return std::puts(text);
    trace().add(text);
    trace().add("\n");
    return 1;
}

int capturing_putchar(int c) {
    if (!trace().capturing) return std::putchar(c);
    const char s[2] = {static_cast<char>(c), '\0'};
    trace().add(s);
    return c;
}

/// Point every GOT slot of the loaded object \p handle that binds \p symbol (JUMP_SLOT or
/// GLOB_DAT relocations) at \p replacement. Returns the number of slots changed.
int replace_got_slots(void* handle, const char* symbol, void* replacement) {
#if defined(__x86_64__)  // both 64-bit ELF: ELF64_R_TYPE/ELF64_R_SYM below
    constexpr unsigned kJumpSlot = R_X86_64_JUMP_SLOT, kGlobDat = R_X86_64_GLOB_DAT;
#elif defined(__aarch64__)
    constexpr unsigned kJumpSlot = R_AARCH64_JUMP_SLOT, kGlobDat = R_AARCH64_GLOB_DAT;
#else
    (void)handle, (void)symbol, (void)replacement;
    return 0;
#endif
#if defined(__x86_64__) || defined(__aarch64__)
    link_map* map = nullptr;
    if (dlinfo(handle, RTLD_DI_LINKMAP, &map) != 0 || map == nullptr) return 0;
    const ElfW(Addr) base = map->l_addr;
    // glibc has relocated these d_ptr values in place on x86-64 and AArch64; stay safe if not.
    auto at = [base](ElfW(Addr) p) { return p < base ? p + base : p; };
    // The dynamic section's entries (0 where absent), pointers relocated.
    auto entry = [map](ElfW(Sxword) tag) -> ElfW(Xword) {
        for (const ElfW(Dyn)* d = map->l_ld; d->d_tag != DT_NULL; ++d)
            if (d->d_tag == tag) return d->d_un.d_val;
        return 0;
    };
    auto pointer = [&](ElfW(Sxword) tag) -> ElfW(Addr) {
        const ElfW(Addr) p = entry(tag);
        return p == 0 ? 0 : at(p);
    };
    const auto* symtab = reinterpret_cast<const ElfW(Sym)*>(pointer(DT_SYMTAB));
    const auto* strtab = reinterpret_cast<const char*>(pointer(DT_STRTAB));
    const std::array<const ElfW(Rela)*, 2> rela{reinterpret_cast<const ElfW(Rela)*>(pointer(DT_JMPREL)),
                                                reinterpret_cast<const ElfW(Rela)*>(pointer(DT_RELA))};
    const std::array<std::size_t, 2> rela_bytes{entry(DT_PLTRELSZ), entry(DT_RELASZ)};
    const bool plt_is_rela = entry(DT_PLTREL) == 0 || entry(DT_PLTREL) == DT_RELA;
    if (symtab == nullptr || strtab == nullptr || !plt_is_rela) return 0;

    // The part of PT_GNU_RELRO that the loader made read-only (whole pages only).
    struct Relro {
        ElfW(Addr) base, begin = 0, end = 0;
    } relro{base};
    const auto page = static_cast<ElfW(Addr)>(sysconf(_SC_PAGESIZE));
    dl_iterate_phdr(
        [](dl_phdr_info* info, std::size_t, void* data) {
            auto* r = static_cast<Relro*>(data);
            if (info->dlpi_addr != r->base) return 0;
            for (int i = 0; i < info->dlpi_phnum; ++i)
                if (info->dlpi_phdr[i].p_type == PT_GNU_RELRO) {
                    r->begin = info->dlpi_addr + info->dlpi_phdr[i].p_vaddr;
                    r->end = r->begin + info->dlpi_phdr[i].p_memsz;
                }
            return 1;
        },
        &relro);
    relro.begin &= ~(page - 1);
    relro.end &= ~(page - 1);

    int changed = 0;
    for (std::size_t k = 0; k < rela.size(); ++k) {
        if (rela[k] == nullptr) continue;
        for (std::size_t i = 0; i < rela_bytes[k] / sizeof(ElfW(Rela)); ++i) {
            const ElfW(Rela)& r = rela[k][i];
            const auto type = ELF64_R_TYPE(r.r_info);
            if ((type != kJumpSlot && type != kGlobDat) ||
                std::strcmp(strtab + symtab[ELF64_R_SYM(r.r_info)].st_name, symbol) != 0)
                continue;
            const ElfW(Addr) slot = base + r.r_offset;
            const ElfW(Addr) slot_page = slot & ~(page - 1);
            const bool read_only = slot_page >= relro.begin && slot_page < relro.end;
            void* p = reinterpret_cast<void*>(slot_page);
            if (read_only && mprotect(p, page, PROT_READ | PROT_WRITE) != 0) continue;
            *reinterpret_cast<void**>(slot) = replacement;
            if (read_only) mprotect(p, page, PROT_READ);
            ++changed;
        }
    }
    return changed;
#endif
}

std::string object_of(const void* address) {
    Dl_info info{};
    return dladdr(address, &info) != 0 && info.dli_fname != nullptr ? info.dli_fname : "";
}

std::mutex& tetgen_mutex() {
    static std::mutex m;
    return m;
}

}  // namespace

Library load(const Symbols& symbols) {
    // The runtime package's soname first (Debian's libtet1.5); the -dev symlink as fallback.
    std::vector<const char*> names{"libtet.so.1.5", "libtet.so"};
#ifdef STRATA_LIBTET
    names.insert(names.begin(), STRATA_LIBTET);
#endif
    // Linked into the program after all (global scope)? Then libtet binds to libgmsh's copy
    // if libgmsh comes first, which crashes: refuse with the reason.
    if (void* global = dlsym(RTLD_DEFAULT, symbols.tetrahedralize)) {
        const std::string tet = object_of(global);
        void* shared = dlsym(RTLD_DEFAULT, symbols.shared_with_gmsh);
        if (shared != nullptr && object_of(shared) != tet)
            throw BackendError("TetGen: libtet is linked into this program (" + tet +
                               ") after a library with its own TetGen (" + object_of(shared) +
                               "), so TetGen would crash; do not link libtet, Strata loads it itself "
                               "(hybrid/CMakeLists.txt)");
    }
    void* handle = nullptr;
    std::string tried, loaded;
    for (const char* name : names) {
        handle = dlopen(name, RTLD_NOW | RTLD_LOCAL | RTLD_DEEPBIND);
        if (handle != nullptr) {
            loaded = name;
            break;
        }
        const char* e = dlerror();
        tried += std::string(tried.empty() ? "" : "; ") + (e != nullptr ? e : name);
    }
    if (handle == nullptr)
        throw BackendError("TetGen's library could not be loaded (" + tried + "); install libtet1.5 (Debian/Ubuntu)");
    // Never dlclose()d: TetGen stays loaded for the process.
    Library lib;
    lib.tetrahedralize = reinterpret_cast<TetrahedralizeFn>(dlsym(handle, symbols.tetrahedralize));
    if (lib.tetrahedralize == nullptr)
        throw BackendError("TetGen's library " + loaded + " has no " + symbols.tetrahedralize +
                           " (tetrahedralize(char*, tetgenio*, ...)): not TetGen 1.5 built with TETLIBRARY; "
                           "install Debian's libtet1.5");
    lib.replaced_slots =
        replace_got_slots(handle, symbols.terminate, reinterpret_cast<void*>(&throwing_terminatetetgen));
    if (lib.replaced_slots == 0)
        throw BackendError(std::string("TetGen: no call to ") + symbols.terminate +
                           " (terminatetetgen) could be redirected in its library, so a TetGen failure would "
                           "crash the process instead of being reported; Strata supports Debian's libtet1.5 on "
                           "x86-64 and AArch64");
    // Its internal checks too, where it has any (none if built with NDEBUG).
    lib.assert_slots = replace_got_slots(handle, "__assert_fail", reinterpret_cast<void*>(&throwing_assert_fail));
    // Its printing, so that locate_failure can read its trace.
    lib.print_slots = replace_got_slots(handle, "__printf_chk", reinterpret_cast<void*>(&capturing_printf_chk)) +
                      replace_got_slots(handle, "puts", reinterpret_cast<void*>(&capturing_puts)) +
                      replace_got_slots(handle, "putchar", reinterpret_cast<void*>(&capturing_putchar));
    return lib;
}

namespace {

const Library& library() {
    static const Library lib = load();
    return lib;
}

// TetGen in a child process. A TetGen failure that is neither an exit code nor an assert()
// (a SIGSEGV: Debian's libtet 1.5.0 crashes in sremovevertex on some fronts whose facets it
// cannot recover) would end the whole process, a FreeCAD or Gmsh session with it. So each run
// is forked (run_in_child, core/child_process.h): the child runs tetrahedralize on its copy of
// the input and writes its outcome down a pipe (the output arrays, or the failure), then
// _exit()s; the parent reads it back into `out`. A child that dies on a signal is a
// BackendError naming the signal. Where fork() is not available (EAGAIN, ENOMEM, a sandbox)
// TetGen runs in this process as before.

/// The outcome of a run, as the child sends it.
enum class Outcome : char { Done = 0, Code = 1, Assert = 2, NoMemory = 3, Other = 4 };

/// TetGen's arrays through Bytes (core/bytes.h): a presence flag, then n items if present.
template <class T>
void put_array(Bytes& b, const T* p, std::size_t n) {
    b.put<char>(p != nullptr);
    if (p != nullptr) b.append(p, n * sizeof(T));
}
template <class T>
T* get_array(Bytes& b, std::size_t n) {  // new[]ed, as tetgenio::deinitialize delete[]s it
    if (!b.get<char>()) return nullptr;
    if (n > (b.data.size() - b.at) / sizeof(T)) b.truncated();
    T* p = new T[n > 0 ? n : 1];
    b.take(p, n * sizeof(T));
    return p;
}

/// TetGen's output arrays (those its switches here can produce; the Voronoi ones are not used).
void put_output(Bytes& b, const tetgenio& o) {
    const auto n = static_cast<std::size_t>(std::max(o.numberofpoints, 0));
    const auto nt = static_cast<std::size_t>(std::max(o.numberoftetrahedra, 0));
    const auto nf = static_cast<std::size_t>(std::max(o.numberoftrifaces, 0));
    const auto ne = static_cast<std::size_t>(std::max(o.numberofedges, 0));
    for (const int v : {o.firstnumber, o.mesh_dim, o.numberofpoints, o.numberofpointattributes, o.numberofpointmtrs,
                        o.numberoftetrahedra, o.numberofcorners, o.numberoftetrahedronattributes, o.numberoftrifaces,
                        o.numberofedges})
        b.put<int>(v);
    put_array(b, o.pointlist, 3 * n);
    put_array(b, o.pointattributelist, n * static_cast<std::size_t>(std::max(o.numberofpointattributes, 0)));
    put_array(b, o.pointmtrlist, n * static_cast<std::size_t>(std::max(o.numberofpointmtrs, 0)));
    put_array(b, o.pointmarkerlist, n);
    put_array(b, o.tetrahedronlist, nt * static_cast<std::size_t>(std::max(o.numberofcorners, 0)));
    put_array(b, o.tetrahedronattributelist,
              nt * static_cast<std::size_t>(std::max(o.numberoftetrahedronattributes, 0)));
    put_array(b, o.tetrahedronvolumelist, nt);
    put_array(b, o.neighborlist, 4 * nt);
    put_array(b, o.trifacelist, 3 * nf);
    put_array(b, o.trifacemarkerlist, nf);
    put_array(b, o.o2facelist, 3 * nf);
    put_array(b, o.adjtetlist, 2 * nf);
    put_array(b, o.edgelist, 2 * ne);
    put_array(b, o.edgemarkerlist, ne);
    put_array(b, o.o2edgelist, ne);
    put_array(b, o.edgeadjtetlist, ne);
}

void get_output(Bytes& b, tetgenio& o) {
    o.firstnumber = b.get<int>();
    o.mesh_dim = b.get<int>();
    o.numberofpoints = b.get<int>();
    o.numberofpointattributes = b.get<int>();
    o.numberofpointmtrs = b.get<int>();
    o.numberoftetrahedra = b.get<int>();
    o.numberofcorners = b.get<int>();
    o.numberoftetrahedronattributes = b.get<int>();
    o.numberoftrifaces = b.get<int>();
    o.numberofedges = b.get<int>();
    const auto n = static_cast<std::size_t>(std::max(o.numberofpoints, 0));
    const auto nt = static_cast<std::size_t>(std::max(o.numberoftetrahedra, 0));
    const auto nf = static_cast<std::size_t>(std::max(o.numberoftrifaces, 0));
    const auto ne = static_cast<std::size_t>(std::max(o.numberofedges, 0));
    o.pointlist = get_array<REAL>(b, 3 * n);
    o.pointattributelist = get_array<REAL>(b, n * static_cast<std::size_t>(std::max(o.numberofpointattributes, 0)));
    o.pointmtrlist = get_array<REAL>(b, n * static_cast<std::size_t>(std::max(o.numberofpointmtrs, 0)));
    o.pointmarkerlist = get_array<int>(b, n);
    o.tetrahedronlist = get_array<int>(b, nt * static_cast<std::size_t>(std::max(o.numberofcorners, 0)));
    o.tetrahedronattributelist =
        get_array<REAL>(b, nt * static_cast<std::size_t>(std::max(o.numberoftetrahedronattributes, 0)));
    o.tetrahedronvolumelist = get_array<REAL>(b, nt);
    o.neighborlist = get_array<int>(b, 4 * nt);
    o.trifacelist = get_array<int>(b, 3 * nf);
    o.trifacemarkerlist = get_array<int>(b, nf);
    o.o2facelist = get_array<int>(b, 3 * nf);
    o.adjtetlist = get_array<int>(b, 2 * nf);
    o.edgelist = get_array<int>(b, 2 * ne);
    o.edgemarkerlist = get_array<int>(b, ne);
    o.o2edgelist = get_array<int>(b, ne);
    o.edgeadjtetlist = get_array<int>(b, ne);
}

/// tetrahedralize here, its outcome into \p b; true if it succeeded.
bool tetrahedralize_into(const std::string& switches, tetgenio& in, tetgenio& out, tetgenio* background, Bytes& b) {
    std::vector<char> buf(switches.begin(), switches.end());
    buf.push_back('\0');
    try {
        library().tetrahedralize(buf.data(), &in, &out, nullptr, background);
        b.put(Outcome::Done);
        return true;
    } catch (int code) {
        b.put(Outcome::Code);
        b.put<int>(code);
    } catch (const FailedAssertion& a) {
        b.put(Outcome::Assert);
        b.put_string(a.text);
    } catch (const std::bad_alloc&) {
        b.put(Outcome::NoMemory);
    } catch (...) {
        b.put(Outcome::Other);
    }
    return false;
}

/// The failure \p b holds as Strata's exception (nothing if it holds a success).
void throw_outcome(Bytes& b) {
    const Outcome o = b.get<Outcome>();
    switch (o) {
        case Outcome::Done:
            return;
        case Outcome::Code: {
            const int code = b.get<int>();
            if (code >= 2 && code <= 5) throw LocalFailure(failure_message(code));
            throw BackendError(failure_message(code));
        }
        case Outcome::Assert:
            throw LocalFailure(
                "TetGen stopped on one of its internal checks (" + b.get_string() +
                "): it met a configuration it assumes cannot happen, usually boundary points exactly on another "
                "boundary face's plane or nearly coincident (a needle or sliver face on the layer top, or layers "
                "nearly touching); remesh the surface (needle faces) or change the layers (fewer or thinner) "
                "there, and retry");
        case Outcome::NoMemory:
            throw BackendError(failure_message(1));
        case Outcome::Other:
            break;
    }
    throw BackendError("TetGen failed with an exception it does not document");
}

/// \p body run in a forked child (run_in_child; it sends what it puts into its Bytes), its
/// bytes returned; false (nothing run) where fork() is not available. BackendError when the
/// child dies on a signal. The caller holds tetgen_mutex().
bool in_child(const std::function<void(Bytes&)>& body, Bytes& result, const Progress* progress) {
    const ChildResult child = run_in_child(
        [&](std::vector<char>& sent) {
            Bytes b;
            try {
                body(b);
            } catch (...) {
                b.data.clear();
                b.put(Outcome::Other);
            }
            sent = std::move(b.data);
        },
        progress);
    if (!child.forked) return false;
    result.data = child.sent;
    result.at = 0;
    result.what = "TetGen's child process";
    if (child.signal == SIGKILL)  // not its own doing: the system's
        throw BackendError("TetGen was killed (signal 9), most likely by the system for want of memory: " +
                           failure_message(1));
    if (child.signal != 0) {
        const char* name = sigdescr_np(child.signal);
        throw LocalFailure("TetGen crashed (signal " + std::to_string(child.signal) + ", " + (name ? name : "unknown") +
                           "), usually on boundary faces it could not recover (nearly coplanar or nearly "
                           "touching faces of the layer top); remesh the surface (needle faces) or change the "
                           "layers (fewer or thinner) there, and retry");
    }
    if (child.exit_status != 0 || result.data.empty())
        throw BackendError("TetGen's child process ended without sending its result (exit status " +
                           std::to_string(child.exit_status) + ")");
    return true;
}

/// An int the child process writes and this one reads (a page both share), for the phase the
/// child's TetGen announced last; -1 before any. Not ok() where it could not be mapped.
class SharedPhase {
public:
    SharedPhase() {
        const int shared = MAP_SHARED | MAP_ANONYMOUS;
        void* page = ::mmap(nullptr, sizeof(std::atomic<int>), PROT_READ | PROT_WRITE, shared, -1, 0);
        if (page != MAP_FAILED) phase_ = new (page) std::atomic<int>(-1);
    }
    ~SharedPhase() {
        if (phase_) ::munmap(phase_, sizeof(std::atomic<int>));
    }
    SharedPhase(const SharedPhase&) = delete;
    SharedPhase& operator=(const SharedPhase&) = delete;
    bool ok() const { return phase_ != nullptr; }
    std::atomic<int>* get() const { return phase_; }

private:
    std::atomic<int>* phase_ = nullptr;
};

/// The parent's side of the phases: each time run_in_child asks whether to stop (every 0.1 s),
/// the phase the child announced since is reported to \p inner as "tetrahedra" at its share of
/// the run (kPhases).
class PhaseWatch : public Progress {
public:
    PhaseWatch(Progress* inner, const std::atomic<int>* phase) : inner_(inner), phase_(phase) {}
    void report(std::string_view stage, double fraction) override { inner_->report(stage, fraction); }
    bool cancelled() const override {
        const int p = phase_->load(std::memory_order_relaxed);
        if (p > last_ && p < static_cast<int>(kPhases.size())) {
            last_ = p;
            inner_->report("tetrahedra", kPhases[static_cast<std::size_t>(p)].at);
        }
        return inner_->cancelled();
    }
    void watch_child(int pid) const override { inner_->watch_child(pid); }

private:
    Progress* inner_;
    const std::atomic<int>* phase_;
    mutable int last_ = -1;
};

/// \p switches without Q: TetGen then announces its phases (and prints its statistics at the
/// end, which the capture swallows); nothing else it computes changes.
std::string announcing(const std::string& switches) {
    std::string s;
    for (const char c : switches)
        if (c != 'Q') s += c;
    return s;
}

/// tetrahedralize, its failures as exceptions, in a child process where possible; the caller
/// holds tetgen_mutex(). With \p progress and TetGen's printing redirected, the child runs it
/// announcing its phases into a page shared with this process, which reports them (PhaseWatch).
void run_locked(const std::string& switches, tetgenio& in, tetgenio& out, tetgenio* background, Progress* progress) {
    library();  // loaded (and patched) before any fork
    Bytes b;
    const SharedPhase shared;
    const bool phases = progress != nullptr && library().print_slots > 0 && shared.ok();
    PhaseWatch watch(progress, shared.get());
    const bool forked = in_child(
        [&](Bytes& sent) {
            if (phases) {  // this process is the child: its trace is its own
                trace() = Trace{};
                trace().capturing = true;
                trace().phase = shared.get();
            }
            tetgenio child_out;
            if (tetrahedralize_into(phases ? announcing(switches) : switches, in, child_out, background, sent))
                put_output(sent, child_out);
        },
        b, phases ? &watch : progress);
    if (!forked) tetrahedralize_into(switches, in, out, background, b);
    throw_outcome(b);
    if (forked) get_output(b, out);
}

}  // namespace

void run(const std::string& switches, tetgenio& in, tetgenio& out, tetgenio* background, Progress* progress) {
    std::lock_guard<std::mutex> lock(tetgen_mutex());
    run_locked(switches, in, out, background, progress);
}

std::vector<int> locate_failure(const std::string& switches, tetgenio& in, tetgenio* background,
                                const Progress* progress) {
    std::lock_guard<std::mutex> lock(tetgen_mutex());
    if (library().print_slots == 0) return {};
    const std::string traced = announcing(switches) + "VVV";
    // Where it was, in a page the child shares with this process: what the trace said last
    // stays readable even if the child crashes.
    void* page = ::mmap(nullptr, sizeof(Located), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    Located here;
    Located* located = page != MAP_FAILED ? new (page) Located : &here;
    const auto traced_run = [&](Bytes& sent) {
        Trace& t = trace();
        t = Trace{};
        t.capturing = true;
        t.points = in.numberofpoints;
        t.located = located;
        tetgenio out;
        tetrahedralize_into(traced, in, out, background, sent);
        t = Trace{};
    };
    Bytes b;
    bool failed = true;  // a crash is a failure too
    try {
        if (!in_child(traced_run, b, progress)) traced_run(b);
        failed = b.get<Outcome>() != Outcome::Done;
    } catch (const Error&) {
    }
    std::vector<int> ids;
    if (failed) ids.assign(located->ids, located->ids + located->count);
    if (page != MAP_FAILED) ::munmap(page, sizeof(Located));
    return ids;
}

std::string failure_message(int code) {
    const std::string c = " (TetGen code " + std::to_string(code) + ")";
    switch (code) {
        case 1:
            return "TetGen ran out of memory" + c +
                   ": the tetrahedral mesh is too large; coarsen it (larger growth or max_volume, a coarser "
                   "farfield) or use a machine with more memory";
        case 2:
            return "TetGen failed internally" + c +
                   ": usually a boundary with nearly degenerate or nearly touching triangles; check the input "
                   "surface for needle or sliver triangles and the layer top for folds, and retry";
        case 3:
            return "TetGen: the boundary intersects itself" + c +
                   ": the layer top or the farfield overlaps itself or the other; reduce the layer thickness "
                   "or enlarge the farfield";
        case 4:
            return "TetGen: the boundary has a very small feature" + c +
                   ": two boundary nodes, or a node and a triangle, nearly touch (relative to the bounding box); "
                   "merge near-duplicate nodes, reduce the layer thickness where the layer top nearly touches "
                   "itself, or enlarge the farfield less";
        case 5:
            return "TetGen: two boundary triangles are very close to each other" + c +
                   ": the layer top nearly touches itself or the farfield (e.g. layers meeting in a narrow "
                   "gap); reduce the layer thickness there";
        case 10:
            return "TetGen rejected its input" + c +
                   ": a degenerate boundary triangle or a boundary that is not a closed surface; check the "
                   "input surface (strata surface reports what it finds)";
        default:
            return "TetGen failed" + c;
    }
}

}  // namespace strata::tetgen
