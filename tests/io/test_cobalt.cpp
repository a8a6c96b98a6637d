// write_cobalt: boxes of every cell type are written, read back with an independent reader
// (cobalt_reader.h) and checked face by face: 1-based ids, every face once, patch numbers and
// the .bc map, face normals from c1 to c2 (Newell's method, against cell centroids), header
// maxima, exact coordinates, the cells rebuilt from the faces alone, and validate_mesh on them.
// Errors: topology problems and unwritable targets throw and leave nothing behind.

#include "cobalt_reader.h"
#include "core/box_mesh.h"
#include "test_support.h"

#include <strata/core/error.h>
#include <strata/core/validate.h>
#include <strata/io/cobalt.h>

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace strata;
using strata::test::BoxMesh;
using strata::test::CobaltGrid;
using strata::test::CobaltPatch;
using strata::test::CubeSplit;
using strata::test::RebuiltMesh;
using strata::test::ScratchDir;

namespace {

using strata::test::slurp;

std::vector<Index> sorted_nodes(std::vector<Index> v) {
    std::sort(v.begin(), v.end());
    return v;
}

/// Same cyclic order (a rotation of one another).
bool same_cycle(const std::vector<Index>& a, const std::vector<Index>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t r = 0; r < a.size(); ++r) {
        bool ok = true;
        for (std::size_t i = 0; i < a.size() && ok; ++i) ok = a[i] == b[(i + r) % b.size()];
        if (ok) return true;
    }
    return false;
}

/// Newell's normal of a polygon (not normalised).
Vec3 newell(const std::vector<Vec3>& p) {
    Vec3 n = Vec3::Zero();
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec3& a = p[i];
        const Vec3& b = p[(i + 1) % p.size()];
        n.x() += (a.y() - b.y()) * (a.z() + b.z());
        n.y() += (a.z() - b.z()) * (a.x() + b.x());
        n.z() += (a.x() - b.x()) * (a.y() + b.y());
    }
    return n;
}

std::vector<Index> face_of(const CobaltGrid& g, std::int64_t f) {
    std::vector<Index> v;
    for (std::int64_t k = 0; k < g.face_size(f); ++k) v.push_back(g.node(f, k));
    return v;
}

template <std::size_t N>
std::vector<std::vector<Index>> node_sets(const std::vector<std::array<Index, N>>& cells) {
    std::vector<std::vector<Index>> s;
    for (const auto& c : cells) s.push_back(sorted_nodes(std::vector<Index>(c.begin(), c.end())));
    return s;
}

struct Expected {
    int max_nodes_per_face;
    int max_faces_per_cell;
};

