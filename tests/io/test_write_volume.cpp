#include "core/box_mesh.h"
#include "test_support.h"

#include <strata/core/error.h>
#include <strata/core/validate.h>
#include <strata/io/read_surface.h>
#include <strata/io/write_surface.h>
#include <strata/io/write_volume.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace strata;
using strata::test::CubeSplit;
using strata::test::expect_same_cells;
using strata::test::ScratchDir;

namespace {

/// Every cell type: hexahedron | six pyramids | two prisms in a row, six tetrahedra on top of
/// the prisms (their triangles meet the prisms' ends).
VolumeMesh all_types_mesh(double h = 0.1, Vec3 origin = Vec3(0.3, -0.25, 1e-3)) {
    test::BoxMesh box(3, 1, 2, h, origin);
    box.set(1, 0, 0, CubeSplit::Pyramids);
    box.set(2, 0, 0, CubeSplit::Prisms);
    box.set(2, 0, 1, CubeSplit::Kuhn);
    for (int i = 0; i < 2; ++i) box.remove(i, 0, 1);
    VolumeMesh m = box.build();
    m.boundary.patches[0].name = "inlet wall";  // a name with a space survives too
    return m;
}

/// Coordinates as a user's file has them: 12 significant digits.
VolumeMesh decimal(VolumeMesh m) {
    for (Vec3& x : m.points)
        for (int d = 0; d < 3; ++d) {
            char buf[32];
            std::snprintf(buf, sizeof buf, "%.12g", x[d]);
            x[d] = std::strtod(buf, nullptr);
        }
    return m;
}

/// Boundary faces as a sorted list of (patch, nodes): MSH 2.2 does not keep the face order.
std::vector<std::vector<Index>> face_set(const SurfaceMesh& b) {
    std::vector<std::vector<Index>> faces;
    for (Index f = 0; f < b.num_faces(); ++f) {
        std::vector<Index> row{b.face_patch[f]};
        row.insert(row.end(), b.face_begin(f), b.face_end(f));
        faces.push_back(row);
    }
    std::sort(faces.begin(), faces.end());
    return faces;
}

std::vector<std::string> files_in(const std::filesystem::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::string read_text(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST(WriteVolume, AllTypesMeshIsValid) {
    const VolumeMesh m = all_types_mesh();
    EXPECT_EQ(m.hexes.size(), 1u);
    EXPECT_EQ(m.pyramids.size(), 6u);
    EXPECT_EQ(m.prisms.size(), 2u);
    EXPECT_EQ(m.tets.size(), 6u);
    const ValidationReport r = validate_mesh(m);
    EXPECT_TRUE(r.ok()) << (r.problems.empty() ? "" : r.problems.front());
}

TEST(WriteVolume, Msh41RoundTripIsExact) {
    ScratchDir dir("write_volume_41");
    const VolumeMesh m = decimal(all_types_mesh());
    const std::string path = dir.file("mesh.msh");
    write_volume(m, path);
    EXPECT_NE(read_text(path).find("$MeshFormat\n4.1 0 8"), std::string::npos);

    const VolumeMesh r = read_volume_msh(path);
    EXPECT_EQ(r.tets.size(), 6u);
    EXPECT_EQ(r.pyramids.size(), 6u);
    EXPECT_EQ(r.prisms.size(), 2u);
    EXPECT_EQ(r.hexes.size(), 1u);
    ASSERT_EQ(r.points.size(), m.points.size());
    for (std::size_t i = 0; i < m.points.size(); ++i) EXPECT_EQ(r.points[i], m.points[i]) << "node " << i;
    // Same cells and boundary faces in the same order (MSH 4.1 keeps element tags).
    expect_same_cells(m, r);
    EXPECT_EQ(r.boundary.face_offsets, m.boundary.face_offsets);
    EXPECT_EQ(r.boundary.face_nodes, m.boundary.face_nodes);
    ASSERT_EQ(r.boundary.patches.size(), 6u);
    for (std::size_t p = 0; p < 6; ++p) EXPECT_EQ(r.boundary.patches[p].name, m.boundary.patches[p].name);
    EXPECT_EQ(r.boundary.face_patch, m.boundary.face_patch);
    const ValidationReport v = validate_mesh(r);
    EXPECT_TRUE(v.ok()) << (v.problems.empty() ? "" : v.problems.front());
    EXPECT_EQ(files_in(dir.path()), std::vector<std::string>{"mesh.msh"});
}

TEST(WriteVolume, Msh22RoundTrip) {
    ScratchDir dir("write_volume_22");
    const VolumeMesh m = test::mixed_box(0.5).build();
    const std::string path = dir.file("mesh.msh");
    write_volume(m, path, 2.2);
    EXPECT_NE(read_text(path).find("$MeshFormat\n2.2 0 8"), std::string::npos);

    const VolumeMesh r = read_volume_msh(path);
    EXPECT_EQ(r.tets.size(), m.tets.size());
    EXPECT_EQ(r.pyramids.size(), m.pyramids.size());
    EXPECT_EQ(r.prisms.size(), m.prisms.size());
    EXPECT_EQ(r.hexes.size(), m.hexes.size());
    ASSERT_EQ(r.points.size(), m.points.size());
    for (std::size_t i = 0; i < m.points.size(); ++i) EXPECT_EQ(r.points[i], m.points[i]);
    // MSH 2.2 renumbers elements: cells keep their order within a type, boundary faces come
    // back grouped by patch.
    expect_same_cells(m, r);
    ASSERT_EQ(r.boundary.patches.size(), 6u);
    EXPECT_EQ(r.boundary.patches[0].name, "xmin");
    EXPECT_EQ(r.boundary.patches[5].name, "zmax");
    EXPECT_EQ(face_set(r.boundary), face_set(m.boundary));
    const ValidationReport v = validate_mesh(r);
    EXPECT_TRUE(v.ok()) << (v.problems.empty() ? "" : v.problems.front());
    EXPECT_NEAR(v.cell_volume, 27 * 0.125, 1e-12);
}

TEST(WriteVolume, Msh41CoordinatesComeBackBitForBit) {
    // Strata writes ASCII MSH 4.1 itself, each coordinate in the shortest form that reads back
    // to the same double (Gmsh's own writer kept 16 digits: a few units in the last place off).
    ScratchDir dir("write_volume_digits");
    const VolumeMesh m = all_types_mesh(1.0 / 7.0, Vec3(1.0 / 3.0, -2.0 / 7.0, 1e5 / 3.0));
    const std::string path = dir.file("mesh.msh");
    write_volume(m, path);
    const VolumeMesh r = read_volume_msh(path);
    ASSERT_EQ(r.points.size(), m.points.size());
    for (std::size_t i = 0; i < m.points.size(); ++i) EXPECT_EQ(r.points[i], m.points[i]) << "node " << i;
    EXPECT_TRUE(validate_mesh(r).ok());
}

TEST(WriteVolume, Msh41ByStrataReadsBackAsGmshsOwnBinary) {
    // The ASCII file Strata writes and the binary one Gmsh writes from the same model read back
    // to the same mesh: nodes, cells, faces in order, patches (two sharing a name: one group; one
    // with no faces: none).
    ScratchDir dir("write_volume_same");
    VolumeMesh m = all_types_mesh(1.0 / 7.0, Vec3(1.0 / 3.0, -2.0 / 7.0, 1e5 / 3.0));
    m.boundary.patches[3].name = m.boundary.patches[1].name;
    m.boundary.patches.push_back({"unused", PatchKind::Wall});
    const std::string ascii = dir.file("ascii.msh"), binary = dir.file("binary.msh");
    write_volume(m, ascii);
    write_volume(m, binary, MshFormat(4.1, true));
    const VolumeMesh a = read_volume_msh(ascii), b = read_volume_msh(binary);
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(a.tets, b.tets);
    EXPECT_EQ(a.pyramids, b.pyramids);
    EXPECT_EQ(a.prisms, b.prisms);
    EXPECT_EQ(a.hexes, b.hexes);
    EXPECT_EQ(a.boundary.face_offsets, b.boundary.face_offsets);
    EXPECT_EQ(a.boundary.face_nodes, b.boundary.face_nodes);
    EXPECT_EQ(a.boundary.face_patch, b.boundary.face_patch);
    ASSERT_EQ(a.boundary.patches.size(), b.boundary.patches.size());
    for (std::size_t p = 0; p < a.boundary.patches.size(); ++p)
        EXPECT_EQ(a.boundary.patches[p].name, b.boundary.patches[p].name) << "patch " << p;
    EXPECT_EQ(a.boundary.patches.size(), 5u);  // six sides, two of them one name
}

TEST(WriteVolume, PhysicalGroupsAreNamed) {
    ScratchDir dir("write_volume_groups");
    const std::string path = dir.file("mesh.msh");
    write_volume(all_types_mesh(), path);
    const std::string text = read_text(path);
    EXPECT_NE(text.find("3 1 \"fluid\""), std::string::npos) << text.substr(0, 400);
    EXPECT_NE(text.find("2 1 \"inlet wall\""), std::string::npos);
    EXPECT_NE(text.find("2 6 \"zmax\""), std::string::npos);
}

TEST(WriteVolume, VtkByExtension) {
    ScratchDir dir("write_volume_vtk");
    const std::string path = dir.file("mesh.vtk");
    write_volume(all_types_mesh(), path);
    const std::string text = read_text(path);
    EXPECT_NE(text.find("CELLS"), std::string::npos);
    EXPECT_EQ(files_in(dir.path()), std::vector<std::string>{"mesh.vtk"});
}

TEST(WriteVolume, OtherFormatsByExtension) {
    ScratchDir dir("write_volume_formats");
    const VolumeMesh m = all_types_mesh();
    for (const char* name : {"mesh.su2", "mesh.unv", "mesh.inp", "mesh.bdf", "mesh.mesh"}) {
        write_volume(m, dir.file(name));
        EXPECT_GT(std::filesystem::file_size(dir.file(name)), 500u) << name;
    }
    EXPECT_NE(read_text(dir.file("mesh.su2")).find("NELEM= 15"), std::string::npos);
    EXPECT_EQ(files_in(dir.path()).size(), 5u);
}

TEST(WriteVolume, UnknownExtensionAndMissingDirectoryThrowAndLeaveNoFile) {
    ScratchDir dir("write_volume_bad");
    const VolumeMesh m = all_types_mesh();
    EXPECT_THROW(write_volume(m, dir.file("mesh.xyz")), InputError);
    EXPECT_THROW(write_volume(m, dir.file("mesh.stl")), InputError);  // surface-only format
    EXPECT_THROW(write_volume(m, dir.file("mesh.neu")), InputError);  // Gmsh 4.8 crashes on it
    EXPECT_THROW(write_volume(m, dir.file("no_such_dir/mesh.msh")), InputError);
    EXPECT_THROW(write_volume(m, dir.file("mesh.msh"), 3.0), InputError);
    EXPECT_TRUE(files_in(dir.path()).empty());
    try {
        write_volume(m, dir.file("mesh.xyz"));
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("mesh.xyz"), std::string::npos) << e.what();
    }
}

TEST(WriteVolume, MalformedMeshThrowsNamingTheCell) {
    ScratchDir dir("write_volume_malformed");
    VolumeMesh m = all_types_mesh();
    m.prisms[1][2] = 10000;
    try {
        write_volume(m, dir.file("mesh.msh"));
        FAIL() << "no throw";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("prism 1 (2 7 10000 10 15 14) uses node 10000"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(write_volume(VolumeMesh{}, dir.file("mesh.msh")), InputError);
    EXPECT_TRUE(files_in(dir.path()).empty());
}

TEST(ReadVolumeMsh, MissingFileAndSurfaceMeshThrowNamingTheFile) {
    ScratchDir dir("read_volume_bad");
    const std::string missing = dir.file("missing.msh");
    try {
        read_volume_msh(missing);
        FAIL() << "no throw";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
    }
    const std::string surface = dir.file("surface.msh");
    write_surface(test::quad_grid(2, 2), surface);
    try {
        read_volume_msh(surface);
        FAIL() << "no throw";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("surface.msh' holds no tetrahedra"), std::string::npos) << e.what();
    }
    const std::string garbage = dir.file("garbage.msh");
    std::ofstream(garbage) << "this is not a mesh\n";
    EXPECT_THROW(read_volume_msh(garbage), InputError);
}

TEST(ReadVolumeMsh, SecondOrderElementsAreRejected) {
    ScratchDir dir("read_volume_order2");
    const std::string path = dir.file("tet10.msh");
    // One 10-node tetrahedron, MSH 2.2.
    std::ofstream(path) << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n10\n"
                           "1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 0.5 0 0\n6 0.5 0.5 0\n7 0 0.5 0\n"
                           "8 0 0 0.5\n9 0 0.5 0.5\n10 0.5 0 0.5\n$EndNodes\n$Elements\n1\n"
                           "1 11 2 1 1 1 2 3 4 5 6 7 8 9 10\n$EndElements\n";
    test::expect_error<InputError>([&] { read_volume_msh(path); }, {"tet10.msh", "Gmsh type 11"});
}
