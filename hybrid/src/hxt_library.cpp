// Gmsh's HXT tetrahedral mesher, called directly; see hxt_library.h.
//
// Why not through Gmsh's model (a volume on discrete surfaces, Mesh.Algorithm3D = 10): Gmsh 4.8
// hands HXT the boundary's nodes in the order of their addresses in memory (a std::set of
// MVertex pointers in meshGRegionHxt.cpp), and HXT's output depends on that order, so the same
// boundary gave different tetrahedra from run to run even on one thread (3 runs of one
// 21k-triangle sphere in a box: 3 different meshes). HXT itself repeats its output for the same
// points in the same order and the same thread count (its `reproducible` option, which Gmsh
// also sets). Called directly, the points go in Strata's order and the output repeats.
//
// What is assumed of libgmsh: the HXT it carries is the one of Gmsh 4.8 (contrib/hxt of
// gmsh 4.8.4, Debian's libgmsh4.8: its SONAME pins the minor version, the header's version is
// checked at compile time below). Its C structures HXTMesh and HXTTetMeshOptions are declared
// here field for field as that version has them, since Debian installs no HXT header; its four
// entry points (hxtMeshCreate, hxtTetMesh, hxtMeshDelete, hxtSetMessageCallback) are exported by
// libgmsh. Its arrays are allocated with malloc and freed by hxtMeshDelete with free (HXT built
// without HXT_ALIGN_ALLOCATIONS, as Gmsh builds it), so the input arrays are malloc()ed here.
// tests/hybrid/test_tet_fill_hxt.cpp meshes boxes and spheres through it and checks every tet.
//
// HXT runs in this process (TetGen runs in a child): its failures are statuses, not crashes,
// and a child forked after OpenMP threads have run cannot use OpenMP safely.

#include "hxt_library.h"

#include <strata/core/bytes.h>
#include <strata/core/child_process.h>
#include <strata/core/error.h>

#include <gmsh.h>
#include <omp.h>

#include <csignal>
#include <cstdlib>
#include <exception>
#include <cstring>
#include <mutex>
#include <new>
#include <string>

#if GMSH_API_VERSION_MAJOR == 4 && GMSH_API_VERSION_MINOR == 8
#define STRATA_HXT_OF_GMSH_4_8 1
#else
#define STRATA_HXT_OF_GMSH_4_8 0
#endif

namespace {

// HXT 2020 as in Gmsh 4.8 (contrib/hxt/core/include/hxt_mesh.h, hxt_message.h,
// contrib/hxt/tetMesh/include/hxt_tetMesh.h): the layouts libgmsh was compiled with.
extern "C" {
using HXTStatus = int;  // an enum of int values: 0 OK, negative an error
constexpr std::uint32_t kGhostVertex = UINT32_MAX;
constexpr std::uint32_t kColorOut = UINT32_MAX;

struct HXTMesh {
    struct {
        double* coord;  // 4 per vertex: x, y, z, size
        std::uint32_t num;
        std::uint32_t size;
    } vertices;
    struct {
        std::uint32_t* node;
        std::uint64_t* neigh;
        std::uint32_t* color;
        std::uint16_t* flag;
        std::uint64_t num;
        std::uint64_t size;
    } tetrahedra;
    struct {
        std::uint32_t* node;
        std::uint32_t* color;
        std::uint64_t num;
        std::uint64_t size;
    } triangles;
    struct {
        std::uint32_t* node;
        std::uint32_t* color;
        std::uint64_t num;
        std::uint64_t size;
    } lines;
    struct {
        std::uint32_t* node;
        std::uint32_t* color;
        std::uint32_t num;
        std::uint32_t size;
    } points;
    struct {
        std::uint32_t numVolumes;
        std::uint32_t* numSurfacesPerVolume;
        std::uint32_t* surfacesPerVolume;
        std::uint32_t numSurfaces;
        std::uint32_t* numCurvesPerSurface;
        std::uint32_t* curvesPerSurface;
        std::uint32_t numCurves;
        std::uint32_t* endPointsOfCurves;
        std::uint32_t numPoints;
        std::uint32_t* points;
    } brep;
};

struct HXTMessage {
    const char* string;
    const char* func;
    const char* file;
    const char* line;
    int threadId;
    int numThreads;
    int level;  // 0 info, 1 debug, 2 warning, 3 error, 4 trace
};

struct HXTTetMeshOptions {
    int defaultThreads;
    int delaunayThreads;
    int improveThreads;
    int reproducible;
    int verbosity;
    int stat;
    int refine;
    int optimize;
    struct {
        double (*callback)(double*, double*, double*, double*, void*);
        void* userData;
        double min;
    } quality;
    struct {
        HXTStatus (*callback)(double* coord, std::uint32_t* volume, std::size_t n, void* userData);
        void* userData;
        double min;
        double max;
        double factor;
    } nodalSizes;
};

#if STRATA_HXT_OF_GMSH_4_8
HXTStatus hxtMeshCreate(HXTMesh** mesh);
HXTStatus hxtMeshDelete(HXTMesh** mesh);
HXTStatus hxtTetMesh(HXTMesh* mesh, HXTTetMeshOptions* options);
HXTStatus hxtSetMessageCallback(HXTStatus (*callback)(HXTMessage* msg));
#endif
}  // extern "C"

#if !STRATA_HXT_OF_GMSH_4_8  // another Gmsh: its HXT's layouts are not known here (run() refuses)
HXTStatus hxtMeshCreate(HXTMesh**) { return -1; }
HXTStatus hxtMeshDelete(HXTMesh**) { return -1; }
HXTStatus hxtTetMesh(HXTMesh*, HXTTetMeshOptions*) { return -1; }
HXTStatus hxtSetMessageCallback(HXTStatus (*)(HXTMessage*)) { return -1; }
#endif

}  // namespace