/// Write \p mesh to \p path and check every property of the file against \p mesh; returns the
/// mesh rebuilt from the file.
RebuiltMesh write_and_check(const VolumeMesh& mesh, const std::string& path, Expected expected) {
    EXPECT_TRUE(validate_mesh(mesh).ok()) << "the test mesh itself is invalid";
    write_cobalt(mesh, path);
    const CobaltGrid g = test::read_cobalt(path);
    const std::vector<CobaltPatch> bc = test::read_cobalt_bc(path + ".bc");
    const SurfaceMesh& b = mesh.boundary;

    // Header.
    EXPECT_EQ(g.ndim, 3);
    EXPECT_EQ(g.nzones, 1);
    EXPECT_EQ(g.nnodes, static_cast<std::int64_t>(mesh.points.size()));
    EXPECT_EQ(g.ncells, mesh.num_cells());
    EXPECT_EQ(g.max_nodes_per_face, expected.max_nodes_per_face);
    EXPECT_EQ(g.max_faces_per_cell, expected.max_faces_per_cell);
    std::int64_t cell_faces = 4 * static_cast<std::int64_t>(mesh.tets.size()) +
                              5 * static_cast<std::int64_t>(mesh.pyramids.size() + mesh.prisms.size()) +
                              6 * static_cast<std::int64_t>(mesh.hexes.size());
    EXPECT_EQ(g.nfaces, (cell_faces + b.num_faces()) / 2) << "every face exactly once";

    // Patches: only those with faces, in patch-table order, names and kinds in the .bc file.
    std::vector<Index> used;
    for (std::size_t p = 0; p < b.patches.size(); ++p)
        if (std::count(b.face_patch.begin(), b.face_patch.end(), static_cast<Index>(p)))
            used.push_back(static_cast<Index>(p));
    EXPECT_EQ(g.npatches, static_cast<std::int64_t>(used.size()));
    EXPECT_EQ(bc.size(), used.size());
    for (std::size_t k = 0; k < std::min(bc.size(), used.size()); ++k) {
        EXPECT_EQ(bc[k].number, static_cast<std::int64_t>(k + 1));
        EXPECT_EQ(bc[k].name, b.patches[used[k]].name);
        EXPECT_EQ(bc[k].kind, std::string(to_string(b.patches[used[k]].kind)));
    }

    // Coordinates round-trip bit for bit.
    EXPECT_EQ(g.points.size(), mesh.points.size());
    for (std::size_t i = 0; i < std::min(g.points.size(), mesh.points.size()); ++i)
        for (int d = 0; d < 3; ++d) EXPECT_EQ(g.points[i][d], mesh.points[i][d]) << "node " << i << " coordinate " << d;

    // Ids are 1-based and span exactly 1..count.
    EXPECT_EQ(*std::min_element(g.face_nodes.begin(), g.face_nodes.end()), 1);
    EXPECT_EQ(*std::max_element(g.face_nodes.begin(), g.face_nodes.end()), g.nnodes);
    std::int64_t cmin = std::numeric_limits<std::int64_t>::max(), cmax = 0;
    std::vector<int> seen(static_cast<std::size_t>(g.ncells), 0);
    for (std::int64_t f = 0; f < g.nfaces; ++f)
        for (std::int64_t c : {g.c1[f], g.c2[f]})
            if (c > 0) {
                cmin = std::min(cmin, c);
                cmax = std::max(cmax, c);
                ++seen[c - 1];
            }
    EXPECT_EQ(cmin, 1);
    EXPECT_EQ(cmax, g.ncells);
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 0), 0) << "every cell has faces";

    // Deterministic order: by first cell.
    EXPECT_TRUE(std::is_sorted(g.c1.begin(), g.c1.end()));

    // Every face once; boundary faces match the mesh's, with their patch and orientation.
    std::map<std::vector<Index>, Index> boundary_by_set;
    for (Index f = 0; f < b.num_faces(); ++f)
        boundary_by_set[sorted_nodes(std::vector<Index>(b.face_begin(f), b.face_end(f)))] = f;
    std::set<std::vector<Index>> sets;
    const RebuiltMesh r = test::rebuild_mesh(g, bc);
    std::int64_t nboundary = 0;
    for (std::int64_t f = 0; f < g.nfaces; ++f) {
        const std::vector<Index> v = face_of(g, f);
        EXPECT_TRUE(sets.insert(sorted_nodes(v)).second) << "face " << f + 1 << " listed twice";
        std::vector<Vec3> x;
        Vec3 fc = Vec3::Zero();
        for (Index n : v) {
            x.push_back(g.points[n]);
            fc += g.points[n];
        }
        fc /= static_cast<double>(v.size());
        const Vec3 normal = newell(x);
        const Vec3& from = r.cell_centroid[g.c1[f] - 1];
        if (g.c2[f] > 0) {
            EXPECT_NE(g.c1[f], g.c2[f]) << "face " << f + 1;
            EXPECT_GT(normal.dot(r.cell_centroid[g.c2[f] - 1] - from), 0.0)
                << "interior face " << f + 1 << " does not point from c1 to c2";
            EXPECT_EQ(boundary_by_set.count(sorted_nodes(v)), 0u) << "interior face " << f + 1 << " is a boundary face";
        } else {
            ++nboundary;
            EXPECT_GE(-g.c2[f], 1);
            EXPECT_LE(-g.c2[f], g.npatches);
            EXPECT_GT(normal.dot(fc - from), 0.0) << "boundary face " << f + 1 << " does not point out of the domain";
            const auto it = boundary_by_set.find(sorted_nodes(v));
            if (it == boundary_by_set.end()) {
                ADD_FAILURE() << "boundary face " << f + 1 << " is no boundary face of the mesh";
                continue;
            }
            const Index p = b.face_patch[it->second];
            EXPECT_EQ(bc[-g.c2[f] - 1].name, b.patches[p].name) << "boundary face " << f + 1;
            EXPECT_TRUE(same_cycle(v, std::vector<Index>(b.face_begin(it->second), b.face_end(it->second))))
                << "boundary face " << f + 1 << " oriented unlike the mesh's boundary face";
        }
    }
    EXPECT_EQ(nboundary, b.num_faces());

    // Cells rebuilt from the faces: numbered tets, pyramids, prisms, hexes in mesh order.
    EXPECT_EQ(r.mesh.tets.size(), mesh.tets.size());
    EXPECT_EQ(r.mesh.pyramids.size(), mesh.pyramids.size());
    EXPECT_EQ(r.mesh.prisms.size(), mesh.prisms.size());
    EXPECT_EQ(r.mesh.hexes.size(), mesh.hexes.size());
    EXPECT_TRUE(std::is_sorted(r.cell_type.begin(), r.cell_type.end(),
                               [](CellType a, CellType c) { return static_cast<int>(a) < static_cast<int>(c); }));
    EXPECT_EQ(node_sets(r.mesh.tets), node_sets(mesh.tets));
    EXPECT_EQ(node_sets(r.mesh.pyramids), node_sets(mesh.pyramids));
    EXPECT_EQ(node_sets(r.mesh.prisms), node_sets(mesh.prisms));
    EXPECT_EQ(node_sets(r.mesh.hexes), node_sets(mesh.hexes));

    const ValidationReport report = validate_mesh(r.mesh);
    std::string problems;
    for (const std::string& s : report.problems) problems += "\n  " + s;
    EXPECT_TRUE(report.ok()) << problems;
    EXPECT_EQ(report.cells, mesh.num_cells());
    return r;
}

