// The tetrahedral fill: Strata's one adapter to TetGen 1.5 (Debian's libtet), loaded
// privately at run time (see "Loading libtet" below for why it is not linked).
//
// What happens:
//  1. The boundary is checked (triangles only, ids in range, finite, no repeated triangle,
//     encloses a positive volume, i.e. normals point out of the region) and handed to
//     TetGen as a PLC: one facet of one polygon per triangle, the hole seeds as volume holes.
//  2. TetGen runs with  p Y z Q [q<ratio>[/<angle>]] [a<vol>] [m]:
//       p  the input is a PLC;
//       Y  the boundary triangles are kept exactly: no Steiner point on the boundary (the
//          layer top must stay conforming with the prisms/pyramids under it);
//       z  0-based indices, so TetGen's point i is our point i;
//       Q  quiet (TetGen prints to stdout otherwise);
//       q  radius-edge [/ min dihedral] bound, only with params.refine;
//       a  global volume bound, only with params.refine and max_volume > 0;
//       m  sizing field (only with params.refine and growth > 0), see below.
//  3. The result is converted (Gmsh tet order, positive volume) and checked independently of
//     TetGen: the boundary points come back unchanged with their ids, every tet has positive
//     volume, every boundary triangle is a face of exactly one tet with that tet on the side
//     its normal points away from, and the tet volumes sum to the volume the boundary
//     encloses. Together (a tet face cannot have a vertex of another tet inside it in a
//     conforming mesh) this means no Steiner point lies on the boundary. A violation is a
//     BackendError, a wrongly oriented boundary an InputError.
//
// Sizing (params.growth > 0). TetFillParams::growth documents the field
//     h(x) = min(h_wall + growth · d(x), h_far),
// d the distance to the non-farfield ("wall", the layer top) part of the boundary. Here:
//   * h_wall is the mean length of the boundary edges at the nearest wall node, d the
//     distance to that node (the nearest node instead of the nearest triangle: off by less
//     than one wall edge, i.e. by growth × edge ≪ edge in h);
//   * h_far is the mean edge length of the farfield triangles (no farfield patch: no cap
//     beyond the bounding-box diagonal), lowered to the edge of the regular tet of volume
//     max_volume if that is set (TetGen's -m sizes also act as spacings: a point closer to a
//     vertex than the vertex's size is rejected, which would otherwise keep -a from being
//     met); boundary nodes keep their own mean edge length, capped the same way;
//   * TetGen's -m size is a bound on the circumradius of the tets at a vertex (checktet4split
//     splits a tet whose circumradius exceeds the size at one of its corners), so the size
//     given is kRadiusPerEdge × h.
// Sizes given only at the boundary points would be interpolated linearly by TetGen across
// the first, huge tets between body and farfield, i.e. the growth rate would be whatever the
// distance to the farfield makes it, not params.growth. So h is sampled on a background mesh
// (TetGen's bgmesh, tetrahedralize's last argument): a quality-only refinement (q2, no size)
// of the same PLC, whose node density already follows the local feature size (fine at the
// wall, coarse far out), which resolves the piecewise-linear h well and costs a fraction of
// the final run. h is evaluated at its nodes, TetGen interpolates linearly inside its tets.
//
// TetGen is not reentrant: exactinit() sets the robust predicates' static error bounds from
// each input's bounding box (process-wide globals), so two concurrent runs would corrupt each
// other's predicates. Every call into TetGen holds one process-wide mutex.
//
// Memory: tetgenio's destructor frees every array with delete[] (deinitialize()), so the
// arrays given to it are allocated with new[] and owned by the tetgenio from that moment.
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
// throws: the mesh is freed once, by the destructor, and the int reaches run_tetgen. Where
// the slot cannot be found (another libtet build or architecture) TetGen still works, but a
// failure would crash. tests/hybrid/test_tetgen_fill.cpp checks a self-intersecting boundary
// (BackendError) and TetGen with Gmsh's Delaunay and HXT meshers in one process, both orders.
// Left as they are: on a failure TetGen leaks a few KB of its own (arraypools local to
// recoverboundary; valgrind) and may print a line or two to stdout despite Q ("Found two
// segments intersect each other.").
//
// Caveat of RTLD_DEEPBIND: libtet resolves operator new/delete in libstdc++ even if the
// program replaces them (as AddressSanitizer does), while tetgenio's inline destructor uses
// the program's: run sanitizer builds with ASAN_OPTIONS=alloc_dealloc_mismatch=0.

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/core/mesh_check.h>
#include <strata/core/face_geometry.h>
#include <strata/hybrid/tetgen_fill.h>

