// to_polymesh and write_polymesh: a tiny mesh with one cell of each type (hexahedron, prism
// beside it, pyramid on top of it, tetrahedron on a side of the pyramid) converted and checked
// face by face against geometry computed here (face counts, owner < neighbour, upper-triangular
// order, every face pointing out of its owner, closed cells, patch ranges); the files' headers
// and boundary as OpenFOAM writes them; byte-identical reruns and thread counts; the directory
// replaced whole, and nothing left behind by a bad path, a bad mesh or a cancellation.
// (OpenFOAM's own checkMesh on whole meshes: tests/openfoam/check_polymesh.sh.)

#include "core/box_mesh.h"
#include "test_support.h"

#include <strata/core/cell_faces.h>
#include <strata/core/error.h>
#include <strata/core/validate.h>
#include <strata/io/openfoam.h>
#include <strata/io/write_volume.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace strata;
using strata::test::CancelAt;
using strata::test::ScratchDir;
namespace fs = std::filesystem;

namespace {

using strata::test::slurp;

/// One cell of each type, all valid and conforming: the hexahedron [0,1]³, a prism on its x = 1
/// side (a wedge out to x = 2 along the floor), a pyramid on its top (apex at z = 1.5) and a
/// tetrahedron on the pyramid's y = 0 side. Boundary faces are every cell face on no other cell,
/// on patch "floor" (wall) where z = 0, "mirror plane" (symmetry) on the tetrahedron, and
/// "far" (farfield) elsewhere; an empty patch "unused" too.
VolumeMesh one_of_each() {
    VolumeMesh m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1},       {1, 0, 1},
                {1, 1, 1}, {0, 1, 1}, {2, 0, 0}, {2, 1, 0}, {0.5, 0.5, 1.5}, {0.5, -0.8, 1.3}};
    m.hexes.push_back({0, 1, 2, 3, 4, 5, 6, 7});
    // Bottom triangle 1-8-5 at y = 0, top 2-9-6 at y = 1 (each above the other along +y).
    m.prisms.push_back({1, 5, 8, 2, 6, 9});
    m.pyramids.push_back({4, 5, 6, 7, 10});
    m.tets.push_back({4, 5, 10, 11});
    m.boundary.patches = {{"floor", PatchKind::Wall},
                          {"mirror plane", PatchKind::Symmetry},
                          {"far", PatchKind::Farfield},
                          {"unused", PatchKind::Other}};
    // Boundary: the cell faces whose node set occurs once.
    struct Face {
        CellType type;
        std::array<Index, 4> v;
        int size;
    };
    std::vector<Face> all;
    std::map<std::array<Index, 4>, int> uses;
    for (CellType t : kCellTypes)
        for (std::size_t i = 0; i < m.num_cells(t); ++i) {
            const CellFaceTable& ft = cell_faces(t);
            for (int f = 0; f < ft.count; ++f) {
                Face face{t, {}, ft.size[f]};
                for (int k = 0; k < ft.size[f]; ++k) face.v[k] = m.cell(t, i)[ft.node[f][k]];
                ++uses[sorted_face_key(face.v.data(), face.size)];
                all.push_back(face);
            }
        }
    for (const Face& face : all) {
        if (uses[sorted_face_key(face.v.data(), face.size)] != 1) continue;
        bool floor = true;
        for (int k = 0; k < face.size; ++k) floor = floor && m.points[face.v[k]].z() == 0.0;
        m.boundary.add_face(face.v.data(), face.size, floor ? 0 : face.type == CellType::Tet ? 1 : 2);
    }
    return m;
}

Vec3 centroid(const VolumeMesh& m, const Index* v, std::size_t n) {
    Vec3 c = Vec3::Zero();
    for (std::size_t k = 0; k < n; ++k) c += m.points[v[k]];
    return c / static_cast<double>(n);
}