// ---------------------------------------------------------------------------------------
// Meshes of each kind: header maxima, every property above.

TEST(WriteCobalt, TetsOnly) {
    ScratchDir dir("cobalt_tets");
    BoxMesh box(2, 2, 1);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) box.set(i, j, 0, CubeSplit::Kuhn);
    const RebuiltMesh r = write_and_check(box.build(), dir.file("tets.cgr"), {3, 4});
    EXPECT_EQ(r.mesh.tets.size(), 24u);
}

TEST(WriteCobalt, HexAndPrisms) {
    ScratchDir dir("cobalt_hex_prisms");
    BoxMesh box(2, 1, 1);
    box.set(1, 0, 0, CubeSplit::Prisms);
    const RebuiltMesh r = write_and_check(box.build(), dir.file("box.cgr"), {4, 6});
    EXPECT_EQ(r.mesh.hexes.size(), 1u);
    EXPECT_EQ(r.mesh.prisms.size(), 2u);
    // Numbering: prisms before hexes, so the hex is cell 3.
    EXPECT_EQ(r.cell_type[2], CellType::Hex);
}

TEST(WriteCobalt, HexesOnly) {
    ScratchDir dir("cobalt_hexes");
    const VolumeMesh m = BoxMesh(2, 2, 2).build();
    write_and_check(m, dir.file("hexes.cgr"), {4, 6});
}

TEST(WriteCobalt, PrismsOnly) {
    ScratchDir dir("cobalt_prisms");
    BoxMesh box(1, 1, 2);
    box.set(0, 0, 0, CubeSplit::Prisms);
    box.set(0, 0, 1, CubeSplit::Prisms);
    write_and_check(box.build(), dir.file("prisms.cog"), {4, 5});
}

TEST(WriteCobalt, SixPyramidsAroundTheCentre) {
    ScratchDir dir("cobalt_pyramids");
    BoxMesh box(1, 1, 1);
    box.set(0, 0, 0, CubeSplit::Pyramids);
    const VolumeMesh m = box.build();
    ASSERT_EQ(m.pyramids.size(), 6u);
    const RebuiltMesh r = write_and_check(m, dir.file("pyramids.cgr"), {4, 5});
    EXPECT_EQ(r.mesh.pyramids.size(), 6u);
}