// TETLIBRARY: TetGen's library interface (hybrid/CMakeLists.txt does not link strata::tetgen,
// which would put libtet on the link line; see "Loading libtet" above).
#ifndef TETLIBRARY
#define TETLIBRARY
#endif
#include <tetgen.h>

#include <dlfcn.h>
#include <elf.h>
#include <link.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <new>
#include <numeric>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace strata {
namespace {

/// TetGen's -m size (a circumradius bound) per target edge length. Calibrated: under the
/// bound r, TetGen's q1.5 tets have a mean edge of about 1.33 r (1.63 r for a regular tet), so
/// 0.75 h gives a mean edge within ~5% of h up to the farfield's influence (checked with
/// growth 0.1-0.3 on the cube in a box of tests/hybrid/test_tetgen_fill.cpp).
constexpr double kRadiusPerEdge = 0.75;
/// Radius-edge bound of the background mesh's quality-only refinement.
constexpr double kBackgroundRatio = 2.0;

std::mutex& tetgen_mutex() {
    static std::mutex m;
    return m;
}

std::string face_name(const SurfaceMesh& b, Index f) {
    std::string s = "boundary triangle " + std::to_string(f);
    const Index p = b.face_patch[f];
    if (p >= 0 && p < static_cast<Index>(b.patches.size())) s += " (patch '" + b.patches[p].name + "')";
    Vec3 c = Vec3::Zero();
    for (int i = 0; i < 3; ++i) c += b.points[b.face_node(f, i)];
    return s + " at " + format_point(c / 3.0);
}

/// (1/6) a·(b×c): the triangle's share of the volume it and the rest of a closed surface enclose.
double triangle_volume_term(const Vec3& a, const Vec3& b, const Vec3& c) {
    return a.dot(b.cross(c)) / 6.0;
}

/// det(v1−v0, v2−v0, v3−v0) / 6.
double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return (b - a).cross(c - a).dot(d - a) / 6.0;
}

// ---------------------------------------------------------------------------------------
// Input checks.

