// Surface-mesh readers (STL, MSH through Gmsh) and the Gmsh writer: counts of the real example
// files, exact coordinates, ASCII/binary agreement, patch mapping, write→read round trips,
// and every error naming the file.

#include <strata/core/error.h>
#include <strata/io/gmsh_session.h>
#include <strata/io/read_surface.h>
#include <strata/io/write_surface.h>

#include <gtest/gtest.h>

#include "msh_variants.h"
#include "test_support.h"

#include <sys/stat.h>
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace strata {
namespace {

namespace fs = std::filesystem;
using test::example_data;
using test::test_data;

using strata::test::slurp;

std::vector<std::string> files_in(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

/// Run \p f, expect an InputError whose message contains every string of \p parts.
void expect_input_error(const std::function<void()>& f, const std::vector<std::string>& parts) {
    test::expect_error<InputError>(f, parts);
}

/// Binary STL of \p m's triangles (float32, as the format stores them), header \p header.
void write_binary_stl(const SurfaceMesh& m, const std::string& path, const std::string& header) {
    std::string out(80, ' ');
    std::memcpy(out.data(), header.data(), std::min<std::size_t>(header.size(), 80));
    auto put = [&out](const void* p, std::size_t n) { out.append(static_cast<const char*>(p), n); };
    const std::uint32_t n = static_cast<std::uint32_t>(m.num_faces());
    put(&n, 4);
    for (Index f = 0; f < m.num_faces(); ++f) {
        const float normal[3] = {0, 0, 0};
        put(normal, sizeof normal);
        for (Index k = 0; k < 3; ++k) {
            const Vec3& x = m.points[m.face_node(f, k)];
            const float v[3] = {static_cast<float>(x.x()), static_cast<float>(x.y()), static_cast<float>(x.z())};
            put(v, sizeof v);
        }
        const std::uint16_t attribute = 0;
        put(&attribute, 2);
    }
    std::ofstream(path, std::ios::binary) << out;
}

/// ASCII STL of \p m's triangles with 17 significant digits (exact for any double).
void write_ascii_stl(const SurfaceMesh& m, const std::string& path) {
    std::ofstream out(path);
    char buf[128];
    out << "solid exact\n";
    for (Index f = 0; f < m.num_faces(); ++f) {
        out << "facet normal 0 0 0\nouter loop\n";
        for (Index k = 0; k < 3; ++k) {
            const Vec3& x = m.points[m.face_node(f, k)];
            std::snprintf(buf, sizeof buf, "vertex %.17g %.17g %.17g\n", x.x(), x.y(), x.z());
            out << buf;
        }
        out << "endloop\nendfacet\n";
    }
    out << "endsolid exact\n";
}

/// Node coordinates sorted lexicographically, to compare meshes up to node renumbering.
std::vector<std::array<double, 3>> sorted_points(const SurfaceMesh& m) {
    std::vector<std::array<double, 3>> p;
    for (const Vec3& x : m.points) p.push_back({x.x(), x.y(), x.z()});
    std::sort(p.begin(), p.end());
    return p;
}

/// Each face as (patch name, node coordinates in the face's own order), sorted: compares two
/// meshes up to node renumbering and face reordering (Gmsh's MSH 2.2 writer renumbers the
/// elements type by type, so face order does not survive a 2.2 file).
std::vector<std::pair<std::string, std::vector<std::array<double, 3>>>> canonical_faces(const SurfaceMesh& m) {
    std::vector<std::pair<std::string, std::vector<std::array<double, 3>>>> faces;
    for (Index f = 0; f < m.num_faces(); ++f) {
        std::vector<std::array<double, 3>> xs;
        for (const Index* v = m.face_begin(f); v != m.face_end(f); ++v)
            xs.push_back({m.points[*v].x(), m.points[*v].y(), m.points[*v].z()});
        faces.emplace_back(m.patches[m.face_patch[f]].name, std::move(xs));
    }
    std::sort(faces.begin(), faces.end());
    return faces;
}

// ------------------------------------------------------------------------------------------
// STL

TEST(ReadStl, SphereAsciiCountsAndCoordinates) {
    const SurfaceMesh m = read_stl(example_data("sphere.stl"));
    EXPECT_EQ(m.num_faces(), 606);
    EXPECT_EQ(m.num_triangles(), 606);
    EXPECT_EQ(m.num_points(), 1818);  // not merged: 3 nodes per facet
    ASSERT_EQ(m.patches.size(), 1u);
    EXPECT_EQ(m.patches[0].name, "Created_by_Gmsh");  // "Created by Gmsh", what Gmsh writes after "solid", as one word
    EXPECT_EQ(m.face_patch, std::vector<Index>(606, 0));
    // First facet, as in the file, nodes in file order.
    EXPECT_EQ(m.face_node(0, 0), 0);
    EXPECT_EQ(m.face_node(0, 2), 2);
    EXPECT_EQ(m.points[0], Vec3(-0.222521, 0, 0.974928));
    EXPECT_EQ(m.points[1], Vec3(-0.316546, 0.143271, 0.937695));
    EXPECT_EQ(m.points[2], Vec3(-0.433884, 0, 0.900969));
    // Last facet.
    EXPECT_EQ(m.points[m.face_node(605, 0)], Vec3(0.900922, -0.400494, -0.167164));
    EXPECT_EQ(m.points[m.face_node(605, 1)], Vec3(0.900969, -0.433884, 0));
    EXPECT_EQ(m.points[m.face_node(605, 2)], Vec3(0.789345, -0.577437, -0.208566));
}

TEST(ReadStl, BinaryMatchesAscii) {
    test::ScratchDir dir("io_stl_binary");
    const SurfaceMesh a = read_stl(example_data("sphere.stl"));
    // The header starts with "solid", as many exporters write it: detection must use the size.
    write_binary_stl(a, dir.file("sphere_bin.stl"), "solid sphere exported as binary");
    const SurfaceMesh b = read_stl(dir.file("sphere_bin.stl"));
    ASSERT_EQ(b.num_faces(), a.num_faces());
    ASSERT_EQ(b.num_points(), a.num_points());
    EXPECT_EQ(b.face_offsets, a.face_offsets);
    EXPECT_EQ(b.face_nodes, a.face_nodes);
    EXPECT_EQ(b.face_patch, a.face_patch);
    ASSERT_EQ(b.patches.size(), 1u);
    EXPECT_EQ(b.patches[0].name, "sphere_bin");  // binary: the file stem
    for (Index i = 0; i < a.num_points(); ++i)
        for (int k = 0; k < 3; ++k)  // binary stores float32: exactly the ASCII value rounded to float
            ASSERT_EQ(b.points[i][k], static_cast<double>(static_cast<float>(a.points[i][k]))) << i;

    // ASCII printed from the float values with 17 digits reads back bit-identical to binary.
    write_ascii_stl(b, dir.file("sphere_exact.stl"));
    const SurfaceMesh c = read_stl(dir.file("sphere_exact.stl"));
    EXPECT_EQ(c.points, b.points);
    EXPECT_EQ(c.face_nodes, b.face_nodes);
}

TEST(ReadStl, BytesInMemoryReadAsTheFile) {
    // read_stl_bytes (the fuzz target's entry) is read_stl without the file: same mesh, and the
    // source in place of the path, in messages and as a binary file's patch name.
    test::ScratchDir dir("io_stl_bytes");
    const SurfaceMesh a = read_stl(example_data("sphere.stl"));
    const SurfaceMesh from_text = read_stl_bytes(slurp(example_data("sphere.stl")), "text.stl");
    EXPECT_EQ(from_text.points, a.points);
    EXPECT_EQ(from_text.face_nodes, a.face_nodes);
    EXPECT_EQ(from_text.patches[0].name, a.patches[0].name);  // ASCII: the solid's name
    write_binary_stl(a, dir.file("sphere_bin.stl"), "solid sphere");
    const SurfaceMesh b = read_stl(dir.file("sphere_bin.stl"));
    const SurfaceMesh from_binary = read_stl_bytes(slurp(dir.file("sphere_bin.stl")), "in/memory.stl");
    EXPECT_EQ(from_binary.points, b.points);
    EXPECT_EQ(from_binary.patches[0].name, "memory");
    expect_input_error([] { read_stl_bytes("solid s\nfacet normal 0 0 1\n", "upload.stl"); },
                       {"'upload.stl': line 3", "expected 'outer loop', found the end of the file"});
    expect_input_error([] { read_stl_bytes(std::string(100, '\x01'), "upload.stl"); },
                       {"'upload.stl': binary STL header announces 16843009 facets"});
}

TEST(ReadStl, MultiSolidAsciiGivesOnePatchPerSolid) {
    const SurfaceMesh m = read_stl(test_data("io_two_solids.stl"));
    ASSERT_EQ(m.patches.size(), 2u);
    EXPECT_EQ(m.patches[0].name, "fuselage");
    EXPECT_EQ(m.patches[1].name, "wall");  // "SOLID" with no name
    EXPECT_EQ(m.face_patch, (std::vector<Index>{0, 0, 1}));
    EXPECT_EQ(m.num_points(), 9);
    // Upper-case keywords, '+' signs and exponents are all accepted.
    EXPECT_EQ(m.points[6], Vec3(0, 0, 2.5));
    EXPECT_EQ(m.points[7], Vec3(0.5, 0.15, 2.5));
    EXPECT_EQ(m.points[8], Vec3(-10, 1, 2.5));
}

TEST(ReadStl, SolidNamesAreWordsEveryFormatTakes) {
    // A CAD tool's solid names (spaces, brackets, a leading digit) are the patch names every
    // format writes, the same in the summary as in OpenFOAM's boundary file.
    const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                              "endloop\nendfacet\n";
    const std::string text = "solid Wing Body.001 (left)\n" + facet + "endsolid Wing Body.001 (left)\nsolid 2nd part\n" +
                             facet + "endsolid\nsolid fin-1_a\n" + facet + "endsolid\n";
    const SurfaceMesh m = read_stl_bytes(text, "t.stl");
    ASSERT_EQ(m.patches.size(), 3u);
    EXPECT_EQ(m.patches[0].name, "Wing_Body.001_left");
    EXPECT_EQ(m.patches[1].name, "patch_2nd_part");
    EXPECT_EQ(m.patches[2].name, "fin-1_a");  // a word already: as it is
    EXPECT_EQ(patch_word("", 4), "patch_5");
    EXPECT_EQ(patch_word("a  b;;", 0), "a_b");
}

TEST(ReadStl, MissingFile) {
    const std::string path = "/nonexistent_dir/io_missing.stl";
    expect_input_error([&] { read_stl(path); }, {"cannot open", path, "no such file"});
}

TEST(ReadStl, PipeReadToItsEndDeviceRefused) {
    test::ScratchDir dir("io_stl_pipe");
    const std::string fifo = dir.file("sphere.stl");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::thread writer = test::fill_fifo(fifo, slurp(example_data("sphere.stl")));  // it waits for the reader
    const SurfaceMesh m = read_stl(fifo);
    writer.join();
    EXPECT_EQ(m.num_triangles(), 606);
    EXPECT_EQ(m.points, read_stl(example_data("sphere.stl")).points);
    // A device's size means nothing (/dev/zero: 0, and it never ends).
    fs::create_symlink("/dev/zero", dir.file("zero.stl"));
    expect_input_error([&] { read_stl(dir.file("zero.stl")); }, {"zero.stl' is a device, not a file"});
}

TEST(ReadStl, TruncatedBinary) {
    test::ScratchDir dir("io_stl_truncated");
    SurfaceMesh m = read_stl(test_data("io_two_solids.stl"));
    // A header that starts with "solid" must still be recognised as (truncated) binary.
    write_binary_stl(m, dir.file("cut.stl"), "solid cut");
    const std::string whole = slurp(dir.file("cut.stl"));
    ASSERT_EQ(whole.size(), 84u + 50u * 3u);
    std::ofstream(dir.file("cut.stl"), std::ios::binary | std::ios::trunc) << whole.substr(0, whole.size() - 20);
    expect_input_error([&] { read_stl(dir.file("cut.stl")); }, {"cut.stl", "84+50*3", "234 bytes expected", "214"});
}

TEST(ReadStl, MalformedAsciiNamesLine) {
    expect_input_error([] { read_stl(test_data("io_malformed.stl")); },
                       {"io_malformed.stl", "line 12", "expected 'vertex x y z'", "found 'vertx 1 1 0'"});
}

TEST(ReadStl, TruncatedAsciiAndEmptyAndNotStl) {
    test::ScratchDir dir("io_stl_bad");
    const std::string text = slurp(test_data("io_two_solids.stl"));
    std::ofstream(dir.file("half.stl")) << text.substr(0, text.find("vertex 1 1 0"));
    expect_input_error([&] { read_stl(dir.file("half.stl")); }, {"half.stl", "line 12", "end of the file"});
    std::ofstream(dir.file("empty.stl")) << "solid nothing\nendsolid nothing\n";
    expect_input_error([&] { read_stl(dir.file("empty.stl")); }, {"empty.stl", "no facets"});
    std::ofstream(dir.file("words.stl")) << "hello\n";
    expect_input_error([&] { read_stl(dir.file("words.stl")); }, {"words.stl", "not an STL file"});
    std::ofstream(dir.file("nan.stl")) << "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                                          "vertex 1 nan 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
    expect_input_error([&] { read_stl(dir.file("nan.stl")); }, {"nan.stl", "line 5", "non-finite"});
}

// ------------------------------------------------------------------------------------------
// MSH

TEST(ReadMsh, SpherePyhypQuads) {
    const SurfaceMesh m = read_msh(example_data("sphere_pyhyp_quads.msh"));
    EXPECT_EQ(m.num_quads(), 1536);
    EXPECT_EQ(m.num_triangles(), 0);
    EXPECT_EQ(m.num_points(), 1538);  // closed genus-0 quad mesh: V = F + 2; sparse tags compacted
    ASSERT_EQ(m.patches.size(), 6u);  // no physical groups: one patch per surface entity
    for (int s = 0; s < 6; ++s) EXPECT_EQ(m.patches[s].name, "surface_" + std::to_string(s + 1));
    for (Index f = 0; f < m.num_faces(); ++f) ASSERT_TRUE(m.face_patch[f] >= 0 && m.face_patch[f] < 6);
    // Every node is used by some face, every face node is in range.
    std::vector<int> used(m.points.size(), 0);
    for (Index v : m.face_nodes) {
        ASSERT_TRUE(v >= 0 && v < m.num_points());
        used[v] = 1;
    }
    EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
    for (const Vec3& x : m.points) EXPECT_NEAR(x.norm(), 1.0, 0.01);
}

TEST(ReadMsh, OneraM6Mixed) {
    const SurfaceMesh m = read_msh(example_data("onera_m6_mixed_quadtri.msh"));
    EXPECT_EQ(m.num_quads(), 7753);
    EXPECT_EQ(m.num_triangles(), 2588);
    EXPECT_EQ(m.num_points(), 9049);   // closed: V = E − F + 2 with E = (4·7753 + 3·2588)/2
    EXPECT_EQ(m.patches.size(), 11u);  // the 11 CAD faces
}

TEST(ReadMsh, OneraM6PyhypQuads) {
    const SurfaceMesh m = read_msh(example_data("onera_m6_pyhyp_quads.msh"));
    EXPECT_EQ(m.num_quads(), 15232);
    EXPECT_EQ(m.num_triangles(), 0);
    EXPECT_EQ(m.patches.size(), 9u);
    EXPECT_LE(m.num_points(), 15321);
}

TEST(ReadMsh, PhysicalGroupsSparseTagsAndVolumeNodes) {
    // Surface 1 is in groups 5 "top" and 2 (unnamed): the lowest tag, 2, wins. Surface 2 is in
    // "top" only, surface 3 in no group. Node tags 10..40 are sparse; node 99 is volume-only.
    const SurfaceMesh m = read_msh(test_data("io_groups.msh"));
    ASSERT_EQ(m.patches.size(), 3u);
    EXPECT_EQ(m.patches[0].name, "physical_2");
    EXPECT_EQ(m.patches[1].name, "top");
    EXPECT_EQ(m.patches[2].name, "surface_3");
    ASSERT_EQ(m.num_faces(), 4);
    EXPECT_EQ(m.face_patch, (std::vector<Index>{0, 1, 1, 2}));
    EXPECT_EQ(m.face_offsets, (std::vector<Index>{0, 4, 7, 10, 13}));
    // Nodes in tag order 10, 11, 20, 21, 30, 31, 40 → 0..6.
    EXPECT_EQ(m.face_nodes, (std::vector<Index>{0, 1, 2, 3, 1, 4, 5, 1, 5, 2, 4, 6, 5}));
    ASSERT_EQ(m.num_points(), 7);
    EXPECT_EQ(m.points[2], Vec3(1, 1, 0));
    EXPECT_EQ(m.points[6], Vec3(3, 0, 0));
}

TEST(ReadMsh, GroupsWithoutFacesMakeNoPatch) {
    // One rule for every reader (gmsh_model.h): a 2D physical group whose surfaces hold no
    // elements makes no patch. (Before the readers shared one conversion, read_msh made an empty
    // patch "empty" here while the CAD import made none.)
    test::ScratchDir dir("io_msh_empty_group");
    const std::string path = dir.file("groups.msh");
    {
        GmshSession session("write_groups");
        gmsh::model::addDiscreteEntity(2, 1);
        gmsh::model::addDiscreteEntity(2, 2);  // no elements
        gmsh::model::mesh::addNodes(2, 1, {1, 2, 3}, {0, 0, 0, 1, 0, 0, 0, 1, 0});
        gmsh::model::mesh::addElementsByType(1, 2, {1}, {1, 2, 3});
        gmsh::model::addPhysicalGroup(2, {2}, 1);
        gmsh::model::setPhysicalName(2, 1, "empty");
        gmsh::model::addPhysicalGroup(2, {1}, 2);
        gmsh::model::setPhysicalName(2, 2, "hull");
        gmsh::option::setNumber("Mesh.SaveAll", 1);
        gmsh::write(path);
    }
    const SurfaceMesh m = read_msh(path);
    ASSERT_EQ(m.patches.size(), 1u);
    EXPECT_EQ(m.patches[0].name, "hull");
    EXPECT_EQ(m.face_patch, (std::vector<Index>{0}));
}

TEST(ReadMsh, BinaryAndVersion22AgreeWithAscii) {
    test::ScratchDir dir("io_msh_binary");
    const std::string src = example_data("onera_m6_mixed_quadtri.msh");
    const SurfaceMesh ref = read_msh(src);
    test::write_msh_variants(src, dir);
    for (const char* name : {"b41.msh", "b22.msh", "a22.msh"}) {
        SCOPED_TRACE(name);
        const SurfaceMesh m = read_msh(dir.file(name));
        EXPECT_EQ(m.points, ref.points);  // binary: exact doubles; 2.2 ASCII: %.16g of the same
        EXPECT_EQ(m.num_quads(), 7753);
        EXPECT_EQ(m.num_triangles(), 2588);
        if (std::string(name) == "b41.msh") {  // same element tags: same face order
            EXPECT_EQ(m.face_offsets, ref.face_offsets);
            EXPECT_EQ(m.face_nodes, ref.face_nodes);
            EXPECT_EQ(m.face_patch, ref.face_patch);
        }
        EXPECT_TRUE(canonical_faces(m) == canonical_faces(ref));
        ASSERT_EQ(m.patches.size(), ref.patches.size());
        for (std::size_t p = 0; p < m.patches.size(); ++p) EXPECT_EQ(m.patches[p].name, ref.patches[p].name);
    }
}

TEST(ReadMsh, Errors) {
    const std::string missing = "/nonexistent_dir/io_missing.msh";
    expect_input_error([&] { read_msh(missing); }, {"cannot open", missing});
    expect_input_error([] { read_msh(test_data("io_lines_only.msh")); },
                       {"io_lines_only.msh", "no triangles or quadrangles"});
    expect_input_error([] { read_msh(test_data("io_tri6.msh")); },
                       {"io_tri6.msh", "surface 7", "Gmsh type 9", "first order"});
    test::ScratchDir dir("io_msh_bad");
    std::ofstream(dir.file("garbage.msh")) << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 oops\n";
    expect_input_error([&] { read_msh(dir.file("garbage.msh")); }, {"garbage.msh", "Could not read nodes"});
    // Cut inside $Elements: Gmsh's own complaint, as an InputError naming the file.
    std::ofstream(dir.file("cut.msh")) << slurp(example_data("sphere_pyhyp_quads.msh")).substr(0, 120000);
    expect_input_error([&] { read_msh(dir.file("cut.msh")); }, {"cut.msh", "Could not read elements"});
}

// ------------------------------------------------------------------------------------------
// write_surface

/// Mixed mesh: a 3×2 quad grid (spacing 0.25, exact in any decimal form) on patches "wing"
/// and "farfield_top", a triangle fan with short-decimal coordinates on "symmetry", an empty
/// patch "unused" between them, faces of different patches interleaved, one unused node.
SurfaceMesh mixed_mesh() {
    SurfaceMesh m = test::quad_grid(3, 2, 0.25);
    m.patches = {{"wing", PatchKind::Wall},
                 {"unused", PatchKind::Wall},
                 {"farfield_top", PatchKind::Farfield},
                 {"symmetry", PatchKind::Symmetry}};
    for (Index f = 3; f < 6; ++f) m.face_patch[f] = 2;  // upper row of quads
    m.face_patch[1] = 2;                                // interleave patches in face order
    const Index hub = m.num_points();
    m.points.emplace_back(0.974928, -0.433884, 0.1);
    m.points.emplace_back(123.456, 7.0, -0.000321);  // unused node: not written
    m.add_face({hub, 0, 1}, 3);                      // triangles sharing grid nodes
    m.add_face({hub, 1, 2}, 3);
    m.add_face({2, 6, 1}, 0);  // a triangle on the quad patch: mixed types on one surface
    return m;
}

/// Face-by-face comparison up to node renumbering: same size, same coordinates in the same
/// order, same patch name.
void expect_same_faces(const SurfaceMesh& a, const SurfaceMesh& b) {
    ASSERT_EQ(a.num_faces(), b.num_faces());
    EXPECT_EQ(a.num_triangles(), b.num_triangles());
    EXPECT_EQ(a.num_quads(), b.num_quads());
    for (Index f = 0; f < a.num_faces(); ++f) {
        ASSERT_EQ(a.face_size(f), b.face_size(f)) << "face " << f;
        for (Index k = 0; k < a.face_size(f); ++k)
            EXPECT_EQ(a.points[a.face_node(f, k)], b.points[b.face_node(f, k)]) << "face " << f << " node " << k;
        EXPECT_EQ(a.patches[a.face_patch[f]].name, b.patches[b.face_patch[f]].name) << "face " << f;
    }
}

class WriteSurfaceRoundTrip : public testing::TestWithParam<double> {};

TEST_P(WriteSurfaceRoundTrip, PreservesFacesCoordinatesAndPatches) {
    const double version = GetParam();
    test::ScratchDir dir("io_roundtrip_" + std::to_string(static_cast<int>(version * 10)));
    const SurfaceMesh m = mixed_mesh();
    write_surface(m, dir.file("out.msh"), version);
    EXPECT_EQ(files_in(dir.path()), std::vector<std::string>{"out.msh"});  // no temporary left
    const std::string text = slurp(dir.file("out.msh"));
    EXPECT_EQ(text.rfind(version == 2.2 ? "$MeshFormat\n2.2 0" : "$MeshFormat\n4.1 0", 0), 0u);

    const SurfaceMesh r = read_msh(dir.file("out.msh"));
    EXPECT_EQ(r.num_triangles(), m.num_triangles());
    EXPECT_EQ(r.num_quads(), m.num_quads());
    EXPECT_TRUE(canonical_faces(r) == canonical_faces(m));  // coordinates exact, patch per face
    // Patches with faces, in order; the empty one is not written.
    ASSERT_EQ(r.patches.size(), 3u);
    EXPECT_EQ(r.patches[0].name, "wing");
    EXPECT_EQ(r.patches[1].name, "farfield_top");
    EXPECT_EQ(r.patches[2].name, "symmetry");
    // Nodes: all used ones, exactly; the unused one dropped.
    SurfaceMesh used = m;
    used.points.pop_back();
    EXPECT_EQ(sorted_points(r), sorted_points(used));
    // Node order is kept too (tags = index + 1); in MSH 4.1 the element tags are kept as well,
    // so the mesh comes back identical.
    EXPECT_EQ(r.points, used.points);
    if (version == 4.1) {
        expect_same_faces(m, r);
        EXPECT_EQ(r.face_nodes, m.face_nodes);
    }
}

INSTANTIATE_TEST_SUITE_P(MshVersions, WriteSurfaceRoundTrip, testing::Values(4.1, 2.2),
                         [](const testing::TestParamInfo<double>& i) {
                             return i.param == 2.2 ? std::string("msh22") : std::string("msh41");
                         });

TEST(WriteSurface, RealMeshRoundTripAndByteIdenticalRerun) {
    test::ScratchDir dir("io_roundtrip_m6");
    const SurfaceMesh m = read_msh(example_data("onera_m6_mixed_quadtri.msh"));
    write_surface(m, dir.file("a.msh"));
    write_surface(m, dir.file("b.msh"));
    EXPECT_EQ(slurp(dir.file("a.msh")), slurp(dir.file("b.msh")));
    const SurfaceMesh r = read_msh(dir.file("a.msh"));
    expect_same_faces(m, r);
    EXPECT_EQ(r.points, m.points);  // file values are %.16g already, so exact again
}

TEST(WriteSurface, ArbitraryDoublesRoundTripToSixteenDigits) {
    // Gmsh writes ASCII coordinates with 16 significant digits: not always the exact double.
    test::ScratchDir dir("io_roundtrip_digits");
    SurfaceMesh m = test::quad_grid(4, 4);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1e3, 1e3);
    for (Vec3& x : m.points) x = Vec3(u(rng), u(rng), u(rng));
    write_surface(m, dir.file("r.msh"));
    const SurfaceMesh r = read_msh(dir.file("r.msh"));
    ASSERT_EQ(r.num_points(), m.num_points());
    for (Index i = 0; i < m.num_points(); ++i)
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.points[i][k], m.points[i][k], 1e-15 * std::abs(m.points[i][k])) << i;
}

TEST(WriteSurface, StlAndVtkByExtension) {
    test::ScratchDir dir("io_formats");
    const SurfaceMesh sphere = read_stl(example_data("sphere.stl"));
    write_surface(sphere, dir.file("s.stl"));
    const SurfaceMesh back = read_stl(dir.file("s.stl"));
    EXPECT_EQ(back.num_triangles(), 606);
    EXPECT_EQ(sorted_points(back), sorted_points(sphere));
    write_surface(mixed_mesh(), dir.file("m.vtk"));
    EXPECT_NE(slurp(dir.file("m.vtk")).find("CELLS"), std::string::npos);
    EXPECT_EQ(files_in(dir.path()), (std::vector<std::string>{"m.vtk", "s.stl"}));
}

TEST(WriteSurface, UnknownExtensionNothingWritten) {
    test::ScratchDir dir("io_badext");
    expect_input_error([&] { write_surface(mixed_mesh(), dir.file("out.xyz123")); }, {"out.xyz123", ".msh"});
    expect_input_error([&] { write_surface(mixed_mesh(), dir.file("out.msh"), 3.7); }, {"out.msh", "3.7"});
    EXPECT_TRUE(files_in(dir.path()).empty());
}

TEST(WriteSurface, MissingDirectoryNothingWritten) {
    test::ScratchDir dir("io_nodir");
    const std::string path = dir.file("nodir/out.msh");
    expect_input_error([&] { write_surface(mixed_mesh(), path); }, {path, "does not exist"});
    EXPECT_TRUE(files_in(dir.path()).empty());
    EXPECT_FALSE(fs::exists(path));
}

TEST(WriteSurface, MalformedMeshRejected) {
    test::ScratchDir dir("io_badmesh");
    SurfaceMesh m = mixed_mesh();
    m.face_nodes[5] = 1000;
    expect_input_error([&] { write_surface(m, dir.file("bad.msh")); }, {"bad.msh", "face 1", "node 1000"});
    SurfaceMesh empty;
    expect_input_error([&] { write_surface(empty, dir.file("empty.msh")); }, {"empty.msh", "no faces"});
    EXPECT_TRUE(files_in(dir.path()).empty());
}

TEST(WriteSurface, CallersGmshOptionsAndModelKept) {
    test::ScratchDir dir("io_options");
    GmshSession outer("test_outer");  // a Gmsh user with a model of their own
    std::string model;
    gmsh::model::getCurrent(model);
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::option::setNumber("Mesh.Binary", 1);
    write_surface(mixed_mesh(), dir.file("o.msh"), 2.2);
    double version = 0, binary = 0;
    gmsh::option::getNumber("Mesh.MshFileVersion", version);
    gmsh::option::getNumber("Mesh.Binary", binary);
    EXPECT_EQ(version, 4.1);
    EXPECT_EQ(binary, 1);
    gmsh::option::setNumber("Mesh.Binary", 0);
    std::string after;
    gmsh::model::getCurrent(after);
    EXPECT_EQ(after, model);
    EXPECT_EQ(slurp(dir.file("o.msh")).rfind("$MeshFormat\n2.2 0 8", 0), 0u);  // ASCII 2.2 anyway
}

}  // namespace
}  // namespace strata