TEST(WriteCobalt, PyramidsAndTets) {
    ScratchDir dir("cobalt_pyramids_tets");
    BoxMesh box(2, 1, 1);
    box.set(0, 0, 0, CubeSplit::Kuhn);
    box.set(1, 0, 0, CubeSplit::PyramidsTets, 0);
    write_and_check(box.build(), dir.file("pt.cgr"), {4, 5});
}

/// Every cell type and junction, odd spacing and jittered nodes: coordinates need all 17 digits.
TEST(WriteCobalt, MixedBoxRoundTripsExactly) {
    ScratchDir dir("cobalt_mixed");
    VolumeMesh m = test::mixed_box(0.1, Vec3(1.0 / 3.0, -2.0 / 7.0, 1e-9 * std::numbers::pi)).build();
    for (std::size_t i = 0; i < m.points.size(); ++i)
        m.points[i] +=
            1e-3 * Vec3(std::sin(12.9898 * static_cast<double>(i)), std::cos(78.233 * static_cast<double>(i)),
                        std::sin(3.7 * static_cast<double>(i) + 1.0));
    ASSERT_TRUE(validate_mesh(m).ok());
    ASSERT_FALSE(m.tets.empty());
    ASSERT_FALSE(m.pyramids.empty());
    ASSERT_FALSE(m.prisms.empty());
    ASSERT_FALSE(m.hexes.empty());
    write_and_check(m, dir.file("mixed.cgr"), {4, 6});
}

TEST(WriteCobalt, ByteIdenticalReruns) {
    ScratchDir dir("cobalt_rerun");
    const VolumeMesh m = test::mixed_box().build();
    write_cobalt(m, dir.file("a.cgr"));
    write_cobalt(m, dir.file("b.cgr"));
    EXPECT_EQ(slurp(dir.file("a.cgr")), slurp(dir.file("b.cgr")));
    const std::string bc_a = slurp(dir.file("a.cgr.bc")), bc_b = slurp(dir.file("b.cgr.bc"));
    // The comment names the grid file; the patch lines are identical.
    EXPECT_EQ(bc_a.substr(bc_a.find('\n')), bc_b.substr(bc_b.find('\n')));
    EXPECT_EQ(test::dir_entries(dir.path()), (std::vector<std::string>{"a.cgr", "a.cgr.bc", "b.cgr", "b.cgr.bc"}));
}

/// Patches without faces are not numbered; numbers follow the patch table; names with spaces
/// and every kind survive the .bc file.
TEST(WriteCobalt, PatchNumbersSkipEmptyPatches) {
    ScratchDir dir("cobalt_patches");
    VolumeMesh m = BoxMesh(2, 1, 1).build();
    // Table: unused, xmin, xmax, unused, ymin, ymax, zmin, zmax, unused.
    std::vector<Patch> table{{"never used", PatchKind::Other}};
    std::vector<Index> remap;
    for (std::size_t p = 0; p < m.boundary.patches.size(); ++p) {
        if (p == 2) table.push_back({"also unused", PatchKind::Wall});
        remap.push_back(static_cast<Index>(table.size()));
        table.push_back(m.boundary.patches[p]);
    }
    table.push_back({"unused at the end", PatchKind::Farfield});
    table[remap[0]] = {"inlet  plane", PatchKind::Farfield};
    table[remap[2]] = {"sym", PatchKind::Symmetry};
    table[remap[5]] = {"top", PatchKind::Other};
    m.boundary.patches = table;
    for (Index& p : m.boundary.face_patch) p = remap[p];
    ASSERT_TRUE(validate_mesh(m).ok());

    write_and_check(m, dir.file("patches.cgr"), {4, 6});
    const CobaltGrid g = test::read_cobalt(dir.file("patches.cgr"));
    EXPECT_EQ(g.npatches, 6);
    const auto bc = test::read_cobalt_bc(dir.file("patches.cgr.bc"));
    ASSERT_EQ(bc.size(), 6u);
    EXPECT_EQ(bc[0].name, "inlet  plane");
    EXPECT_EQ(bc[0].kind, "farfield");
    EXPECT_EQ(bc[2].name, "sym");
    EXPECT_EQ(bc[2].kind, "symmetry");
    EXPECT_EQ(bc[5].name, "top");
    EXPECT_EQ(bc[5].kind, "other");
    // The x− side (one cube face) is "inlet  plane", patch 1.
    int on_inlet = 0;
    for (std::int64_t f = 0; f < g.nfaces; ++f) {
        if (g.c2[f] != -1) continue;
        ++on_inlet;
        for (std::int64_t k = 0; k < g.face_size(f); ++k) EXPECT_EQ(g.points[g.node(f, k)].x(), 0.0);
    }
    EXPECT_EQ(on_inlet, 1);
    // The .bc file explains itself.
    EXPECT_EQ(slurp(dir.file("patches.cgr.bc")).rfind("# ", 0), 0u);
}