/// Area vector of a polygon (Newell), from the node coordinates alone.
Vec3 area_vector(const VolumeMesh& m, const Index* v, std::size_t n) {
    Vec3 a = Vec3::Zero();
    for (std::size_t k = 0; k < n; ++k) a += m.points[v[k]].cross(m.points[v[(k + 1) % n]]);
    return 0.5 * a;
}

std::vector<Vec3> cell_centroids(const VolumeMesh& m) {
    std::vector<Vec3> c;
    for (CellType t : kCellTypes)
        for (std::size_t i = 0; i < m.num_cells(t); ++i)
            c.push_back(centroid(m, m.cell(t, i), static_cast<std::size_t>(cell_corners(t))));
    return c;
}

/// The PolyMesh's face \p f: its nodes.
std::vector<Index> face(const PolyMesh& pm, std::int64_t f) {
    return {pm.face_nodes.begin() + pm.face_offsets[static_cast<std::size_t>(f)],
            pm.face_nodes.begin() + pm.face_offsets[static_cast<std::size_t>(f) + 1]};
}

/// Every property OpenFOAM asks of a polyMesh that does not need its code: owner < neighbour,
/// upper-triangular order, faces pointing out of their owner (against the centroids), each
/// cell closed (its outward area vectors sum to zero) with a positive divergence volume, patches
/// back to back after the internal faces.
void expect_sound_polymesh(const VolumeMesh& m, const PolyMesh& pm) {
    const std::vector<Vec3> cc = cell_centroids(m);
    ASSERT_EQ(pm.num_cells, static_cast<std::int64_t>(cc.size()));
    ASSERT_EQ(static_cast<std::int64_t>(pm.owner.size()), pm.num_faces());
    const std::int64_t ni = pm.num_internal_faces();
    for (std::int64_t f = 0; f < ni; ++f) {
        const auto fi = static_cast<std::size_t>(f);
        EXPECT_LT(pm.owner[fi], pm.neighbour[fi]) << "face " << f;
        if (f > 0) {
            const bool ordered = pm.owner[fi - 1] < pm.owner[fi] ||
                                 (pm.owner[fi - 1] == pm.owner[fi] && pm.neighbour[fi - 1] < pm.neighbour[fi]);
            EXPECT_TRUE(ordered) << "face " << f << " is not in upper-triangular order";
        }
    }
    std::vector<Vec3> closure(cc.size(), Vec3::Zero());
    std::vector<double> volume(cc.size(), 0.0);
    for (std::int64_t f = 0; f < pm.num_faces(); ++f) {
        const std::vector<Index> v = face(pm, f);
        ASSERT_TRUE(v.size() == 3 || v.size() == 4);
        const Vec3 a = area_vector(m, v.data(), v.size()), c = centroid(m, v.data(), v.size());
        const auto o = static_cast<std::size_t>(pm.owner[static_cast<std::size_t>(f)]);
        EXPECT_GT(a.dot(c - cc[o]), 0.0) << "face " << f << " points into its owner " << o;
        closure[o] += a;
        volume[o] += a.dot(c) / 3.0;
        if (f < ni) {
            const auto n = static_cast<std::size_t>(pm.neighbour[static_cast<std::size_t>(f)]);
            EXPECT_LT(a.dot(c - cc[n]), 0.0) << "face " << f << " points out of its neighbour " << n;
            closure[n] -= a;
            volume[n] -= a.dot(c) / 3.0;
        }
    }
    for (std::size_t c = 0; c < cc.size(); ++c) {
        EXPECT_LT(closure[c].norm(), 1e-12) << "cell " << c << " is not closed";
        EXPECT_GT(volume[c], 0.0) << "cell " << c;
    }
    std::int64_t next = ni;
    for (const PolyPatch& p : pm.patches) {
        EXPECT_EQ(p.start, next) << p.name;
        EXPECT_GT(p.size, 0) << p.name;
        next += p.size;
    }
    EXPECT_EQ(next, pm.num_faces());
}

}  // namespace

