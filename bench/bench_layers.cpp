// bench_layers: wall time of the boundary-layer module on ~100k-face closed surfaces, for 1
// and 2 OpenMP threads, and a check that the thread count does not change the result.
//
// The work is fixed: 10 layers of exactly 10 point-Jacobi sweeps (sweeps = max_sweeps), so
// the times compare like with like. Surfaces: a cubed sphere of 6 × 130 × 130 quadrilaterals
// (101,400 faces) and the same construction at 6 × 91 × 91 with every quad split into two
// triangles (99,372 faces). Each case runs 3 times; the table shows the best.
//   bench_layers            (build in Release: scripts/bench.sh)

#include <strata/core/error.h>
#include <strata/geometry/intersections.h>
#include <strata/geometry/topology.h>
#include <strata/module/layers.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace strata;

/// Unit sphere from the six faces of a cube, n × n cells per face on the equiangular grid
/// (tan of evenly spaced angles: quads of nearly equal size), nodes shared across cube edges,
/// normals out. \p triangles splits each quad along alternating diagonals.
SurfaceMesh cubed_sphere(int n, bool triangles) {
    // Each face: normal axis N and in-plane axes U, V with U × V = N (outward orientation).
    const std::array<std::array<Vec3, 3>, 6> frames{{
        {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()},
        {-Vec3::UnitX(), Vec3::UnitZ(), Vec3::UnitY()},
        {Vec3::UnitY(), Vec3::UnitZ(), Vec3::UnitX()},
        {-Vec3::UnitY(), Vec3::UnitX(), Vec3::UnitZ()},
        {Vec3::UnitZ(), Vec3::UnitX(), Vec3::UnitY()},
        {-Vec3::UnitZ(), Vec3::UnitY(), Vec3::UnitX()},
    }};
    SurfaceMesh m;
    m.patches.push_back({"sphere", PatchKind::Wall});
    const double quarter = std::numbers::pi / 4.0;
    for (const auto& [N, U, V] : frames) {
        const Index base = m.num_points();
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                const double a = -quarter + 2.0 * quarter * i / n, b = -quarter + 2.0 * quarter * j / n;
                m.points.push_back((N + std::tan(a) * U + std::tan(b) * V).normalized());
            }
        auto id = [&](int i, int j) { return base + static_cast<Index>(j * (n + 1) + i); };
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const Index q[4] = {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
                if (!triangles) {
                    m.add_face(q, 4, 0);
                } else if ((i + j) % 2 == 0) {
                    m.add_face({q[0], q[1], q[2]}, 0);
                    m.add_face({q[0], q[2], q[3]}, 0);
                } else {
                    m.add_face({q[0], q[1], q[3]}, 0);
                    m.add_face({q[1], q[2], q[3]}, 0);
                }
            }
    }
    // The cube's edges are generated twice (once per adjacent face): merge them.
    return merge_coincident_nodes(m);
}

struct Run {
    double best_seconds = 0.0;
    LayerMesh result;
};

/// What the layer stage checks besides the marching: the proximity rays, and local stopping
/// (each column's cells judged after every layer, the steps closed); without stopping, only
/// the fold check every layer always had.
struct Checks {
    ProximityMode proximity = ProximityMode::Stop;  // the default
    bool stopping = true;                           // LayerParams::min_quality 0.2 (the default), else 0
};

Run time_extrusion(const SurfaceMesh& wall, int threads, int repeats, Checks checks = {}) {
    LayerParams p;
    p.proximity = checks.proximity;
    if (!checks.stopping) p.min_quality = 0.0, p.hold_back = false;
    p.distribution.layers = 10;
    p.distribution.kind = Distribution::Geometric;
    p.distribution.first_height = 1e-3;  // unit sphere
    p.distribution.growth = 1.2;
    p.sweeps = 10;
    p.max_sweeps = 10;  // fixed work: exactly ten sweeps per layer
    p.threads = threads;
    Run run;
    run.best_seconds = 1e300;
    for (int r = 0; r < repeats; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        LayerMesh lm = extrude_layers(wall, p);
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        run.best_seconds = std::min(run.best_seconds, s);
        run.result = std::move(lm);
    }
    return run;
}

