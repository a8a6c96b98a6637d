// The geometry stage as one call: dispatch by file type, patch kinds, merge, check, orient.

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/format.h>
#include <strata/geometry/primitives.h>
#include <strata/geometry/topology.h>
#include <strata/io/read_surface.h>
#include <strata/surface/prepare.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>
#include <fstream>
#include <numbers>

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

TEST(Prepare, CollapsedFacesAreRemovedAndCounted) {
    // An STL-like sphere whose pole a CAD tool wrote with a collapsed triangle (its two
    // corners at one point): removed, counted, and the surface closed as before.
    SurfaceMesh s = icosphere(Vec3::Zero(), 1.0, 2, {"wall", PatchKind::Wall});
    const Index faces = s.num_faces();
    const Index a = s.face_node(0, 0), b = s.face_node(0, 1);
    s.points.push_back(s.points[static_cast<std::size_t>(a)]);  // a's twin, merged into it
    s.add_face({a, b, static_cast<Index>(s.points.size() - 1)}, 0);
    PrepareReport rep;
    const SurfaceMesh m = prepare_mesh(s, {}, "pole.stl", &rep);
    EXPECT_EQ(rep.collapsed_faces, 1);
    EXPECT_EQ(m.num_faces(), faces);
    EXPECT_TRUE(test::closed_manifold(m));
    EXPECT_GT(test::enclosed_volume(m), 0.0);
}

TEST(Prepare, CoordinatesSpanningBeyondADoubleNameTheFile) {
    // Finite coordinates the reader accepts, but whose span overflows: merging refuses them (it
    // made infinite cells and undefined integers of them, a fuzzer's find), naming the file.
    test::ScratchDir dir("prepare_huge");
    std::ofstream(dir.file("huge.stl")) << "solid s\nfacet normal 0 0 1\nouter loop\nvertex -1e308 0 0\n"
                                           "vertex 1e308 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
    test::expect_error<TopologyError>(
        [&] { prepare_surface(dir.file("huge.stl"), {}); },
        {"huge.stl: merge_coincident_nodes: the nodes span from (-1e+308, 0, 0)", "wrong unit"});
}

TEST(Prepare, ErrorsAfterTheCheckNameTheFile) {
    // A Moebius strip passes check_surface but cannot be oriented: orient_surface's error
    // names faces and an edge, prepare_mesh adds the file.
    const SurfaceMesh strip = test::moebius_strip();
    test::expect_error<TopologyError>([&] { prepare_mesh(strip, {}, "strip.stl"); },
                                      {"strip.stl: orient_surface: surface component 0", "not orientable"});
    // Internal flow inside a surface with a hole: orient_surface's InputError, with the file.
    SurfaceMesh open = icosphere(Vec3::Zero(), 1.0, 1, {"wall", PatchKind::Wall});
    open.face_offsets.pop_back();
    open.face_nodes.resize(static_cast<std::size_t>(open.face_offsets.back()));
    open.face_patch.pop_back();
    PrepareParams internal;
    internal.internal_flow = true;
    test::expect_error<InputError>([&] { prepare_mesh(open, internal, "duct.stl"); },
                                   {"duct.stl: internal flow (PrepareParams::internal_flow)"});
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
        test::expect_contains(msg, {"model.msh", "'Wing'"});
        EXPECT_NE(msg.find("SymmetryPlane"), std::string::npos) << msg;  // lists what exists
    }
}

TEST(Prepare, UnknownTypeAndMissingFile) {
    EXPECT_THROW(prepare_surface("/no/such/file.stl", {}), InputError);
    EXPECT_THROW(prepare_surface(example_data("SOURCES.md"), {}), InputError);
    EXPECT_THROW(prepare_surface(std::string(STRATA_EXAMPLES_DATA), {}), InputError);
}