TEST(ToPolyMesh, OneCellOfEachType) {
    const VolumeMesh m = one_of_each();
    const ValidationReport v = validate_mesh(m);
    ASSERT_TRUE(v.ok()) << v.problems.front();
    const PolyMesh pm = to_polymesh(m);
    expect_sound_polymesh(m, pm);
    // Cells in CellNumbering order: tet 0, pyramid 1, prism 2, hex 3. Faces: hex 6, prism 5,
    // pyramid 5, tet 4 = 20 cell faces; 3 shared (hex-prism, hex-pyramid, pyramid-tet) → 17.
    EXPECT_EQ(pm.num_cells, 4);
    EXPECT_EQ(pm.num_faces(), 17);
    ASSERT_EQ(pm.num_internal_faces(), 3);
    // Internal (0 1, 1 3, 2 3), floor (prism, hex), mirror plane (tet), far (pyramid, prism, hex).
    EXPECT_EQ(pm.owner, (std::vector<Index>{0, 1, 2, 2, 3, 0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3}));
    EXPECT_EQ(pm.neighbour, (std::vector<Index>{1, 3, 3}));
    // Internal faces: tet-pyramid a triangle, pyramid-hex and prism-hex quads.
    EXPECT_EQ(face(pm, 0).size(), 3u);
    EXPECT_EQ(face(pm, 1).size(), 4u);
    EXPECT_EQ(face(pm, 2).size(), 4u);
    std::size_t tris = 0, quads = 0;
    for (std::int64_t f = 0; f < pm.num_faces(); ++f) (face(pm, f).size() == 3 ? tris : quads) += 1;
    EXPECT_EQ(tris, 4u + 4u + 2u - 1u);   // tet 4, pyramid sides 4, prism ends 2; one shared
    EXPECT_EQ(quads, 6u + 3u + 1u - 2u);  // hex 6, prism sides 3, pyramid base 1; two shared
    // Patches: the empty one is left out, the names are OpenFOAM words.
    ASSERT_EQ(pm.patches.size(), 3u);
    EXPECT_EQ(pm.patches[0].name, "floor");
    EXPECT_EQ(pm.patches[0].size, 2);  // the hexahedron's and the prism's floor
    EXPECT_EQ(pm.patches[1].name, "mirror_plane");
    EXPECT_EQ(pm.patches[1].kind, PatchKind::Symmetry);
    EXPECT_EQ(pm.patches[1].size, 3);
    EXPECT_EQ(pm.patches[2].name, "far");
    EXPECT_EQ(pm.patches[2].size, 9);  // 3 each of the pyramid, the prism and the hexahedron
    // Each patch's faces by owner.
    for (const PolyPatch& p : pm.patches)
        for (std::int64_t f = p.start + 1; f < p.start + p.size; ++f)
            EXPECT_LE(pm.owner[static_cast<std::size_t>(f - 1)], pm.owner[static_cast<std::size_t>(f)]);
}

/// Every cell type in a box (the arrangement tests/io/test_write_volume.cpp validates): hexahedra,
/// six pyramids, two prisms in a row, six tetrahedra on top of the prisms.
VolumeMesh every_type_box() {
    test::BoxMesh box(3, 1, 2);
    box.set(1, 0, 0, test::CubeSplit::Pyramids);
    box.set(2, 0, 0, test::CubeSplit::Prisms);
    box.set(2, 0, 1, test::CubeSplit::Kuhn);
    for (int i = 0; i < 2; ++i) box.remove(i, 0, 1);
    return box.build();
}

