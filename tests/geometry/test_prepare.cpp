// The geometry stage as one call: dispatch by file type, patch kinds, merge, check, orient.

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/geometry/prepare.h>
#include <strata/io/read_surface.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <fstream>

namespace strata {
namespace {

using test::example_data;

/// Write \p m as an ASCII STL (one solid per patch is not needed here: one solid).
void write_ascii_stl(const SurfaceMesh& m, const std::string& path) {
    std::ofstream out(path);
    out.precision(17);
    out << "solid hull\n";
    for (Index f = 0; f < m.num_faces(); ++f) {
        out << " facet normal 0 0 0\n  outer loop\n";
        for (Index i = 0; i < 3; ++i) {
            const Vec3& p = m.points[m.face_node(f, i)];
            out << "   vertex " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
        }
        out << "  endloop\n endfacet\n";
    }
    out << "endsolid hull\n";
}

TEST(Prepare, StlIsMergedAndOrientedOutward) {
    PrepareReport rep;
    const SurfaceMesh m = prepare_surface(example_data("sphere.stl"), {}, &rep);
    EXPECT_EQ(m.num_points(), 305);
    EXPECT_EQ(rep.merged_nodes, 3 * 606 - 305);
    EXPECT_EQ(rep.orient.components, 1);
    EXPECT_EQ(rep.orient.closed_components, 1);
    ASSERT_EQ(m.patches.size(), 1u);
    EXPECT_EQ(m.patches[0].kind, PatchKind::Wall);
    const Vec3 c = [&] {
        Vec3 s = Vec3::Zero();
        for (const Vec3& p : m.points) s += p;
        return Vec3(s / m.num_points());
    }();
    for (Index f = 0; f < m.num_faces(); ++f)
        EXPECT_GT(face_area_vector(m, f).dot(face_centroid(m, m.points, f) - c), 0.0) << "face " << f;
}

TEST(Prepare, SphereWithFlippedFacesIsRepaired) {
    // Take the STL sphere, flip every third facet, write it, and read it back through the stage.
    SurfaceMesh raw = read_stl(example_data("sphere.stl"));
    Index flipped = 0;
    for (Index f = 0; f < raw.num_faces(); f += 3, ++flipped)
        std::swap(raw.face_nodes[raw.face_offsets[f] + 1], raw.face_nodes[raw.face_offsets[f] + 2]);
    test::ScratchDir dir("prepare_flipped");
    write_ascii_stl(raw, dir.file("flipped.stl"));
    PrepareReport rep;
    const SurfaceMesh m = prepare_surface(dir.file("flipped.stl"), {}, &rep);
    EXPECT_EQ(rep.orient.flipped_faces, flipped);
    for (Index f = 0; f < m.num_faces(); ++f)
        EXPECT_GT(face_area_vector(m, f).dot(face_centroid(m, m.points, f)), 0.0) << "face " << f;
}

TEST(Prepare, PatchKindsFromNamesAndMappings) {
    SurfaceMesh m;
    m.patches = {{"Body", PatchKind::Other}, {"SymmetryPlane", PatchKind::Other}, {"outer_FARFIELD", PatchKind::Other}};
    assign_patch_kinds(m, {}, "model.msh");
    EXPECT_EQ(m.patches[0].kind, PatchKind::Wall);
    EXPECT_EQ(m.patches[1].kind, PatchKind::Symmetry);
    EXPECT_EQ(m.patches[2].kind, PatchKind::Farfield);
    assign_patch_kinds(m, {{"Body", PatchKind::Other}, {"SymmetryPlane", PatchKind::Wall}}, "model.msh");
    EXPECT_EQ(m.patches[0].kind, PatchKind::Other);
    EXPECT_EQ(m.patches[1].kind, PatchKind::Wall);
    try {
        assign_patch_kinds(m, {{"Wing", PatchKind::Wall}}, "model.msh");
        FAIL() << "unknown patch accepted";
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("model.msh"), std::string::npos) << msg;
        EXPECT_NE(msg.find("'Wing'"), std::string::npos) << msg;
        EXPECT_NE(msg.find("SymmetryPlane"), std::string::npos) << msg;  // lists what exists
    }
}

TEST(Prepare, UnknownTypeAndMissingFile) {
    EXPECT_THROW(prepare_surface("/no/such/file.stl", {}), InputError);
    EXPECT_THROW(prepare_surface(example_data("SOURCES.md"), {}), InputError);
    EXPECT_THROW(prepare_surface(std::string(STRATA_EXAMPLES_DATA), {}), InputError);
}

TEST(Prepare, ParsePatchKind) {
    EXPECT_EQ(parse_patch_kind("Symmetry"), PatchKind::Symmetry);
    EXPECT_EQ(parse_patch_kind("farfield"), PatchKind::Farfield);
    for (PatchKind k : {PatchKind::Wall, PatchKind::Symmetry, PatchKind::Farfield, PatchKind::Other})
        EXPECT_EQ(parse_patch_kind(to_string(k)), k);
    EXPECT_THROW(parse_patch_kind("inlet"), InputError);
}

}  // namespace
}  // namespace strata