void check_input(const SurfaceMesh& b, const std::vector<Vec3>& holes, const TetFillParams& p) {
    const std::string where = "fill_with_tets: ";
    // One check for every stage; TetGen fills a triangulated boundary (quads are split first,
    // by pyramids on the layer top). A non-finite coordinate is the caller's input here too.
    const MeshProblems arrays = check_surface_arrays(b, {.triangles_only = true, .word = "boundary face"});
    if (!arrays.ok()) throw InputError(where + arrays.lines.front());
    if (b.points.size() > static_cast<std::size_t>(std::numeric_limits<int>::max() / 3) ||
        b.face_nodes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
        throw InputError(where + "the boundary is too large for TetGen's 32-bit ints");
    for (std::size_t h = 0; h < holes.size(); ++h)
        if (!holes[h].allFinite())
            throw InputError(where + "hole point " + std::to_string(h) + " has a non-finite coordinate");

    if (p.refine) {
        if (!(p.radius_edge >= 1.0) || !std::isfinite(p.radius_edge))
            throw InputError(where + "radius_edge = " + format_number(p.radius_edge) +
                             " is below 1: TetGen would refine without end; use 1.2 or more");
        if (!(p.min_dihedral >= 0.0 && p.min_dihedral < 70.0))
            throw InputError(where + "min_dihedral = " + format_number(p.min_dihedral) +
                             " degrees is outside [0, 70); TetGen reaches about 15-18 in practice");
        if (!(p.max_volume >= 0.0) || !std::isfinite(p.max_volume))
            throw InputError(where + "max_volume = " + format_number(p.max_volume) + " must be 0 (no bound) or positive");
        if (!(p.growth >= 0.0) || !std::isfinite(p.growth))
            throw InputError(where + "growth = " + format_number(p.growth) + " must be 0 (no sizing) or positive");
    }
}

/// Volume enclosed by the boundary (divergence theorem; positive when normals point out).
double enclosed_volume(const SurfaceMesh& b) {
    double v = 0.0;
    for (Index f = 0; f < b.num_faces(); ++f)
        v +=
            triangle_volume_term(b.points[b.face_node(f, 0)], b.points[b.face_node(f, 1)], b.points[b.face_node(f, 2)]);
    return v;
}

// ---------------------------------------------------------------------------------------
// TetGen input, switches and failures.

/// Points and facets (one triangle each) and hole seeds into \p io; the arrays are new[]ed
/// and owned by io from here on (tetgenio::deinitialize delete[]s them).
void set_plc(tetgenio& io, const SurfaceMesh& b, const std::vector<Vec3>& holes) {
    io.firstnumber = 0;
    io.numberofpoints = static_cast<int>(b.points.size());
    io.pointlist = new REAL[3 * b.points.size()];
    for (std::size_t i = 0; i < b.points.size(); ++i)
        for (int k = 0; k < 3; ++k) io.pointlist[3 * i + k] = b.points[i][k];

    const int nf = static_cast<int>(b.num_faces());
    io.facetlist = new tetgenio::facet[nf];
    io.numberoffacets = nf;  // every facet initialised before deinitialize could walk it
    for (int f = 0; f < nf; ++f) tetgenio::init(&io.facetlist[f]);
    for (int f = 0; f < nf; ++f) {
        tetgenio::facet& fa = io.facetlist[f];
        fa.polygonlist = new tetgenio::polygon[1];
        tetgenio::init(&fa.polygonlist[0]);
        fa.numberofpolygons = 1;
        fa.polygonlist[0].vertexlist = new int[3];
        fa.polygonlist[0].numberofvertices = 3;
        for (int i = 0; i < 3; ++i) fa.polygonlist[0].vertexlist[i] = static_cast<int>(b.face_node(f, i));
    }

    if (!holes.empty()) {
        io.holelist = new REAL[3 * holes.size()];
        io.numberofholes = static_cast<int>(holes.size());
        for (std::size_t h = 0; h < holes.size(); ++h)
            for (int k = 0; k < 3; ++k) io.holelist[3 * h + k] = holes[h][k];
    }
}

/// TetGen's exit codes (terminatetetgen in tetgen.h) as a message saying what to do.
std::string tetgen_failure(int code) {
    const std::string c = " (TetGen code " + std::to_string(code) + ")";
    switch (code) {
        case 1:
            return "TetGen ran out of memory" + c +
                   ": the tetrahedral mesh is too large; coarsen it (larger growth or max_volume, a coarser "
                   "farfield) or use a machine with more memory";
        case 2:
            return "TetGen failed internally" + c +
                   ": usually a boundary with nearly degenerate or nearly touching triangles; check the surface "
                   "and the layer top (strata check) and retry";
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
                   "surface (strata check)";
        default:
            return "TetGen failed" + c;
    }
}

/// Switches for one run, parsed by TetGen itself (so its consistency rules apply).
std::string switches(const TetFillParams& p, bool sizing, bool background) {
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
    std::string s = "pYzQ";
    if (background) {
        s += 'c';  // keep the convex hull: every walk towards a point stays inside the mesh
        s += 'q';
        s += format_number(kBackgroundRatio, 17);
        return s;
    }
    if (!p.refine) return s;
    s += 'q';
    s += format_number(p.radius_edge, 17);
    if (p.min_dihedral > 0.0) {
        s += '/';
        s += format_number(p.min_dihedral, 17);
    }
    if (p.max_volume > 0.0) {
        s += 'a';
        s += format_number(p.max_volume, 17);
    }
    if (sizing) s += 'm';
    return s;
}

// ---------------------------------------------------------------------------------------
// Loading libtet (see the file comment).

using TetrahedralizeFn = void (*)(char*, tetgenio*, tetgenio*, tetgenio*, tetgenio*);
constexpr const char* kTetrahedralize = "_Z14tetrahedralizePcP8tetgenioS1_S1_S1_";  // tetrahedralize(char*, ...)
constexpr const char* kTerminate = "_Z15terminatetetgenP10tetgenmeshi";             // terminatetetgen(tetgenmesh*, int)
constexpr const char* kSharedWithGmsh = "_ZN10tetgenmesh10inittablesEv";            // tetgenmesh::inittables()

/// Replaces libtet's terminatetetgen: throw TetGen's exit code, leave the freeing to the
/// tetgenmesh destructor.
[[noreturn]] void throwing_terminatetetgen(tetgenmesh* /*mesh*/, int code) {
    throw code;
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
    const ElfW(Sym)* symtab = nullptr;
    const char* strtab = nullptr;
    std::array<const ElfW(Rela)*, 2> rela{nullptr, nullptr};
    std::array<std::size_t, 2> rela_bytes{0, 0};
    bool plt_is_rela = true;
    for (const ElfW(Dyn)* d = map->l_ld; d->d_tag != DT_NULL; ++d) {
        switch (d->d_tag) {
            case DT_SYMTAB:
                symtab = reinterpret_cast<const ElfW(Sym)*>(at(d->d_un.d_ptr));
                break;
            case DT_STRTAB:
                strtab = reinterpret_cast<const char*>(at(d->d_un.d_ptr));
                break;
            case DT_JMPREL:
                rela[0] = reinterpret_cast<const ElfW(Rela)*>(at(d->d_un.d_ptr));
                break;
            case DT_PLTRELSZ:
                rela_bytes[0] = d->d_un.d_val;
                break;
            case DT_PLTREL:
                plt_is_rela = d->d_un.d_val == DT_RELA;
                break;
            case DT_RELA:
                rela[1] = reinterpret_cast<const ElfW(Rela)*>(at(d->d_un.d_ptr));
                break;
            case DT_RELASZ:
                rela_bytes[1] = d->d_un.d_val;
                break;
            default:
                break;
        }
    }
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

struct LibTet {
    TetrahedralizeFn tetrahedralize = nullptr;
    int replaced_slots = 0;  ///< terminatetetgen GOT slots pointed at throwing_terminatetetgen
    std::string error;       ///< why TetGen cannot be used (empty if it can)
};

std::string object_of(const void* address) {
    Dl_info info{};
    return dladdr(address, &info) != 0 && info.dli_fname != nullptr ? info.dli_fname : "";
}

LibTet load_libtet() {
    LibTet lib;
    // The runtime package's soname first (Debian's libtet1.5); the -dev symlink as fallback.
    std::vector<const char*> names{"libtet.so.1.5", "libtet.so"};
#ifdef STRATA_LIBTET
    names.insert(names.begin(), STRATA_LIBTET);
#endif
    // Linked into the program after all (global scope)? Then libtet binds to libgmsh's copy
    // if libgmsh comes first, which crashes: refuse with the reason.
    if (void* global = dlsym(RTLD_DEFAULT, kTetrahedralize)) {
        const std::string tet = object_of(global);
        void* shared = dlsym(RTLD_DEFAULT, kSharedWithGmsh);
        if (shared != nullptr && object_of(shared) != tet) {
            lib.error = "libtet is linked into this program (" + tet + ") after a library with its own TetGen (" +
                        object_of(shared) +
                        "), so TetGen would crash; do not link libtet, Strata loads it itself (hybrid/CMakeLists.txt)";
            return lib;
        }
    }
    void* handle = nullptr;
    std::string tried;
    for (const char* name : names) {
        handle = dlopen(name, RTLD_NOW | RTLD_LOCAL | RTLD_DEEPBIND);
        if (handle != nullptr) break;
        const char* e = dlerror();
        tried += std::string(tried.empty() ? "" : "; ") + (e != nullptr ? e : name);
    }
    if (handle == nullptr) {
        lib.error = "TetGen's library could not be loaded (" + tried + "); install libtet1.5 (Debian/Ubuntu)";
        return lib;
    }
    lib.tetrahedralize = reinterpret_cast<TetrahedralizeFn>(dlsym(handle, kTetrahedralize));
    if (lib.tetrahedralize == nullptr) {
        lib.error =
            "TetGen's library has no tetrahedralize(char*, tetgenio*, ...) (not TetGen 1.5 built with "
            "TETLIBRARY?)";
        return lib;
    }
    lib.replaced_slots = replace_got_slots(handle, kTerminate, reinterpret_cast<void*>(&throwing_terminatetetgen));
    return lib;  // never dlclose()d: loaded once per process
}

const LibTet& libtet() {
    static const LibTet lib = load_libtet();
    return lib;
}

/// tetrahedralize under the process-wide lock; TetGen's int throws become BackendError.
void run_tetgen(const std::string& sw, tetgenio& in, tetgenio& out, tetgenio* background) {
    std::lock_guard<std::mutex> lock(tetgen_mutex());
    const LibTet& lib = libtet();
    if (!lib.error.empty()) throw BackendError("fill_with_tets: " + lib.error);
    std::vector<char> buf(sw.begin(), sw.end());
    buf.push_back('\0');
    try {
        lib.tetrahedralize(buf.data(), &in, &out, nullptr, background);
    } catch (int code) {
        throw BackendError(tetgen_failure(code));
    } catch (const std::bad_alloc&) {
        throw BackendError(tetgen_failure(1));
    }
}

// ---------------------------------------------------------------------------------------
// Sizing field.

/// Nearest of a fixed point set: a kd-tree stored implicitly in one permuted index array
/// (median of each range at its middle, split axis per middle).
class NearestPoint {
public:
    explicit NearestPoint(const std::vector<Vec3>& points) : p_(points), order_(points.size()), axis_(points.size()) {
        std::iota(order_.begin(), order_.end(), Index{0});
        build(0, static_cast<Index>(order_.size()));
    }

    /// Index into the points given to the constructor (kNone if there were none).
    Index nearest(const Vec3& q) const {
        Index best = kNone;
        double best_d2 = std::numeric_limits<double>::infinity();
        search(q, 0, static_cast<Index>(order_.size()), best, best_d2);
        return best;
    }

private:
    static constexpr Index kLeaf = 8;

    void build(Index lo, Index hi) {
        if (hi - lo <= kLeaf) return;
        Vec3 mn = Vec3::Constant(std::numeric_limits<double>::infinity()), mx = -mn;
        for (Index i = lo; i < hi; ++i) {
            mn = mn.cwiseMin(p_[order_[i]]);
            mx = mx.cwiseMax(p_[order_[i]]);
        }
        int axis = 0;
        (mx - mn).maxCoeff(&axis);
        const Index mid = lo + (hi - lo) / 2;
        std::nth_element(order_.begin() + lo, order_.begin() + mid, order_.begin() + hi,
                         [&](Index a, Index b) { return p_[a][axis] < p_[b][axis]; });
        axis_[mid] = static_cast<char>(axis);
        build(lo, mid);
        build(mid + 1, hi);
    }

    void search(const Vec3& q, Index lo, Index hi, Index& best, double& best_d2) const {
        if (hi - lo <= kLeaf) {
            for (Index i = lo; i < hi; ++i) {
                const double d2 = (p_[order_[i]] - q).squaredNorm();
                if (d2 < best_d2) best_d2 = d2, best = order_[i];
            }
            return;
        }
        const Index mid = lo + (hi - lo) / 2;
        const Vec3& m = p_[order_[mid]];
        const double d2 = (m - q).squaredNorm();
        if (d2 < best_d2) best_d2 = d2, best = order_[mid];
        const double diff = q[axis_[mid]] - m[axis_[mid]];
        if (diff < 0) {
            search(q, lo, mid, best, best_d2);
            if (diff * diff < best_d2) search(q, mid + 1, hi, best, best_d2);
        } else {
            search(q, mid + 1, hi, best, best_d2);
            if (diff * diff < best_d2) search(q, lo, mid, best, best_d2);
        }
    }

    const std::vector<Vec3>& p_;
    std::vector<Index> order_;
    std::vector<char> axis_;
};

/// h(x) = min(h_wall(nearest wall node) + growth·|x − that node|, h_far); see the file comment.
class SizeField {
public:
    /// \p max_volume > 0 also caps h at the edge of the regular tet of that volume: TetGen's
    /// -m sizes are spacings too (a point closer to a vertex than its size is rejected), so
    /// without the cap -a could not be met where h is larger.
    SizeField(const SurfaceMesh& b, double growth, double max_volume) : growth_(growth) {
        // Mean incident edge length per node (interior edges counted from both faces, which
        // leaves the mean unchanged on a closed surface).
        node_size_.assign(b.points.size(), 0.0);
        std::vector<int> count(b.points.size(), 0);
        std::vector<char> wall(b.points.size(), 0);
        double far_sum = 0.0;
        long far_edges = 0;
        for (Index f = 0; f < b.num_faces(); ++f) {
            const bool is_far = b.patches[b.face_patch[f]].kind == PatchKind::Farfield;
            for (int i = 0; i < 3; ++i) {
                const Index u = b.face_node(f, i), v = b.face_node(f, (i + 1) % 3);
                const double l = (b.points[u] - b.points[v]).norm();
                node_size_[u] += l, node_size_[v] += l;
                ++count[u], ++count[v];
                if (is_far) far_sum += l, ++far_edges;
                if (!is_far) wall[u] = wall[v] = 1;
            }
        }
        for (std::size_t i = 0; i < node_size_.size(); ++i)
            if (count[i] > 0) node_size_[i] /= count[i];
        cap_ = far_edges > 0 ? far_sum / static_cast<double>(far_edges) : bounding_box(b.points).diagonal();
        if (max_volume > 0.0) volume_edge_ = std::cbrt(6.0 * std::sqrt(2.0) * max_volume);
        cap_ = std::min(cap_, volume_edge_);
        for (std::size_t i = 0; i < b.points.size(); ++i)
            if (wall[i]) wall_points_.push_back(b.points[i]), wall_size_.push_back(node_size_[i]);
        tree_ = std::make_unique<NearestPoint>(wall_points_);
    }

    /// Target edge length at boundary node \p i: its own mean edge length (capped by max_volume).
    double boundary_size(Index i) const { return std::min(node_size_[i], volume_edge_); }

    /// Target edge length at a point off the boundary.
    double operator()(const Vec3& x) const {
        const Index w = tree_->nearest(x);
        if (w == kNone) return cap_;
        return std::min(wall_size_[w] + growth_ * (x - wall_points_[w]).norm(), cap_);
    }

private:
    double growth_;
    double cap_ = 0.0;
    double volume_edge_ = std::numeric_limits<double>::infinity();
    std::vector<double> node_size_;
    std::vector<Vec3> wall_points_;
    std::vector<double> wall_size_;
    std::unique_ptr<NearestPoint> tree_;
};

/// TetGen -m sizes on \p io's points: boundary nodes (the first \p num_boundary) their own
/// size, the others h(x).
void set_sizes(tetgenio& io, Index num_boundary, const SizeField& h) {
    delete[] io.pointmtrlist;
    io.pointmtrlist = new REAL[static_cast<std::size_t>(io.numberofpoints)];
    io.numberofpointmtrs = 1;
    for (int i = 0; i < io.numberofpoints; ++i) {
        const Vec3 x(io.pointlist[3 * i], io.pointlist[3 * i + 1], io.pointlist[3 * i + 2]);
        const double edge = i < num_boundary ? h.boundary_size(i) : h(x);
        io.pointmtrlist[i] = kRadiusPerEdge * edge;
    }
}

// ---------------------------------------------------------------------------------------
// Result conversion and checks.

/// Sorted node triple: the key of a triangle regardless of orientation.
struct TriKey {
    std::array<Index, 3> v;
    bool operator==(const TriKey& o) const { return v == o.v; }
};
struct TriKeyHash {
    std::size_t operator()(const TriKey& k) const {
        std::size_t h = static_cast<std::size_t>(k.v[0]) * 0x9E3779B97F4A7C15ull;
        h ^= static_cast<std::size_t>(k.v[1]) + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
        h ^= static_cast<std::size_t>(k.v[2]) + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
        return h;
    }
};
TriKey tri_key(Index a, Index b, Index c) {
    std::array<Index, 3> v{a, b, c};
    std::sort(v.begin(), v.end());
    return {v};
}
using FaceIndex = std::unordered_map<TriKey, Index, TriKeyHash>;

/// Boundary triangle by node set; throws InputError on a repeated triangle.
FaceIndex index_faces(const SurfaceMesh& b) {
    FaceIndex face_of;
    face_of.reserve(static_cast<std::size_t>(b.num_faces()) * 2);
    for (Index f = 0; f < b.num_faces(); ++f) {
        const auto [it, fresh] = face_of.emplace(tri_key(b.face_node(f, 0), b.face_node(f, 1), b.face_node(f, 2)), f);
        if (!fresh)
            throw InputError("fill_with_tets: " + face_name(b, f) + " has the same nodes as " +
                             face_name(b, it->second) + "; remove duplicate triangles");
    }
    return face_of;
}

TetFill convert_and_check(const SurfaceMesh& b, const FaceIndex& face_of, const tetgenio& out, double boundary_volume) {
    const std::string where = "fill_with_tets: ";
    const Index nb = b.num_points();
    if (out.numberofpoints < nb || out.pointlist == nullptr)
        throw BackendError(where + "TetGen returned " + std::to_string(out.numberofpoints) + " points for " +
                           std::to_string(nb) +
                           " boundary nodes: it dropped or merged some (duplicate or unused nodes); merge "
                           "coincident nodes and remove unused ones first");
    if (out.numberoftetrahedra <= 0 || out.tetrahedronlist == nullptr)
        throw BackendError(where +
                           "TetGen produced no tetrahedra: a hole point lies in the region to fill (hole points "
                           "go inside the cavities, e.g. inside the body), or the boundary does not enclose a "
                           "region");
    if (out.numberofcorners != 4 || out.firstnumber != 0)
        throw BackendError(where + "TetGen returned tets of " + std::to_string(out.numberofcorners) +
                           " nodes numbered from " + std::to_string(out.firstnumber) + " (expected 4 from 0)");

    TetFill fill;
    fill.points.resize(static_cast<std::size_t>(out.numberofpoints));
    for (int i = 0; i < out.numberofpoints; ++i)
        fill.points[i] = Vec3(out.pointlist[3 * i], out.pointlist[3 * i + 1], out.pointlist[3 * i + 2]);
    for (Index i = 0; i < nb; ++i)
        if (fill.points[i] != b.points[i])
            throw BackendError(where + "TetGen moved or renumbered boundary node " + std::to_string(i) + " at " +
                               format_point(b.points[i]) + " (now " + format_point(fill.points[i]) +
                               "); merge coincident nodes and remove unused ones first");

    // TetGen 1.5 writes a tet (a, b, c, d) with its orient3d(a, b, c, d) < 0, i.e. d on the
    // side (a, b, c)'s right-hand normal points to: already Gmsh's order. The sign of every tet
    // is checked below rather than assumed.
    const Index np = static_cast<Index>(fill.points.size());
    fill.tets.resize(static_cast<std::size_t>(out.numberoftetrahedra));
    double tet_volume_sum = 0.0;
    for (int t = 0; t < out.numberoftetrahedra; ++t) {
        const int* v = out.tetrahedronlist + 4 * static_cast<std::size_t>(t);
        std::array<Index, 4> tet{v[0], v[1], v[2], v[3]};
        for (Index x : tet)
            if (x < 0 || x >= np)
                throw BackendError(where + "TetGen's tet " + std::to_string(t) + " uses node " + std::to_string(x) +
                                   " of " + std::to_string(np));
        const double vol =
            tet_volume(fill.points[tet[0]], fill.points[tet[1]], fill.points[tet[2]], fill.points[tet[3]]);
        if (!(vol > 0.0))
            throw BackendError(where + "TetGen's tet " + std::to_string(t) + " at " +
                               format_point(0.25 * (fill.points[tet[0]] + fill.points[tet[1]] + fill.points[tet[2]] +
                                                    fill.points[tet[3]])) +
                               " has volume " + format_number(vol, 3) + " (not positive)");
        tet_volume_sum += vol;
        fill.tets[t] = tet;
    }

    // Every boundary triangle must be a face of exactly one tet, which lies on the side the
    // triangle's normal points away from.
    std::vector<int> count(static_cast<std::size_t>(b.num_faces()), 0);
    std::vector<char> wrong_side(static_cast<std::size_t>(b.num_faces()), 0);
    static constexpr int kFace[4][4] = {{1, 2, 3, 0}, {0, 2, 3, 1}, {0, 1, 3, 2}, {0, 1, 2, 3}};  // 3 nodes + opposite
    for (const auto& tet : fill.tets) {
        for (const auto& lf : kFace) {
            if (tet[lf[0]] >= nb || tet[lf[1]] >= nb || tet[lf[2]] >= nb) continue;
            const auto it = face_of.find(tri_key(tet[lf[0]], tet[lf[1]], tet[lf[2]]));
            if (it == face_of.end()) continue;
            const Index f = it->second;
            ++count[f];
            const Vec3 &x0 = b.points[b.face_node(f, 0)], &x1 = b.points[b.face_node(f, 1)],
                       &x2 = b.points[b.face_node(f, 2)];
            if (tet_volume(x0, x1, x2, fill.points[tet[lf[3]]]) >= 0.0) wrong_side[f] = 1;
        }
    }
    for (Index f = 0; f < b.num_faces(); ++f) {
        if (count[f] == 0)
            throw BackendError(where + face_name(b, f) +
                               " is not a face of the tet mesh: TetGen split it (a Steiner point on the boundary) "
                               "or left its side empty (a hole point on the wrong side)");
        if (count[f] > 1)
            throw BackendError(where + face_name(b, f) + " is a face of " + std::to_string(count[f]) +
                               " tets: the region lies on both of its sides (an internal or unclosed boundary "
                               "part, or a missing hole point for a cavity)");
    }
    for (Index f = 0; f < b.num_faces(); ++f)
        if (wrong_side[f])
            throw InputError(where + face_name(b, f) +
                             " points into the region to fill; orient the boundary with normals out of the "
                             "region (outer boundary outward, cavity walls into the cavity)");

    // The tets fill exactly the enclosed region: no overlap, no gap.
    const double scale = std::max(std::abs(boundary_volume), std::numeric_limits<double>::min());
    if (std::abs(tet_volume_sum - boundary_volume) > 1e-9 * scale)
        throw BackendError(where + "the tets' volume " + format_number(tet_volume_sum, 12) +
                           " differs from the volume the boundary encloses " + format_number(boundary_volume, 12) +
                           ": TetGen's mesh overlaps or leaves gaps (a missing hole point?)");
    return fill;
}

}  // namespace

namespace {

/// The boundary of the background mesh: \p b with its farfield 1 % larger (about the
/// farfield's centroid). TetGen locates every point of the final mesh in the background
/// mesh by walking, and a walk that leaves the mesh falls back to a search of every tet; the
/// background mesh is therefore the whole convex hull (switch c, no holes: the cavities are
/// meshed too), and its farfield points lie just outside every point of the final mesh. Unchanged when the farfield
/// shares a point with another patch (it is not a separate closed surface then).
SurfaceMesh background_boundary(const SurfaceMesh& b) {
    std::vector<char> far(static_cast<std::size_t>(b.num_points()), 0), other(far.size(), 0);
    for (Index f = 0; f < b.num_faces(); ++f) {
        const bool ff = b.patches[static_cast<std::size_t>(b.face_patch[f])].kind == PatchKind::Farfield;
        for (const Index* v = b.face_begin(f); v != b.face_end(f); ++v)
            (ff ? far : other)[static_cast<std::size_t>(*v)] = 1;
    }
    Vec3 c = Vec3::Zero();
    Index n = 0;
    for (Index i = 0; i < b.num_points(); ++i) {
        if (far[static_cast<std::size_t>(i)] && other[static_cast<std::size_t>(i)]) return b;
        if (far[static_cast<std::size_t>(i)]) c += b.points[i], ++n;
    }
    if (n == 0) return b;
    c /= static_cast<double>(n);
    SurfaceMesh out = b;
    for (Index i = 0; i < b.num_points(); ++i)
        if (far[static_cast<std::size_t>(i)]) out.points[i] = c + 1.01 * (b.points[i] - c);
    return out;
}

}  // namespace

TetFill fill_with_tets(const SurfaceMesh& boundary, const std::vector<Vec3>& holes, const TetFillParams& params) {
    check_input(boundary, holes, params);
    const double volume = enclosed_volume(boundary);
    if (!(volume > 0.0))
        throw InputError("fill_with_tets: the boundary encloses a volume of " + format_number(volume, 6) +
                         " (not positive): its normals point into the region to fill; orient it with normals "
                         "out of the region (outer boundary outward, cavity walls into the cavity)");
    const FaceIndex face_of = index_faces(boundary);

    const bool sizing = params.refine && params.growth > 0.0;
    tetgenio in, out;
    set_plc(in, boundary, holes);
    if (!sizing) {
        run_tetgen(switches(params, false, false), in, out, nullptr);
        return convert_and_check(boundary, face_of, out, volume);
    }

    const SizeField h(boundary, params.growth, params.max_volume);
    if (!params.background_mesh) {  // sizes at the boundary points only, interpolated by TetGen
        set_sizes(in, boundary.num_points(), h);
        run_tetgen(switches(params, true, false), in, out, nullptr);
        return convert_and_check(boundary, face_of, out, volume);
    }
    tetgenio background;
    {
        tetgenio bg_in;
        set_plc(bg_in, background_boundary(boundary), {});  // convex, cavities included (c, no holes)
        run_tetgen(switches(params, false, true), bg_in, background, nullptr);
    }
    if (background.numberofpoints < boundary.num_points() || background.numberoftetrahedra <= 0)
        throw BackendError(
            "fill_with_tets: TetGen's background mesh for the sizing field is empty or lost boundary nodes; "
            "check the hole points (inside the cavities) and merge coincident nodes");
    set_sizes(background, boundary.num_points(), h);
    set_sizes(in, boundary.num_points(), h);
    run_tetgen(switches(params, true, false), in, out, &background);
    return convert_and_check(boundary, face_of, out, volume);
}

}  // namespace strata