TEST(ToPolyMesh, BoxOfEveryCellTypeAndThreadCounts) {
    const VolumeMesh m = every_type_box();
    ASSERT_TRUE(validate_mesh(m).ok());
    const PolyMesh one = to_polymesh(m, 1), two = to_polymesh(m, 2);
    expect_sound_polymesh(m, one);
    EXPECT_EQ(one.face_nodes, two.face_nodes);
    EXPECT_EQ(one.owner, two.owner);
    EXPECT_EQ(one.neighbour, two.neighbour);
    EXPECT_EQ(one.patches.size(), 6u);
    // Every cell face is listed once: interior faces twice over the cells, boundary faces once.
    std::int64_t slots = 0;
    for (CellType t : kCellTypes) slots += static_cast<std::int64_t>(m.num_cells(t)) * cell_faces(t).count;
    EXPECT_EQ(2 * one.num_internal_faces() + (one.num_faces() - one.num_internal_faces()), slots);
    EXPECT_EQ(one.num_faces() - one.num_internal_faces(), m.boundary.num_faces());
}

TEST(ToPolyMesh, TopologyProblemsAreNamed) {
    VolumeMesh m = one_of_each();
    m.boundary.face_offsets.pop_back();  // drop the last boundary face: a hole
    m.boundary.face_nodes.resize(static_cast<std::size_t>(m.boundary.face_offsets.back()));
    m.boundary.face_patch.pop_back();
    test::expect_error<TopologyError>([&] { to_polymesh(m); }, {"polyMesh", "has no neighbouring cell"});
}

TEST(FoamPatchNames, WordsThatOpenFoamReads) {
    EXPECT_EQ(foam_patch_names({"wall", "part (fin2.stl)", "", "2nd", "a/b;c", "wall", "wall_2", "x  "}),
              (std::vector<std::string>{"wall", "part_fin2.stl", "patch_3", "patch_2nd", "a_b_c", "wall_2", "wall_2_2",
                                        "x"}));
    EXPECT_EQ(openfoam_patch_type(PatchKind::Wall), "wall");
    EXPECT_EQ(openfoam_patch_type(PatchKind::Symmetry), "symmetry");
    EXPECT_EQ(openfoam_patch_type(PatchKind::Farfield), "patch");
    EXPECT_EQ(openfoam_patch_type(PatchKind::Other), "patch");
}

TEST(WritePolyMesh, FilesAsOpenFoamWritesThem) {
    ScratchDir dir("polymesh_files");
    const VolumeMesh m = one_of_each();
    const std::string path = dir.file("polyMesh");
    write_volume(m, path);  // by name, through write_volume
    EXPECT_EQ(test::dir_entries(dir.path()), std::vector<std::string>{"polyMesh"});
    EXPECT_EQ(test::dir_entries(path), (std::vector<std::string>{"boundary", "faces", "neighbour", "owner", "points"}));

    const std::string owner = slurp(path + "/owner");
    test::expect_contains(owner, {"    class       labelList;\n"
                                  "    note        \"nPoints:12  nCells:4  nFaces:17  nInternalFaces:3\";\n"
                                  "    location    \"constant/polyMesh\";\n"
                                  "    object      owner;\n",
                                  "\n\n\n17\n(\n0\n1\n2\n2\n3\n0\n"});
    const std::string neighbour = slurp(path + "/neighbour");
    EXPECT_NE(neighbour.find("object      neighbour;"), std::string::npos);
    EXPECT_NE(neighbour.find("\n3\n(\n1\n3\n3\n)\n"), std::string::npos) << neighbour;
    const std::string points = slurp(path + "/points");
    EXPECT_NE(points.find("class       vectorField;"), std::string::npos);
    test::expect_contains(points, {"\n12\n(\n(0 0 0)\n(1 0 0)\n", "(0.5 -0.8 1.3)\n)\n"});
    const std::string faces = slurp(path + "/faces");
    EXPECT_NE(faces.find("class       faceList;"), std::string::npos);
    EXPECT_NE(faces.find("\n17\n(\n3("), std::string::npos) << faces;

    const std::string boundary = slurp(path + "/boundary");
    EXPECT_NE(boundary.find("class       polyBoundaryMesh;"), std::string::npos);
    EXPECT_NE(boundary.find("3\n(\n"
                            "    floor\n    {\n        type            wall;\n        inGroups        1(wall);\n"
                            "        nFaces          2;\n        startFace       3;\n    }\n"
                            "    mirror_plane\n    {\n        type            symmetry;\n"
                            "        inGroups        1(symmetry);\n        nFaces          3;\n"
                            "        startFace       5;\n    }\n"
                            "    far\n    {\n        type            patch;\n        nFaces          9;\n"
                            "        startFace       8;\n    }\n)\n"),
              std::string::npos)
        << boundary;
    for (const std::string& text : {owner, neighbour, points, faces, boundary}) {
        EXPECT_EQ(text.rfind("/*", 0), 0u);
        EXPECT_NE(text.find("FoamFile\n{\n    version     2.0;\n    format      ascii;\n"), std::string::npos);
        EXPECT_EQ(text.substr(text.size() - 3), "//\n");
    }
}

