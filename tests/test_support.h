#pragma once
// Helpers shared by the test suites: data paths, scratch directories, tiny meshes.

#include <strata/core/face_geometry.h>
#include <strata/core/progress.h>
#include <strata/core/solver_checks.h>
#include <strata/core/surface_mesh.h>
#include <strata/core/volume_mesh.h>

#include <gtest/gtest.h>

#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <numbers>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace strata::test {

/// Progress that cancels once a stage has reported \p at (a fraction) or more: a writer
/// cancelled half-way or at its end.
struct CancelAt : Progress {
    double at;
    double last = 0.0;
    explicit CancelAt(double a) : at(a) {}
    void report(std::string_view, double fraction) override { last = fraction; }
    bool cancelled() const override { return last >= at; }
};

/// The bytes of the file at \p path (empty if it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

/// The names in \p dir, sorted (what a writer left behind).
inline std::vector<std::string> dir_entries(const std::filesystem::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

/// A file of examples/data (the geometries copied from ../shared/data).
inline std::string example_data(const std::string& name) {
    return std::string(STRATA_EXAMPLES_DATA) + "/" + name;
}
/// A file of tests/data (small inputs written for the tests).
inline std::string test_data(const std::string& name) {
    return std::string(STRATA_TEST_DATA) + "/" + name;
}

/// The message of the exception of type E that \p f throws; a test failure (and "") if it throws
/// none or another type.
template <class E, class F>
std::string error_message(F&& f) {
    try {
        f();
    } catch (const E& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "wrong exception type: " << e.what();
        return {};
    }
    ADD_FAILURE() << "no exception thrown";
    return {};
}

/// \p text contains every one of \p parts (a failure names the part and shows \p text).
inline void expect_contains(const std::string& text, const std::vector<std::string>& parts) {
    for (const std::string& p : parts) EXPECT_NE(text.find(p), std::string::npos) << "'" << p << "' not in: " << text;
}

/// \p f throws an E whose one-line message contains every one of \p parts.
template <class E, class F>
void expect_error(F&& f, const std::vector<std::string>& parts) {
    const std::string msg = error_message<E>(std::forward<F>(f));
    expect_contains(msg, parts);
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "message is not one line: " << msg;
}

/// \p a and \p b have the same cells, type by type, node for node.
inline void expect_same_cells(const VolumeMesh& a, const VolumeMesh& b) {
    EXPECT_EQ(a.tets, b.tets);
    EXPECT_EQ(a.pyramids, b.pyramids);
    EXPECT_EQ(a.prisms, b.prisms);
    EXPECT_EQ(a.hexes, b.hexes);
}

/// A thread that writes \p bytes into the named pipe \p fifo: it waits for a reader to open it.
inline std::thread fill_fifo(const std::string& fifo, std::string bytes) {
    return std::thread([fifo, bytes = std::move(bytes)] {
        std::FILE* f = std::fopen(fifo.c_str(), "wb");
        if (!f) return;
        std::fwrite(bytes.data(), 1, bytes.size(), f);
        std::fclose(f);
    });
}

/// \p program and \p args as the null-terminated argv of exec and posix_spawn, the strings held
/// here.
class Argv {
public:
    Argv(std::string program, const std::vector<std::string>& args) : words_{std::move(program)} {
        words_.insert(words_.end(), args.begin(), args.end());
        for (std::string& w : words_) pointers_.push_back(w.data());
        pointers_.push_back(nullptr);
    }
    Argv(const Argv&) = delete;
    Argv& operator=(const Argv&) = delete;
    char** data() { return pointers_.data(); }

private:
    std::vector<std::string> words_;
    std::vector<char*> pointers_;
};

/// A fresh empty directory for one test, removed when the object goes.
class ScratchDir {
public:
    explicit ScratchDir(const std::string& name) {
        // The pid keeps parallel ctest runs (-j) of the same test name apart.
        path_ = std::filesystem::temp_directory_path() / ("strata_test_" + name + "_" + std::to_string(::getpid()));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~ScratchDir() { std::filesystem::remove_all(path_); }
    std::string file(const std::string& name) const { return (path_ / name).string(); }
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

/// A small tmpfs mounted on a directory for one test (a full disk, a read-only file system),
/// unmounted when the object goes. Mounting needs root: mounted() is false otherwise, and the
/// test says so with GTEST_SKIP.
class SmallFilesystem {
public:
    /// \p options: tmpfs's options, e.g. "size=200k"; \p read_only: mounted read-only.
    SmallFilesystem(const std::filesystem::path& dir, const std::string& options, bool read_only = false) : dir_(dir) {
        std::filesystem::create_directories(dir_);
        const unsigned long flags = read_only ? MS_RDONLY : 0;
        mounted_ = ::geteuid() == 0 && ::mount("tmpfs", dir_.c_str(), "tmpfs", flags, options.c_str()) == 0;
    }
    ~SmallFilesystem() {
        if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
    }
    SmallFilesystem(const SmallFilesystem&) = delete;
    SmallFilesystem& operator=(const SmallFilesystem&) = delete;
    bool mounted() const { return mounted_; }
    std::string file(const std::string& name) const { return (dir_ / name).string(); }

private:
    std::filesystem::path dir_;
    bool mounted_ = false;
};

/// What a program that run_program ran did: its exit code (-1: ended by a signal) and output.
struct CliResult {
    int code = -1;
    std::string out, err;
};

/// Run \p program with \p args (already shell-quoted) in \p dir, under \p wrapper (a command
/// prefix such as "timeout 60 "), its standard input empty and its output captured (in files of
/// \p dir, removed afterwards).
/// \p feed: a shell command whose output is piped in instead.
inline CliResult run_program(const ScratchDir& dir, const std::string& program, const std::string& args,
                             const std::string& wrapper = "", const std::string& feed = "") {
    const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
    const std::string cmd = "cd '" + dir.path().string() + "' && " + (feed.empty() ? "" : feed + " | ") + wrapper +
                            "'" + program + "' " + args + " >'" + out + "' 2>'" + err + "'" +
                            (feed.empty() ? " </dev/null" : "");
    const int status = std::system(cmd.c_str());
    CliResult r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
}

/// Every undirected edge is used by exactly two faces (a closed manifold surface).
inline bool closed_manifold(const SurfaceMesh& m) {
    std::map<std::pair<Index, Index>, int> uses;
    for (Index f = 0; f < m.num_faces(); ++f)
        for (Index i = 0, n = m.face_size(f); i < n; ++i)
            ++uses[std::minmax(m.face_node(f, i), m.face_node(f, (i + 1) % n))];
    return std::all_of(uses.begin(), uses.end(), [](const auto& e) { return e.second == 2; });
}

/// Σ (1/3) centroid · area vector over the faces of \p m, the faces indexing \p points: the volume a
/// closed surface encloses, positive when its normals point out.
/// The largest first-layer aspect ratio (right_prism_aspect_ratio, OpenFOAM's) of a layer of
/// height \p h over \p m's wall faces: what CadParams::max_aspect_ratio holds down.
inline double worst_wall_aspect(const SurfaceMesh& m, double h) {
    double worst = 0.0;
    for (Index f = 0; f < m.num_faces(); ++f) {
        if (m.patches[static_cast<std::size_t>(m.face_patch[f])].kind != PatchKind::Wall) continue;
        std::array<Vec3, 4> c;
        for (Index i = 0; i < m.face_size(f); ++i)
            c[static_cast<std::size_t>(i)] = m.points[static_cast<std::size_t>(m.face_node(f, i))];
        worst = std::max(worst, right_prism_aspect_ratio(c.data(), static_cast<int>(m.face_size(f)), h));
    }
    return worst;
}

inline double enclosed_volume(const SurfaceMesh& m, const std::vector<Vec3>& points) {
    double v = 0.0;
    for (Index f = 0; f < m.num_faces(); ++f)
        v += face_centroid(m, points, f).dot(face_area_vector(m, points, f)) / 3.0;
    return v;
}
inline double enclosed_volume(const SurfaceMesh& m) {
    return enclosed_volume(m, m.points);
}

/// \p a and \p b as one surface: b's points, patches and faces after a's.
inline SurfaceMesh merged(SurfaceMesh a, const SurfaceMesh& b) {
    const Index n = a.num_points(), np = static_cast<Index>(a.patches.size());
    a.points.insert(a.points.end(), b.points.begin(), b.points.end());
    a.patches.insert(a.patches.end(), b.patches.begin(), b.patches.end());
    for (Index f = 0; f < b.num_faces(); ++f) {
        std::vector<Index> v(b.face_begin(f), b.face_end(f));
        for (Index& i : v) i += n;
        a.add_face(v.data(), static_cast<Index>(v.size()), b.face_patch[f] + np);
    }
    return a;
}

/// The eight corners of the unit cube moved by \p offset (node id = x + 2y + 4z) and one "wall"
/// patch, for a test to add the faces it needs.
inline SurfaceMesh cube_corners(const Vec3& offset = Vec3::Zero()) {
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 2; ++x) m.points.push_back(Vec3(x, y, z) + offset);
    return m;
}

/// A Möbius strip of 12 quads round the z axis (radius 3, width 1), patch "strip": it passes
/// check_surface but cannot be oriented. Nodes 2i (top) and 2i + 1 (bottom) at angle i.
inline SurfaceMesh moebius_strip() {
    SurfaceMesh m;
    m.patches.push_back({"strip", PatchKind::Wall});
    const int n = 12;
    for (int i = 0; i < n; ++i) {
        const double th = 2.0 * std::numbers::pi * i / n, tw = th / 2.0;
        const Vec3 c(3.0 * std::cos(th), 3.0 * std::sin(th), 0.0);
        const Vec3 d = std::cos(tw) * Vec3(std::cos(th), std::sin(th), 0.0) + std::sin(tw) * Vec3::UnitZ();
        m.points.push_back(c + 0.5 * d);
        m.points.push_back(c - 0.5 * d);
    }
    for (Index i = 0; i + 1 < n; ++i) m.add_face({2 * i, 2 * i + 1, 2 * i + 3, 2 * i + 2}, 0);
    m.add_face({2 * (n - 1), 2 * (n - 1) + 1, 0, 1}, 0);  // the half twist: bottom joins top
    return m;
}

/// Structured nx × ny grid of unit quads in the z = 0 plane, one "wall" patch, normals +z.
/// A torus round a circle of radius \p big whose tube is an ellipse of half-axes \p r (in the
/// torus's plane) and \p flat × \p r (across it), \p around × \p along squares, each split
/// into two triangles: locally a thin rod (flat 1) or a thin wing with round edges (flat < 1).
inline SurfaceMesh thin_torus(double big, double r, int around, int along, double flat = 1.0) {
    SurfaceMesh m;
    m.patches.push_back({"rod", PatchKind::Wall});
    for (int j = 0; j < along; ++j)
        for (int i = 0; i < around; ++i) {
            const double u = 2.0 * std::numbers::pi * j / along, v = 2.0 * std::numbers::pi * i / around;
            const double rad = big + r * std::cos(v);
            m.points.emplace_back(rad * std::cos(u), rad * std::sin(u), flat * r * std::sin(v));
        }
    auto at = [&](int i, int j) { return static_cast<Index>((j % along) * around + (i % around)); };
    for (int j = 0; j < along; ++j)
        for (int i = 0; i < around; ++i) {  // counter-clockwise seen from outside the tube
            const std::array<Index, 3> a{at(i, j), at(i, j + 1), at(i + 1, j + 1)};
            const std::array<Index, 3> b{at(i, j), at(i + 1, j + 1), at(i + 1, j)};
            m.add_face(a.data(), 3, 0);
            m.add_face(b.data(), 3, 0);
        }
    return m;
}

inline SurfaceMesh quad_grid(int nx, int ny, double h = 1.0) {
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) m.points.emplace_back(i * h, j * h, 0.0);
    auto id = [nx](int i, int j) { return static_cast<Index>(j * (nx + 1) + i); };
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) m.add_face({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)}, 0);
    return m;
}