namespace strata::hxt {
namespace {

/// What HXT said while it ran: its warnings and errors (the last few), for the error message.
struct Messages {
    std::mutex mutex;
    std::string text;
};
Messages& messages() {
    static Messages m;
    return m;
}

HXTStatus keep_message(HXTMessage* msg) {
    if (msg == nullptr || msg->string == nullptr || msg->level < 2 || msg->level > 3) return 0;
    Messages& m = messages();
    std::lock_guard<std::mutex> lock(m.mutex);
    if (m.text.size() < 2000) m.text += (m.text.empty() ? "" : "; ") + std::string(msg->string);
    return 0;
}

std::mutex& hxt_mutex() {
    static std::mutex m;
    return m;
}

template <class T>
T* allocate(std::size_t n) {  // malloc()ed: hxtMeshDelete free()s it
    void* p = std::malloc(std::max<std::size_t>(n, 1) * sizeof(T));
    if (p == nullptr) throw std::bad_alloc();
    return static_cast<T*>(p);
}

/// The HXT mesh, deleted with hxtMeshDelete whatever happens.
struct MeshHandle {
    HXTMesh* mesh = nullptr;
    MeshHandle() {
        if (hxtMeshCreate(&mesh) != 0 || mesh == nullptr) throw std::bad_alloc();
    }
    ~MeshHandle() {
        if (mesh != nullptr) hxtMeshDelete(&mesh);
    }
    MeshHandle(const MeshHandle&) = delete;
    MeshHandle& operator=(const MeshHandle&) = delete;
};

void set_input(HXTMesh& m, const Input& in) {
    const std::size_t np = in.points.size(), nt = in.triangles.size();
    m.vertices.coord = allocate<double>(4 * np);
    m.vertices.num = m.vertices.size = static_cast<std::uint32_t>(np);
    for (std::size_t i = 0; i < np; ++i) {
        for (int k = 0; k < 3; ++k) m.vertices.coord[4 * i + k] = in.points[i][k];
        m.vertices.coord[4 * i + 3] = in.sizes[i];
    }
    m.triangles.node = allocate<std::uint32_t>(3 * nt);
    m.triangles.color = allocate<std::uint32_t>(nt);
    m.triangles.num = m.triangles.size = nt;
    for (std::size_t t = 0; t < nt; ++t) {
        for (int k = 0; k < 3; ++k) m.triangles.node[3 * t + k] = in.triangles[t][k];
        m.triangles.color[t] = in.triangle_surface[t];
    }
    m.brep.numVolumes = 1;
    m.brep.numSurfacesPerVolume = allocate<std::uint32_t>(1);
    m.brep.numSurfacesPerVolume[0] = static_cast<std::uint32_t>(in.surfaces.size());
    m.brep.surfacesPerVolume = allocate<std::uint32_t>(in.surfaces.size());
    std::memcpy(m.brep.surfacesPerVolume, in.surfaces.data(), in.surfaces.size() * sizeof(std::uint32_t));
}

/// The tets of volume 0 (HXT's colour for the one volume of the input's BRep) and the points.
Output take_output(const HXTMesh& m) {
    Output out;
    out.points.resize(m.vertices.num);
    for (std::size_t i = 0; i < out.points.size(); ++i)
        out.points[i] = {m.vertices.coord[4 * i], m.vertices.coord[4 * i + 1], m.vertices.coord[4 * i + 2]};
    for (std::uint64_t t = 0; t < m.tetrahedra.num; ++t) {
        const std::uint32_t* v = m.tetrahedra.node + 4 * t;
        if (v[3] == kGhostVertex || m.tetrahedra.color[t] != 0) continue;
        out.tets.push_back({v[0], v[1], v[2], v[3]});
    }
    return out;
}

/// The size function and what it threw (out of memory): HXT stops on the error status.
struct SizeCall {
    const SizeFunction* size;
    std::exception_ptr thrown;
};

HXTStatus call_size(double* coord, std::uint32_t* /*volume*/, std::size_t n, void* user) {
    auto& call = *static_cast<SizeCall*>(user);
    try {
        std::vector<double> xyz(3 * n), h(n);
        for (std::size_t i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) xyz[3 * i + k] = coord[4 * i + k];
        (*call.size)(xyz.data(), n, h.data());
        for (std::size_t i = 0; i < n; ++i) coord[4 * i + 3] = h[i];
        return 0;
    } catch (...) {
        call.thrown = std::current_exception();
        return -1;  // HXT_STATUS_ERROR: HXT stops and returns it
    }
}

/// Restores the calling thread's OpenMP thread count, which hxtTetMesh sets (for the run in this
/// process where fork() fails).
struct OmpThreadsScope {
    int saved = omp_get_max_threads();
    ~OmpThreadsScope() { omp_set_num_threads(saved); }
};

/// What the child sends: Done and the output, or Failed and why.
enum class Outcome : char { Done = 0, Failed = 1 };

std::string said() {
    std::lock_guard<std::mutex> lock(messages().mutex);
    return messages().text;
}

/// HXT ends the process with exit() where it fails inside a parallel loop ("cannot break OpenMP
/// region -> exiting"); in the child, this handler (registered last, so run first) sends what it
/// said and ends the child at once.
void send_failure_at_exit() {
    Bytes b;
    b.put(Outcome::Failed);
    b.put_string("it stopped the process inside a parallel loop" + (said().empty() ? "" : ": " + said()));
    child_exit(b.data, 2);
}

/// hxtTetMesh on \p in, its outcome into \p sent.
void mesh_into(const Input& in, const SizeFunction& size, const Options& options, Bytes& sent) {
    {
        std::lock_guard<std::mutex> m(messages().mutex);
        messages().text.clear();
    }
    hxtSetMessageCallback(keep_message);
    OmpThreadsScope threads;
    MeshHandle handle;
    set_input(*handle.mesh, in);
    HXTTetMeshOptions o{};
    o.defaultThreads = options.threads;
    o.reproducible = 1;
    o.refine = options.refine ? 1 : 0;
    SizeCall call{&size, nullptr};
    if (size) {
        o.nodalSizes.callback = call_size;
        o.nodalSizes.userData = &call;
    }
    const HXTStatus status = hxtTetMesh(handle.mesh, &o);
    if (call.thrown) std::rethrow_exception(call.thrown);
    if (status != 0) {
        sent.put(Outcome::Failed);
        sent.put_string("status " + std::to_string(status) + (said().empty() ? "" : ": " + said()));
        return;
    }
    const Output out = take_output(*handle.mesh);
    sent.put(Outcome::Done);
    sent.put_vector(out.points);
    sent.put_vector(out.tets);
}

/// mesh_into in a forked child (in this process where fork() fails), its bytes returned.
Bytes mesh_in_child(const Input& in, const SizeFunction& size, const Options& options, const Progress* progress) {
    Bytes b;
    b.what = "HXT's child process";
    const ChildResult child = run_in_child(
        [&](std::vector<char>& sent) {
            std::atexit(send_failure_at_exit);
            Bytes mine;
            mesh_into(in, size, options, mine);
            sent = std::move(mine.data);
        },
        progress, {.free_openmp_threads = true});
    if (!child.forked) {
        mesh_into(in, size, options, b);
        return b;
    }
    if (child.signal != 0) {
        const char* name = sigdescr_np(child.signal);
        throw BackendError("HXT crashed (signal " + std::to_string(child.signal) + ", " + (name ? name : "unknown") +
                           ")" + (child.signal == SIGKILL ? ", most likely killed by the system for want of memory" : ""));
    }
    if (child.sent.empty())
        throw BackendError("HXT's child process ended without its result (exit status " +
                           std::to_string(child.exit_status) + ")");
    b.data = child.sent;
    return b;
}

}  // namespace

bool available() { return STRATA_HXT_OF_GMSH_4_8 != 0; }

Output run(const Input& in, const SizeFunction& size, const Options& options, const Progress* progress) {
    if (!available())
        throw BackendError("HXT (--tets hxt) is called in the libgmsh of Gmsh 4.8 only and this build has Gmsh " +
                           std::string(GMSH_API_VERSION));
    std::lock_guard<std::mutex> lock(hxt_mutex());
    Bytes b = mesh_in_child(in, size, options, progress);
    if (b.get<Outcome>() != Outcome::Done) throw BackendError("HXT failed: " + b.get_string());
    Output out;
    out.points = b.get_vector<std::array<double, 3>>();
    out.tets = b.get_vector<std::array<std::uint32_t, 4>>();
    return out;
}

}  // namespace strata::hxt