/// An ASCII STL tetrahedron (solid "part") with its corner at \p o, facets in any orientation.
std::string tet_stl(const Vec3& o) {
    const Vec3 p[4] = {o, o + Vec3(1, 0, 0), o + Vec3(0, 1, 0), o + Vec3(0, 0, 1)};
    const int f[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    std::string s = "solid part\n";
    for (const auto& t : f) {
        s += "facet normal 0 0 0\nouter loop\n";
        for (int i : t)
            s += "vertex " + std::to_string(p[i].x()) + " " + std::to_string(p[i].y()) + " " +
                 std::to_string(p[i].z()) + "\n";
        s += "endloop\nendfacet\n";
    }
    return s + "endsolid part\n";
}

TEST(Prepare, SeveralInputsAreOneSurfaceEachKeepingItsPatches) {
    test::ScratchDir dir("prepare_several");
    const std::string a = dir.file("a.stl"), b = dir.file("b.stl");
    std::ofstream(a) << tet_stl(Vec3(0, 0, 0));
    std::ofstream(b) << tet_stl(Vec3(3, 0, 0));
    PrepareReport rep;
    const SurfaceMesh m = prepare_surfaces({a, b}, {}, &rep);
    EXPECT_EQ(m.num_faces(), 8);
    EXPECT_EQ(m.num_points(), 8);
    EXPECT_EQ(rep.orient.components, 2);
    ASSERT_EQ(m.patches.size(), 2u);
    EXPECT_EQ(m.patches[0].name, "part");
    EXPECT_EQ(m.patches[1].name, "part_b.stl");  // the same name again: the file's after it, one word
    // Both oriented outward, as one file with both would be.
    for (Index f = 0; f < m.num_faces(); ++f) {
        const Vec3 centre = m.face_patch[f] == 0 ? Vec3(0.25, 0.25, 0.25) : Vec3(3.25, 0.25, 0.25);
        EXPECT_GT(face_area_vector(m, f).dot(face_centroid(m, m.points, f) - centre), 0.0) << f;
    }
    // A CAD file among them: read in its unit, which the report states.
    PrepareParams fused;
    fused.cad.fuse = true;  // its wing and fuselage overlap
    const SurfaceMesh with_cad = prepare_surfaces({a, example_data("wing_fuselage.step")}, fused, &rep);
    EXPECT_EQ(rep.units.unit, "m");
    EXPECT_GT(with_cad.patches.size(), 2u);
    // One input: prepare_surface itself; none, or a missing one: an error naming it.
    EXPECT_EQ(prepare_surfaces({a}, {}).face_nodes, prepare_surface(a, {}).face_nodes);
    EXPECT_THROW(prepare_surfaces({}, {}), InputError);
    const std::string missing = dir.file("missing.stl");
    try {
        prepare_surfaces({a, missing}, {});
        FAIL() << "a missing input must be an error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("missing.stl"), std::string::npos) << e.what();
    }
}

TEST(Prepare, FusedBodiesWhoseCutsPassANodeAreRepaired) {
    // A CAD tool's STL of a sphere and a cone that overlap: the union's cut passes within the
    // merge tolerance of a node of the sphere's tessellation, so merging the union's nodes
    // leaves two faces that repeat a node. They go as the input's do (counted with them), where
    // they used to stop --fuse with "uses node ... twice".
    PrepareParams p;
    p.fuse = true;
    PrepareReport rep;
    const SurfaceMesh m = prepare_surface(test::test_data("prepare_sphere_cone_brepmesh.stl"), p, &rep);
    EXPECT_EQ(rep.fused_components, 2);
    EXPECT_EQ(rep.collapsed_faces, 4);  // 2 in the file, 2 from the union
    EXPECT_TRUE(test::closed_manifold(m));
    Index nc = 0;
    face_components(m, &nc);
    EXPECT_EQ(nc, 1);
    PrepareReport alone;
    (void)prepare_surface(test::test_data("prepare_sphere_cone_brepmesh.stl"), {}, &alone);
    EXPECT_EQ(alone.collapsed_faces, 2);
}

TEST(Prepare, AFaceWrittenTwiceIsRemovedAndTheMergeToleranceChecked) {
    // A tetrahedron's STL with its first facet written again (a CAD export's slip): its three
    // edges bounded three faces each, which check_surface refuses. The copy goes and is counted.
    test::ScratchDir dir("prepare_duplicate");
    std::string text = tet_stl(Vec3(0, 0, 0));
    const std::size_t first = text.find("facet normal"), second = text.find("facet normal", first + 1);
    text.insert(text.rfind("endsolid"), text.substr(first, second - first));
    const std::string path = dir.file("twice.stl");
    std::ofstream(path) << text;
    PrepareReport rep;
    const SurfaceMesh m = prepare_surface(path, {}, &rep);
    EXPECT_EQ(rep.duplicate_faces, 1);
    EXPECT_EQ(m.num_faces(), 4);
    EXPECT_TRUE(test::closed_manifold(m));
    // The weld distance is a share of the model's size, at most 0.001.
    PrepareParams p;
    p.merge_tolerance = 0.01;
    test::expect_error<InputError>([&] { (void)prepare_surface(path, p); },
                                   {"twice.stl", "merge_tolerance = 0.01", "[0, 0.001]"});
}

/// Sphere "a" through sphere "b", a hole in a, a face of b written twice and a fin on an edge of
/// a: a surface nothing repairs in place (non-manifold edges, a hole, self-intersections).
SurfaceMesh dirty_spheres() {
    SurfaceMesh a = icosphere(Vec3::Zero(), 1.0, 3, {"a", PatchKind::Wall});
    std::vector<char> drop(static_cast<std::size_t>(a.num_faces()), 0);
    drop[0] = drop[1] = 1;
    SurfaceMesh soup = test::merged(remove_faces(a, drop), icosphere(Vec3(1.2, 0.1, 0), 0.8, 3, {"b", PatchKind::Wall}));
    soup.add_face(soup.face_begin(soup.num_faces() - 1), 3, 1);
    const Index* e = soup.face_begin(100);
    soup.points.push_back(0.5 * (soup.points[e[0]] + soup.points[e[1]]) * 1.05);
    const std::array<Index, 3> fin{e[0], e[1], static_cast<Index>(soup.points.size() - 1)};
    soup.add_face(fin.data(), 3, 0);
    return soup;
}

TEST(Prepare, ASurfaceNothingRepairsIsWrappedAndRemeshed) {
    test::ScratchDir dir("prepare_wrap");
    write_ascii_stl(dirty_spheres(), dir.file("dirty.stl"));
    // Refused as it is, and the error names the wrap.
    test::expect_error<TopologyError>([&] { (void)prepare_surface(dir.file("dirty.stl"), {}); },
                                      {"dirty.stl", "PrepareParams::wrap"});
    PrepareParams p;
    p.wrap = true;
    p.wrapping.alpha = 0.1;
    p.remesh = true;
    p.remeshing.size = 0.08;
    PrepareReport rep;
    const SurfaceMesh m = prepare_surface(dir.file("dirty.stl"), p, &rep);
    EXPECT_TRUE(rep.wrapped);
    EXPECT_TRUE(rep.remeshed);
    EXPECT_EQ(rep.wrap.input_faces, 2 * 1280 - 2 + 2);
    EXPECT_LT(rep.wrap.wrap_to_input, 0.1);
    EXPECT_TRUE(test::closed_manifold(m));
    Index nc = 0;
    face_components(m, &nc);
    EXPECT_EQ(nc, 1);
    // The remeshed wrap keeps to the spheres: every node away from the fin (which it wraps too)
    // within the offset and a facet's depth, but where the spheres cross: the wrap bridges
    // that concave crease, nothing of it narrower than α (0.1) followed.
    const Vec3 fin = dirty_spheres().points.back();
    for (const Vec3& x : m.points) {
        if ((x - fin).norm() < 0.2) continue;
        const double to_a = std::abs(x.norm() - 1.0), to_b = std::abs((x - Vec3(1.2, 0.1, 0)).norm() - 0.8);
        const bool crease = to_a < 0.1 && to_b < 0.1;
        EXPECT_LT(std::min(to_a, to_b), crease ? 0.1 : 0.03) << format_point(x);
    }
    // Only walls are wrapped: a symmetry plane's cut would be closed over.
    p.patch_kinds = {{"hull", PatchKind::Symmetry}};
    test::expect_error<InputError>([&] { (void)prepare_surface(dir.file("dirty.stl"), p); },
                                   {"dirty.stl", "'hull' is symmetry", "hull=wall"});
}

TEST(Prepare, PatchesAreRenamedAndThoseGivenOneNameMerged) {
    SurfaceMesh m = test::merged(test::merged(icosphere(Vec3::Zero(), 1.0, 1, {"surface_1", PatchKind::Wall}),
                                              icosphere(Vec3(3, 0, 0), 1.0, 1, {"surface_2", PatchKind::Wall})),
                                 icosphere(Vec3(6, 0, 0), 1.0, 1, {"surface_3", PatchKind::Symmetry}));
    const Index faces = m.num_faces();
    SurfaceMesh one = m;
    rename_patches(one, {{"surface_1", "fuselage"}, {"surface_2", "fuselage"}, {"surface_3", "mirror-plane"}}, "t");
    ASSERT_EQ(one.patches.size(), 2u);
    EXPECT_EQ(one.patches[0].name, "fuselage");
    EXPECT_EQ(one.patches[1].name, "mirror-plane");
    EXPECT_EQ(one.patches[1].kind, PatchKind::Symmetry);
    EXPECT_EQ(one.num_faces(), faces);
    EXPECT_EQ(std::count(one.face_patch.begin(), one.face_patch.end(), 0), 2 * faces / 3);
    // Unknown patch, a name a solver would not take, two kinds under one name: refused by name.
    test::expect_error<InputError>([&] { rename_patches(m, {{"wing", "w"}}, "t.stl"); },
                                   {"t.stl", "no patch named 'wing'", "surface_1, surface_2, surface_3"});
    for (const char* bad : {"has space", "1st", "a/b", "x(1)", "abcdefghijabcdefghijabcdefghijabc"})
        test::expect_error<InputError>([&] { rename_patches(m, {{"surface_1", bad}}, "t.stl"); },
                                       {"t.stl", bad, "must start with a letter or _"});
    test::expect_error<InputError>([&] { rename_patches(m, {{"surface_1", "surface_3"}}, "t.stl"); },
                                   {"kinds wall and symmetry", "'surface_3'"});
    // An STL solid's name as written in the file names the patch the reader made a word of it.
    SurfaceMesh solid = icosphere(Vec3::Zero(), 1.0, 1, {"Wing_Body_left", PatchKind::Wall});
    rename_patches(solid, {{"Wing Body (left)", "wing"}}, "t");
    EXPECT_EQ(solid.patches[0].name, "wing");
    assign_patch_kinds(solid, {{"wing", PatchKind::Symmetry}}, "t");
    EXPECT_EQ(solid.patches[0].kind, PatchKind::Symmetry);
    // A CAD body's name (either form) names all its patches: kinds and a new name set at once.
    SurfaceMesh bodies = test::merged(test::merged(icosphere(Vec3::Zero(), 1.0, 1, {"surface_1", PatchKind::Wall, "Part 2"}),
                                                   icosphere(Vec3(3, 0, 0), 1.0, 1, {"surface_2", PatchKind::Wall, "Part 2"})),
                                      icosphere(Vec3(6, 0, 0), 1.0, 1, {"surface_3", PatchKind::Wall, "Part 1"}));
    assign_patch_kinds(bodies, {{"Part_2", PatchKind::Symmetry}}, "t");
    EXPECT_EQ(bodies.patches[0].kind, PatchKind::Symmetry);
    EXPECT_EQ(bodies.patches[1].kind, PatchKind::Symmetry);
    EXPECT_EQ(bodies.patches[2].kind, PatchKind::Wall);
    rename_patches(bodies, {{"Part 2", "mirror"}}, "t");
    ASSERT_EQ(bodies.patches.size(), 2u);
    EXPECT_EQ(bodies.patches[0].name, "mirror");
    test::expect_error<InputError>([&] { assign_patch_kinds(bodies, {{"Part 3", PatchKind::Wall}}, "t.step"); },
                                   {"no patch named 'Part 3'", "the bodies (each naming all its patches): 'Part 2', 'Part 1'"});
    // A patch that keeps its name is not merged with another of the same name it did not get.
    SurfaceMesh twice = test::merged(icosphere(Vec3::Zero(), 1.0, 1, {"p", PatchKind::Wall}),
                                     icosphere(Vec3(3, 0, 0), 1.0, 1, {"p", PatchKind::Wall}));
    rename_patches(twice, {}, "t");
    EXPECT_EQ(twice.patches.size(), 2u);
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