// ---------------------------------------------------------------------------------------
// Errors: TopologyError naming the face, InputError for unwritable targets; nothing written,
// an existing file left as it was.

/// Expect \p f to throw E whose message contains \p text, leaving \p dir with \p entries.
template <class E, class F>
void expect_error(F&& f, const std::string& text, const std::filesystem::path& dir,
                  const std::vector<std::string>& entries) {
    try {
        f();
        ADD_FAILURE() << "no exception; expected one containing '" << text << "'";
    } catch (const E& e) {
        EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
    EXPECT_EQ(test::dir_entries(dir), entries) << "files left behind";
}

TEST(WriteCobalt, FaceSharedByThreeCells) {
    ScratchDir dir("cobalt_three");
    VolumeMesh m = BoxMesh(2, 1, 1).build();
    // A third hexahedron on the x = 1 face (nodes 1, 4, 7, 10) shared by the two cubes.
    for (int k = 0; k < 4; ++k) m.points.emplace_back(5.0 + k, 5.0, 5.0);
    m.hexes.push_back({1, 12, 13, 4, 7, 14, 15, 10});
    expect_error<TopologyError>([&] { write_cobalt(m, dir.file("bad.cgr")); }, "(1 4 10 7) is shared by 3 cells",
                                dir.path(), {});
}

TEST(WriteCobalt, HoleIsNamed) {
    ScratchDir dir("cobalt_hole");
    VolumeMesh m = BoxMesh(1, 1, 1).build();
    // Keep an existing grid to check it survives the failed write.
    write_cobalt(m, dir.file("mesh.cgr"));
    const std::string before = slurp(dir.file("mesh.cgr")), bc_before = slurp(dir.file("mesh.cgr.bc"));
    m.boundary.face_offsets.pop_back();
    m.boundary.face_nodes.resize(static_cast<std::size_t>(m.boundary.face_offsets.back()));
    m.boundary.face_patch.pop_back();
    expect_error<TopologyError>([&] { write_cobalt(m, dir.file("mesh.cgr")); },
                                "of hexahedron 0 at (0.5, 0.5, 0.5) has no neighbouring cell", dir.path(),
                                {"mesh.cgr", "mesh.cgr.bc"});
    EXPECT_EQ(slurp(dir.file("mesh.cgr")), before);
    EXPECT_EQ(slurp(dir.file("mesh.cgr.bc")), bc_before);
}

TEST(WriteCobalt, BoundaryFaceOnInteriorFace) {
    ScratchDir dir("cobalt_bnd_interior");
    VolumeMesh m = BoxMesh(2, 1, 1).build();
    m.boundary.add_face({1, 4, 10, 7}, 0);
    expect_error<TopologyError>([&] { write_cobalt(m, dir.file("bad.cgr")); }, "is an interior face between",
                                dir.path(), {});
}

TEST(WriteCobalt, StrayAndDuplicatedBoundaryFaces) {
    ScratchDir dir("cobalt_stray");
    VolumeMesh m = BoxMesh(1, 1, 1).build();
    VolumeMesh stray = m;
    stray.boundary.add_face({0, 5, 6}, 1);
    expect_error<TopologyError>([&] { write_cobalt(stray, dir.file("bad.cgr")); }, "is no face of any cell", dir.path(),
                                {});
    VolumeMesh twice = m;
    twice.boundary.add_face(m.boundary.face_begin(0), 4, 2);
    expect_error<TopologyError>([&] { write_cobalt(twice, dir.file("bad.cgr")); }, "times in the boundary", dir.path(),
                                {});
}

TEST(WriteCobalt, OverlappingCellsAreRejected) {
    ScratchDir dir("cobalt_overlap");
    VolumeMesh m = BoxMesh(2, 1, 1).build();
    // The second cube mirrored in y: same node sets, every face listed inward, so the x = 1
    // face has the same orientation in both cells and the boundary faces point into the cell.
    // The writer names the first problem in node order (face_match.h).
    auto& h = m.hexes[1];
    ASSERT_EQ(h, (std::array<Index, 8>{1, 2, 5, 4, 7, 8, 11, 10}));
    h = {4, 5, 2, 1, 10, 11, 8, 7};
    expect_error<TopologyError>([&] { write_cobalt(m, dir.file("bad.cgr")); }, "into hexahedron 1 at", dir.path(), {});
}

TEST(WriteCobalt, MalformedInput) {
    ScratchDir dir("cobalt_malformed");
    const VolumeMesh good = BoxMesh(1, 1, 1).build();
    VolumeMesh bad_node = good;
    bad_node.hexes[0][3] = 99;
    expect_error<InputError>([&] { write_cobalt(bad_node, dir.file("m.cgr")); }, "uses node 99", dir.path(), {});
    VolumeMesh nan = good;
    nan.points[2].y() = std::nan("");
    expect_error<TopologyError>([&] { write_cobalt(nan, dir.file("m.cgr")); }, "node 2 has a non-finite", dir.path(),
                                {});
    VolumeMesh bad_patch = good;
    bad_patch.boundary.face_patch[0] = 6;
    expect_error<InputError>([&] { write_cobalt(bad_patch, dir.file("m.cgr")); }, "is on patch 6", dir.path(), {});
    expect_error<InputError>([&] { write_cobalt(VolumeMesh{}, dir.file("m.cgr")); }, "no cells", dir.path(), {});
}

TEST(WriteCobalt, UnwritableTargets) {
    ScratchDir dir("cobalt_unwritable");
    const VolumeMesh m = BoxMesh(1, 1, 1).build();
    // Missing directory.
    expect_error<InputError>([&] { write_cobalt(m, dir.file("missing/mesh.cgr")); }, "does not exist", dir.path(), {});
    // A regular file as the directory.
    { std::ofstream(dir.file("plain")) << "x"; }
    expect_error<InputError>([&] { write_cobalt(m, dir.file("plain/mesh.cgr")); }, "plain", dir.path(), {"plain"});
    // The target (or its .bc) is a directory.
    std::filesystem::create_directory(dir.file("grid.cgr"));
    expect_error<InputError>([&] { write_cobalt(m, dir.file("grid.cgr")); }, "is a directory", dir.path(),
                             {"grid.cgr", "plain"});
    std::filesystem::create_directory(dir.file("other.cgr.bc"));
    expect_error<InputError>([&] { write_cobalt(m, dir.file("other.cgr")); }, "is a directory", dir.path(),
                             {"grid.cgr", "other.cgr.bc", "plain"});
    EXPECT_TRUE(std::filesystem::is_empty(dir.file("grid.cgr")));
    EXPECT_TRUE(std::filesystem::is_empty(dir.file("other.cgr.bc")));
    // A read-only directory (root writes anyway, so only checked for other users).
    if (::geteuid() != 0) {
        const std::string ro = dir.file("readonly");
        std::filesystem::create_directory(ro);
        ::chmod(ro.c_str(), 0555);
        expect_error<InputError>([&] { write_cobalt(m, ro + "/mesh.cgr"); }, "cannot write", ro, {});
        ::chmod(ro.c_str(), 0755);
    }
}

}  // namespace