TEST(WritePolyMesh, ByteIdenticalRerunsAndTheDirectoryReplacedWhole) {
    ScratchDir dir("polymesh_rerun");
    const VolumeMesh m = every_type_box();
    const std::string path = dir.file("polyMesh");
    write_polymesh(m, path);
    std::map<std::string, std::string> first;
    for (const std::string& f : test::dir_entries(path)) first[f] = slurp(path + "/" + f);
    // An existing polyMesh with other files (as gmshToFoam leaves: sets/, zones) is replaced whole.
    fs::create_directories(path + "/sets");
    std::ofstream(path + "/sets/old") << "stale";
    std::ofstream(path + "/cellZones") << "stale";
    write_polymesh(m, path + "/");  // a trailing slash names the same directory
    EXPECT_EQ(test::dir_entries(dir.path()), std::vector<std::string>{"polyMesh"});
    ASSERT_EQ(test::dir_entries(path), (std::vector<std::string>{"boundary", "faces", "neighbour", "owner", "points"}));
    for (const auto& [f, text] : first) EXPECT_TRUE(slurp(path + "/" + f) == text) << f;
}

TEST(WritePolyMesh, BadPathsBadMeshesAndCancellingLeaveNothing) {
    ScratchDir dir("polymesh_bad");
    const VolumeMesh m = one_of_each();
    test::expect_error<InputError>([&] { write_polymesh(m, dir.file("no_such_case/constant/polyMesh")); },
                                   {"no_such_case/constant", "does not exist"});
    std::ofstream(dir.file("polyMesh")) << "a file";
    test::expect_error<InputError>([&] { write_polymesh(m, dir.file("polyMesh")); }, {"polyMesh", "is a file"});
    fs::remove(dir.file("polyMesh"));

    VolumeMesh bad = m;
    bad.prisms[0][2] = 99;
    test::expect_error<InputError>([&] { write_polymesh(bad, dir.file("polyMesh")); }, {"polyMesh", "99"});
    VolumeMesh overlapping = m;
    overlapping.hexes.push_back(overlapping.hexes[0]);
    test::expect_error<TopologyError>([&] { write_polymesh(overlapping, dir.file("polyMesh")); },
                                      {"cannot write OpenFOAM polyMesh", "hexahedron 1"});
    for (double at : {0.5, 1.0}) {
        CancelAt cancel(at);
        EXPECT_THROW(write_polymesh(m, dir.file("polyMesh"), &cancel), Cancelled) << at;
    }
    EXPECT_TRUE(test::dir_entries(dir.path()).empty());

    // A failed write leaves an existing polyMesh as it was.
    write_polymesh(m, dir.file("polyMesh"));
    const std::string before = slurp(dir.file("polyMesh/faces"));
    CancelAt cancel(1.0);
    EXPECT_THROW(write_polymesh(test::BoxMesh(1, 1, 1).build(), dir.file("polyMesh"), &cancel), Cancelled);
    EXPECT_EQ(test::dir_entries(dir.path()), std::vector<std::string>{"polyMesh"});
    EXPECT_TRUE(slurp(dir.file("polyMesh/faces")) == before);
}
