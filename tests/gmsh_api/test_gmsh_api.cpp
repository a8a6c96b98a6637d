// The Gmsh-API entry point, used as a Gmsh user would: their own gmsh::initialize, an OCC
// sphere meshed in 2D, strata::mesh_current_gmsh_model, then the result asserted from the Gmsh
// model itself (element counts by type, physical groups and their names), written with
// gmsh::write and read back. Also: no gmsh::initialize -> InputError; a failure leaves the
// user's model as it was; add_volume_to_gmsh_model next to a mesh the model already holds.

#include "test_support.h"

#include <strata/core/error.h>
#include <strata/core/progress.h>
#include <strata/core/validate.h>
#include <strata/gmsh_api/gmsh_api.h>
#include <strata/io/gmsh_model.h>
#include <strata/io/write_volume.h>

#include <gmsh.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace strata {
namespace {

constexpr int kTriangle3 = 2;  // Gmsh element types
constexpr int kQuad4 = 3;
constexpr int kTet4 = 4;
constexpr int kHex8 = 5;
constexpr int kPrism6 = 6;
constexpr int kPyramid5 = 7;

/// The user's side: Gmsh initialised and finalised around one test.
class UserGmsh {
public:
    UserGmsh() {
        gmsh::initialize();
        gmsh::option::setNumber("General.Terminal", 0);
    }
    ~UserGmsh() { gmsh::finalize(); }
    UserGmsh(const UserGmsh&) = delete;
    UserGmsh& operator=(const UserGmsh&) = delete;
};

/// A unit sphere (OCC) in a model named "sphere", meshed in 2D with triangles of size ~\p h.
void sphere_surface_mesh(double h) {
    gmsh::model::add("sphere");
    gmsh::model::occ::addSphere(0, 0, 0, 1.0);
    gmsh::model::occ::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeMax", h);
    gmsh::model::mesh::generate(2);
}

/// Number of elements of Gmsh type \p type in the whole current model.
std::size_t count_elements(int type) {
    std::vector<std::size_t> tags, nodes;
    gmsh::model::mesh::getElementsByType(type, tags, nodes, -1);
    return tags.size();
}

/// Physical-group names of dimension \p dim, by name -> entity tags.
std::map<std::string, std::vector<int>> groups(int dim) {
    gmsh::vectorpair dim_tags;
    gmsh::model::getPhysicalGroups(dim_tags, dim);
    std::map<std::string, std::vector<int>> out;
    for (const auto& [d, tag] : dim_tags) {
        std::string name;
        gmsh::model::getPhysicalName(d, tag, name);
        std::vector<int> entities;
        gmsh::model::getEntitiesForPhysicalGroup(d, tag, entities);
        out[name] = entities;
    }
    return out;
}

HybridParams ten_layers() {
    HybridParams p;
    p.layers.distribution.layers = 10;
    p.layers.distribution.first_height = 1e-3;
    p.layers.distribution.growth = 1.2;
    return p;
}

/// Run \p f, expect an InputError whose message contains \p part.
template <class F>
void expect_input_error(F&& f, const std::string& part) {
    test::expect_error<InputError>(std::forward<F>(f), {part});
}

/// A 1D physical group \p tag on the current model's first curve.
void group_on_first_curve(int tag) {
    gmsh::vectorpair curves;
    gmsh::model::getEntities(curves, 1);
    ASSERT_FALSE(curves.empty());
    gmsh::model::addPhysicalGroup(1, {curves.front().second}, tag);
}

TEST(GmshApi, SphereMeshedInPlaceThenWrittenAndReadBack) {
    test::ScratchDir dir("gmsh_api_sphere");
    UserGmsh user;
    sphere_surface_mesh(0.25);
    // The user's own groups: the sphere's surface named "hull", and a 1D group on its seam that
    // the replacement must remove with the old mesh.
    gmsh::model::addPhysicalGroup(2, {1}, 7);
    gmsh::model::setPhysicalName(2, 7, "hull");
    ASSERT_NO_FATAL_FAILURE(group_on_first_curve(3));
    const std::size_t wall_triangles = count_elements(kTriangle3);
    ASSERT_GT(wall_triangles, 100u);
    ASSERT_EQ(count_elements(kQuad4), 0u);

    const HybridReport report = mesh_current_gmsh_model(ten_layers());
    EXPECT_EQ(report.layers.stats.size(), 10u);
    EXPECT_TRUE(report.validation.ok());
    EXPECT_GT(report.validation.min_scaled_jacobian, 0.0);

    // The same model, now holding the volume mesh.
    std::string current;
    gmsh::model::getCurrent(current);
    EXPECT_EQ(current, "sphere");
    const std::size_t prisms = count_elements(kPrism6), tets = count_elements(kTet4);
    EXPECT_EQ(prisms, 10 * wall_triangles);  // one prism per wall triangle per layer
    EXPECT_GT(tets, 0u);
    EXPECT_EQ(count_elements(kPyramid5), 0u);  // an all-triangle wall: no quads to cap
    EXPECT_EQ(count_elements(kHex8), 0u);
    EXPECT_EQ(static_cast<Index>(prisms + tets), report.validation.cells);
    std::vector<int> types;
    gmsh::model::mesh::getElementTypes(types, 1);
    EXPECT_TRUE(types.empty()) << "the old mesh's line elements are still there";
    types.clear();
    gmsh::model::mesh::getElementTypes(types, 2, 1);
    EXPECT_TRUE(types.empty()) << "the old surface mesh is still on the OCC surface";

    const auto g3 = groups(3);
    ASSERT_EQ(g3.size(), 1u);
    ASSERT_EQ(g3.count("fluid"), 1u);
    ASSERT_EQ(g3.at("fluid").size(), 1u);
    const int fluid_volume = g3.at("fluid").front();
    types.clear();
    gmsh::model::mesh::getElementTypes(types, 3, fluid_volume);
    std::sort(types.begin(), types.end());
    EXPECT_EQ(types, (std::vector<int>{kTet4, kPrism6}));
    EXPECT_TRUE(groups(1).empty()) << "the user's old 1D group survived";

    const auto g2 = groups(2);
    EXPECT_EQ(g2.size(), 2u);
    ASSERT_EQ(g2.count("hull"), 1u);
    ASSERT_EQ(g2.count("farfield"), 1u);  // generated: the sphere has no farfield patch
    ASSERT_EQ(g2.at("hull").size(), 1u);
    std::vector<std::size_t> tags, nodes;
    gmsh::model::mesh::getElementsByType(kTriangle3, tags, nodes, g2.at("hull").front());
    EXPECT_EQ(tags.size(), wall_triangles);
    tags.clear();
    nodes.clear();
    gmsh::model::mesh::getElementsByType(kTriangle3, tags, nodes, g2.at("farfield").front());
    EXPECT_GT(tags.size(), 0u);

    // The user's gmsh::write, then Strata's reader on the file.
    const std::string path = dir.file("sphere_hybrid.msh");
    gmsh::write(path);
    const VolumeMesh back = read_volume_msh(path);
    EXPECT_EQ(back.prisms.size(), prisms);
    EXPECT_EQ(back.tets.size(), tets);
    const ValidationReport v = validate_mesh(back);
    EXPECT_TRUE(v.ok());
    EXPECT_EQ(v.cells, report.validation.cells);
    std::set<std::string> names;
    for (const Patch& p : back.boundary.patches) names.insert(p.name);
    EXPECT_EQ(names, (std::set<std::string>{"hull", "farfield"}));

    // read_volume_msh's GmshSession neither finalised the user's Gmsh nor changed its model.
    current.clear();
    gmsh::model::getCurrent(current);
    EXPECT_EQ(current, "sphere");
    EXPECT_EQ(count_elements(kPrism6), prisms);
}

TEST(GmshApi, WithoutInitializeThrowsInputError) {
    // Never initialised in this process (ctest runs each test alone) or already finalised by
    // another test: either way an InputError, not a crash nor a silent no-op.
    expect_input_error([] { mesh_current_gmsh_model(ten_layers()); }, "call gmsh::initialize() first");
    gmsh::initialize();
    gmsh::finalize();
    // Finalised by the user: the same.
    expect_input_error([] { mesh_current_gmsh_model(ten_layers()); }, "Gmsh is not initialised");
    expect_input_error([] { add_volume_to_gmsh_model(VolumeMesh{}); }, "call gmsh::initialize() first");
}

TEST(GmshApi, FailuresLeaveTheUsersModelAsItWas) {
    UserGmsh user;
    // No surface mesh yet: nothing to build on.
    gmsh::model::add("unmeshed");
    gmsh::model::occ::addSphere(0, 0, 0, 1.0);
    gmsh::model::occ::synchronize();
    expect_input_error([] { mesh_current_gmsh_model(ten_layers()); }, "no triangles or quadrangles");

    // An unknown --patch name: the error lists the patches, the model keeps its mesh and groups.
    sphere_surface_mesh(0.5);
    gmsh::model::addPhysicalGroup(2, {1}, 1);
    gmsh::model::setPhysicalName(2, 1, "hull");
    const std::size_t triangles = count_elements(kTriangle3);
    PrepareParams prepare;
    prepare.patch_kinds = {{"wing", PatchKind::Wall}};
    expect_input_error([&] { mesh_current_gmsh_model(ten_layers(), prepare); }, "hull");
    EXPECT_EQ(count_elements(kTriangle3), triangles);
    EXPECT_EQ(count_elements(kTet4) + count_elements(kPrism6), 0u);
    EXPECT_EQ(groups(2).count("hull"), 1u);
}

/// Two OCC spheres 0.0118 apart (examples/data/two_spheres_narrow_gap.geo) meshed in 2D at 0.1.
void two_spheres_surface_mesh() {
    gmsh::model::add("two_spheres");
    gmsh::model::occ::addSphere(0, 0, 0, 0.5);
    gmsh::model::occ::addSphere(1.0118, 0, 0, 0.5);
    gmsh::model::occ::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeMax", 0.1);
    gmsh::model::mesh::generate(2);
}

/// 12 layers from 1e-3: they step at the spheres' gap.
HybridParams twelve_layers() {
    HybridParams p;
    p.layers.distribution.layers = 12;
    p.layers.distribution.first_height = 1e-3;
    p.layers.distribution.growth = 1.2;
    return p;
}

/// Triangles on the 2D physical groups other than "farfield": the walls'.
std::size_t wall_triangles() {
    std::size_t n = 0;
    for (const auto& [name, entities] : groups(2)) {
        if (name == "farfield") continue;
        for (const int e : entities) {
            std::vector<std::size_t> tags, nodes;
            gmsh::model::mesh::getElementsByType(kTriangle3, tags, nodes, e);
            n += tags.size();
        }
    }
    return n;
}

/// Cancels the run once the layers start: after the walls were prepared.
class CancelAtLayers : public Progress {
public:
    void report(std::string_view stage, double) override { stop_ = stop_ || stage == "layers"; }
    bool cancelled() const override { return stop_; }

private:
    bool stop_ = false;
};

TEST(GmshApi, CadWallsAreMeshedAgainWhereTheLayersStepAtAGap) {
    // As the strata program does on the .geo: the walls facing the gap meshed finer for the
    // layers' steps there (prepare_for_layers); without steps or aspect limits, the user's mesh.
    std::size_t user = 0, kept = 0, finer = 0;
    {
        UserGmsh gmsh_user;
        two_spheres_surface_mesh();
        user = count_elements(kTriangle3);
        PrepareParams as_given;
        as_given.cad.step_quality = 0.0;
        as_given.cad.max_aspect_ratio = 0.0;
        EXPECT_TRUE(mesh_current_gmsh_model(twelve_layers(), as_given).validation.ok());
        kept = wall_triangles();
    }
    {
        UserGmsh gmsh_user;
        two_spheres_surface_mesh();
        const HybridReport report = mesh_current_gmsh_model(twelve_layers());
        EXPECT_TRUE(report.validation.ok());
        finer = wall_triangles();
    }
    EXPECT_EQ(kept, user);
    EXPECT_GT(finer, 2 * user);
}

TEST(GmshApi, AFailureAfterTheWallsWereMeshedAgainPutsTheUsersMeshBack) {
    UserGmsh gmsh_user;
    two_spheres_surface_mesh();
    const std::size_t triangles = count_elements(kTriangle3), lines = count_elements(1);
    CancelAtLayers cancel;
    EXPECT_THROW(mesh_current_gmsh_model(twelve_layers(), {}, &cancel), Cancelled);
    EXPECT_EQ(count_elements(kTriangle3), triangles);
    EXPECT_EQ(count_elements(1), lines);
    EXPECT_EQ(count_elements(kTet4) + count_elements(kPrism6), 0u);
}

TEST(GmshApi, AddVolumeNextToAnExistingMeshOffsetsEveryTag) {
    UserGmsh user;
    sphere_surface_mesh(0.5);
    gmsh::model::addPhysicalGroup(2, {1}, 1);
    gmsh::model::setPhysicalName(2, 1, "hull");
    std::vector<std::size_t> old_nodes;
    std::vector<double> xyz, parametric;
    gmsh::model::mesh::getNodes(old_nodes, xyz, parametric);
    const std::size_t triangles = count_elements(kTriangle3);

    // One tetrahedron far from the sphere, its four faces on patch "box".
    VolumeMesh tet;
    tet.points = {Vec3(5, 0, 0), Vec3(6, 0, 0), Vec3(5, 1, 0), Vec3(5, 0, 1)};
    tet.tets = {{0, 1, 2, 3}};
    tet.boundary.patches = {{"box", PatchKind::Wall}};
    for (auto f : {std::array<Index, 3>{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}})
        tet.boundary.add_face(f.data(), 3, 0);
    // A 2D group of the patch's name is the user's: an error, nothing added. Once the user has
    // removed it (Gmsh 4.8 keeps the removed group's name, which would silently block naming a
    // new group), the patch gets the name; a 1D group of that name keeps it.
    gmsh::model::addPhysicalGroup(2, {1}, 5);
    gmsh::model::setPhysicalName(2, 5, "box");
    ASSERT_NO_FATAL_FAILURE(group_on_first_curve(4));
    gmsh::model::setPhysicalName(1, 4, "box");
    expect_input_error([&] { add_volume_to_gmsh_model(tet); }, "2D physical group named 'box'");
    EXPECT_EQ(count_elements(kTet4), 0u);
    gmsh::model::removePhysicalGroups({{2, 5}});
    add_volume_to_gmsh_model(tet);
    EXPECT_EQ(groups(1).count("box"), 1u);

    // The old mesh and group are intact, the new ones sit beside them.
    EXPECT_EQ(count_elements(kTriangle3), triangles + 4);
    EXPECT_EQ(count_elements(kTet4), 1u);
    std::vector<std::size_t> all_nodes;
    gmsh::model::mesh::getNodes(all_nodes, xyz, parametric);
    EXPECT_EQ(all_nodes.size(), old_nodes.size() + 4);
    const auto g2 = groups(2);
    EXPECT_EQ(g2.size(), 2u);
    EXPECT_EQ(g2.at("hull"), std::vector<int>{1});
    ASSERT_EQ(g2.count("box"), 1u);
    EXPECT_NE(g2.at("box").front(), 1);
    ASSERT_EQ(groups(3).count("fluid"), 1u);
    const int volume = groups(3).at("fluid").front();
    EXPECT_NE(volume, 1);  // the OCC sphere's own volume keeps tag 1
    std::vector<std::size_t> tags, nodes;
    gmsh::model::mesh::getElementsByType(kTet4, tags, nodes, volume);
    ASSERT_EQ(nodes.size(), 4u);
    const std::size_t max_old = *std::max_element(old_nodes.begin(), old_nodes.end());
    for (std::size_t n : nodes) EXPECT_GT(n, max_old);
}

TEST(GmshApi, HalfDomainWithSymmetryPlanesInAUsersModel) {
    // A Gmsh user's fluid domain: a box whose floor is the wall, its sides symmetry planes and
    // its lid the farfield, as physical groups; the layers end on the sides, which Strata
    // re-meshes (in scratch models of its own) while the user's model stays current.
    UserGmsh user;
    gmsh::model::add("channel");
    gmsh::model::occ::addBox(0, 0, 0, 1, 1, 1);
    gmsh::model::occ::synchronize();
    const std::array<const char*, 6> names{"symmetry_x0", "symmetry_x1", "symmetry_y0",
                                           "symmetry_y1", "floor",       "farfield_lid"};
    for (int s = 1; s <= 6; ++s) {
        gmsh::model::addPhysicalGroup(2, {s}, s);
        gmsh::model::setPhysicalName(2, s, names[static_cast<std::size_t>(s - 1)]);
    }
    gmsh::option::setNumber("Mesh.MeshSizeMax", 0.125);
    gmsh::model::mesh::generate(2);
    std::vector<std::string> models_before, models;
    gmsh::model::list(models_before);
    const HybridReport report = mesh_current_gmsh_model(ten_layers());
    EXPECT_TRUE(report.validation.ok());
    EXPECT_NEAR(report.validation.cell_volume, 1.0, 1e-9);
    EXPECT_EQ(report.remeshed_patches.size(), 4u);
    std::string current;
    gmsh::model::getCurrent(current);
    EXPECT_EQ(current, "channel");
    gmsh::model::list(models);
    EXPECT_EQ(models, models_before) << "a scratch model was left behind";
    double size_max = 0.0;
    gmsh::option::getNumber("Mesh.MeshSizeMax", size_max);
    EXPECT_EQ(size_max, 0.125) << "the user's Gmsh options must be theirs again";
    const auto g2 = groups(2);
    for (const char* n : names) EXPECT_EQ(g2.count(n), 1u) << n;
    EXPECT_GT(count_elements(kPrism6), 0u);
    EXPECT_GT(count_elements(kTet4), 0u);
}

}  // namespace
}  // namespace strata