/// Same points (bit for bit) and the same cells.
bool identical(const LayerMesh& a, const LayerMesh& b) {
    if (a.mesh.points.size() != b.mesh.points.size()) return false;
    for (std::size_t i = 0; i < a.mesh.points.size(); ++i)
        for (int c = 0; c < 3; ++c)
            if (a.mesh.points[i][c] != b.mesh.points[i][c]) return false;  // exact, on purpose
    return a.mesh.hexes == b.mesh.hexes && a.mesh.prisms == b.mesh.prisms;
}

}  // namespace

int main() {
    constexpr int kRepeats = 3;
    constexpr int kLayers = 10;
    try {
        std::printf("bench_layers: %d layers x 10 sweeps, best of %d runs, %u hardware threads\n\n", kLayers, kRepeats,
                    std::thread::hardware_concurrency());
        std::printf("%-26s %8s %8s %12s %14s %12s %12s %12s %12s\n", "surface", "faces", "threads", "best [s]",
                    "cells/s", "proximity", "stopping", "front test", "all checks");
        bool all_identical = true;
        std::vector<std::string> checks;
        for (const bool triangles : {false, true}) {
            const int n = triangles ? 91 : 130;
            const SurfaceMesh wall = cubed_sphere(n, triangles);
            const std::string name = "cubed sphere " + std::to_string(n) + (triangles ? " tris" : " quads");
            const double cells = static_cast<double>(wall.num_faces()) * kLayers;
            std::vector<Run> runs;
            for (const int threads : {1, 2}) {
                runs.push_back(time_extrusion(wall, threads, kRepeats));
                // What each check costs: the same run without the proximity rays (one AABB tree,
                // one ray per node), without local stopping, and without both (the marching and
                // the fold check alone, as before issue 9).
                const double t = runs.back().best_seconds;
                const double no_rays = time_extrusion(wall, threads, kRepeats, {ProximityMode::Off, true}).best_seconds;
                const double no_stop =
                    time_extrusion(wall, threads, kRepeats, {ProximityMode::Stop, false}).best_seconds;
                const double none = time_extrusion(wall, threads, kRepeats, {ProximityMode::Off, false}).best_seconds;
                // The front test build_hybrid_mesh runs before TetGen (exact self-intersection
                // test of the layer top), once, as a share of the layer stage.
                double front = 1e300;
                for (int r = 0; r < kRepeats; ++r) {
                    const auto t0 = std::chrono::steady_clock::now();
                    if (!self_intersections(runs.back().result.top, 1, threads).empty())
                        throw Error(name + ": the layer top intersects itself");
                    front =
                        std::min(front, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
                }
                std::printf("%-26s %8d %8d %12.3f %14.4g %11.1f%% %11.1f%% %11.1f%% %11.1f%%\n", name.c_str(),
                            static_cast<int>(wall.num_faces()), threads, t, cells / t, 100.0 * (t / no_rays - 1.0),
                            100.0 * (t / no_stop - 1.0), 100.0 * front / t, 100.0 * ((t + front) / none - 1.0));
            }
            const std::vector<Vec3>& top = runs[0].result.top.points;
            if (!(top.front().norm() > 1.0))
                throw Error(name + ": the layers went into the sphere (faces point inward)");
            const bool same = identical(runs[0].result, runs[1].result);
            all_identical = all_identical && same;
            char line[160];
            std::snprintf(line, sizeof line, "%s: 1 vs 2 threads %s (%zu points), speed-up %.2f", name.c_str(),
                          same ? "byte-identical" : "DIFFER", runs[0].result.mesh.points.size(),
                          runs[0].best_seconds / runs[1].best_seconds);
            checks.emplace_back(line);
        }
        std::printf("\n");
        for (const std::string& c : checks) std::printf("%s\n", c.c_str());
        return all_identical ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_layers: %s\n", e.what());
        return 1;
    }
}