/// \p q with each quad split into two triangles of its patch, along its first diagonal (0-2),
/// or with \p alternate every other quad along the other (1-3) so that nodes get valences 4, 6
/// and 8 on a grid; triangles kept as they are.
inline SurfaceMesh split_into_triangles(const SurfaceMesh& q, bool alternate) {
    SurfaceMesh t;
    t.points = q.points;
    t.patches = q.patches;
    for (Index f = 0; f < q.num_faces(); ++f) {
        const Index* v = q.face_begin(f);
        if (q.face_size(f) != 4) {
            t.add_face(v, q.face_size(f), q.face_patch[f]);
            continue;
        }
        const bool other = alternate && f % 2 == 1;
        const std::array<Index, 6> halves = other ? std::array<Index, 6>{v[0], v[1], v[3], v[1], v[2], v[3]}
                                                  : std::array<Index, 6>{v[0], v[1], v[2], v[0], v[2], v[3]};
        t.add_face(halves.data(), 3, q.face_patch[f]);
        t.add_face(halves.data() + 3, 3, q.face_patch[f]);
    }
    return t;
}

/// A blade along y (0..1, \p ny segments): its section a triangle of apex angle \p apex_deg
/// with the sharp edge at x = 1 and the blunt base at x = 0, closed by triangular end caps;
/// triangles, normals out of the blade.
inline SurfaceMesh blade(int ny, double apex_deg) {
    const double t = std::tan(0.5 * apex_deg * std::numbers::pi / 180.0);
    SurfaceMesh m;
    m.patches = {{"blade", PatchKind::Wall}};
    for (int j = 0; j <= ny; ++j) {
        const double y = static_cast<double>(j) / ny;
        m.points.push_back(Vec3(0.0, y, -t));   // 3j: base, lower
        m.points.push_back(Vec3(0.0, y, t));    // 3j + 1: base, upper
        m.points.push_back(Vec3(1.0, y, 0.0));  // 3j + 2: the sharp edge
    }
    auto quad = [&](Index a, Index b, Index c, Index d) {
        m.add_face({a, b, c}, 0);
        m.add_face({a, c, d}, 0);
    };
    for (Index j = 0; j < ny; ++j) {
        const Index bl = 3 * j, bu = bl + 1, a = bl + 2, n = 3;
        quad(bu, a, a + n, bu + n);    // upper
        quad(bl, bl + n, a + n, a);    // lower
        quad(bl, bu, bu + n, bl + n);  // base
    }
    const Index e = 3 * static_cast<Index>(ny);
    m.add_face({0, 2, 1}, 0);
    m.add_face({e, e + 1, e + 2}, 0);
    return m;
}

/// A .geo (OpenCASCADE) written into \p dir: the box [0,1]² × [0,height] as a fluid domain
/// whose floor (z = 0) is the wall, the four sides symmetry planes ("symmetry_x0", "_x1",
/// "_y0", "_y1") and the lid the farfield, meshed with triangles of size \p size. Layers
/// grown from the floor end on the four sides and march up the box's vertical edges.
inline std::string box_domain_geo(const ScratchDir& dir, double height, double size) {
    const std::string path = dir.file("box_domain.geo");
    std::ofstream(path) << "SetFactory(\"OpenCASCADE\");\n"
                        << "Box(1) = {0, 0, 0, 1, 1, " << height << "};\n"
                        << "Physical Surface(\"symmetry_x0\") = {1};\nPhysical Surface(\"symmetry_x1\") = {2};\n"
                        << "Physical Surface(\"symmetry_y0\") = {3};\nPhysical Surface(\"symmetry_y1\") = {4};\n"
                        << "Physical Surface(\"floor\") = {5};\nPhysical Surface(\"farfield_lid\") = {6};\n"
                        << "Mesh.MeshSizeMax = " << size << ";\n";
    return path;
}

}  // namespace strata::test
