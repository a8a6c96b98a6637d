// The Gmsh adapter's trial runs (gmsh_session.h): gmsh_probe's outcomes, and
// generate_surfaces_in_child on a model whose Blossom recombination ends the process
// (examples/sweep/spiky.geo fused) and on calls that crash or abort.
#include <strata/core/error.h>
#include <strata/io/gmsh_session.h>

#include "test_support.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <csignal>
#include <stdexcept>
#include <string>
#include <vector>

namespace strata {
namespace {

using test::example_data;

[[noreturn]] void throw_out_of_the_loop() {
    throw std::runtime_error("out of the loop");
}

/// \p p ran and ended only as \p how says (returned, threw or aborted), with \p message.
void expect_ended(const GmshProbe& p, bool GmshProbe::*how, const std::string& message) {
    ASSERT_TRUE(p.ran);
    for (bool GmshProbe::*flag : {&GmshProbe::returned, &GmshProbe::threw, &GmshProbe::aborted})
        EXPECT_EQ(p.*flag, flag == how);
    EXPECT_EQ(p.message, message);
}

TEST(GmshProbe, AReturnIsReturned) {
    GmshSession session("probe_returns");
    int touched = 0;
    const GmshProbe p = gmsh_probe([&] {
        gmsh::model::occ::addBox(0, 0, 0, 1, 1, 1);
        gmsh::model::occ::synchronize();
        touched = 1;
    });
    ASSERT_TRUE(p.ran);
    EXPECT_TRUE(p.returned);
    EXPECT_FALSE(p.aborted || p.threw);
    EXPECT_EQ(p.signal, 0);
    // Nothing of the trial reaches this process: neither the variable nor Gmsh's model.
    EXPECT_EQ(touched, 0);
    gmsh::vectorpair volumes;
    gmsh::model::getEntities(volumes, 3);
    EXPECT_TRUE(volumes.empty());
}

TEST(GmshProbe, AnExceptionIsItsText) {
    GmshSession session("probe_throws");
    expect_ended(gmsh_probe([] { throw std::string("Gmsh's words"); }), &GmshProbe::threw, "Gmsh's words");
}

TEST(GmshProbe, AnAbortIsItsTextAndThisProcessLivesOn) {
    // As Gmsh 4.8 does: an exception out of a region no exception may leave (an OpenMP loop;
    // here a noexcept function) ends the process through std::terminate.
    GmshSession session("probe_aborts");
    expect_ended(gmsh_probe([] { []() noexcept { throw_out_of_the_loop(); }(); }), &GmshProbe::aborted,
                 "out of the loop");
}

TEST(GmshProbe, ACrashIsItsSignal) {
    GmshSession session("probe_crashes");
    const GmshProbe p = gmsh_probe([] { std::raise(SIGSEGV); });
    ASSERT_TRUE(p.ran);
    EXPECT_EQ(p.signal, SIGSEGV);
    EXPECT_FALSE(p.returned || p.aborted || p.threw);
}

/// The sphere with three cones fused, quads asked with Blossom at the size the sweep's quads
/// run gives it: Blossom finds no perfect matching on a cone and Gmsh throws out of its
/// OpenMP meshing loop.
void spiky_with_blossom(GmshOptionScope& options) {
    gmsh::merge(example_data("../sweep/spiky.geo"));
    gmsh::vectorpair volumes, out;
    std::vector<gmsh::vectorpair> map;
    gmsh::model::getEntities(volumes, 3);
    ASSERT_EQ(volumes.size(), 4u);
    gmsh::model::occ::fuse({volumes[0]}, gmsh::vectorpair(volumes.begin() + 1, volumes.end()), out, map);
    gmsh::model::occ::synchronize();
    options.set("Mesh.MeshSizeMax", 0.127131);
    options.set("Mesh.RecombineAll", 1);
    options.set("Mesh.RecombinationAlgorithm", 1);
}

double option(const std::string& name) {
    double v = 0.0;
    gmsh::option::getNumber(name, v);
    return v;
}

/// The quadrilaterals of the current model's mesh.
std::size_t quads_here() {
    std::vector<std::size_t> quads, quad_nodes;
    gmsh::model::mesh::getElementsByType(3, quads, quad_nodes);
    return quads.size();
}

/// In a session of its own, a unit box, quads asked with Blossom at size 0.3 (Blossom meshes it).
struct BlossomBox {
    GmshSession session;
    GmshOptionScope options;
    explicit BlossomBox(const std::string& name) : session(name) {
        gmsh::model::occ::addBox(0, 0, 0, 1, 1, 1);
        gmsh::model::occ::synchronize();
        options.set("Mesh.MeshSizeMax", 0.3);
        options.set("Mesh.RecombineAll", 1);
        options.set("Mesh.RecombinationAlgorithm", 1);
    }
};

/// The current model's mesh has more than \p quads quadrilaterals, and recombination algorithm
/// \p algorithm is Gmsh's setting (1: Blossom, 0: the simple one).
void expect_quads(double algorithm, std::size_t quads) {
    EXPECT_EQ(option("Mesh.RecombinationAlgorithm"), algorithm);
    EXPECT_GT(quads_here(), quads);
}

TEST(GenerateSurfacesInChild, BlossomsAbortFoundInAChildAndTheSimpleAlgorithmMeshesIt) {
    GmshSession session("blossom_aborts");
    GmshOptionScope options;
    spiky_with_blossom(options);
    const auto generate = [] { gmsh::model::mesh::generate(2); };
    // Not asked for quads: the surfaces are meshed as they are, and Blossom's abort is an error
    // of this process, not its end.
    test::expect_error<BackendError>([&] { generate_surfaces_in_child("spiky", false, options, generate); },
                                     {"spiky: Gmsh aborts (", "Perfect Match"});
    EXPECT_EQ(option("Mesh.RecombinationAlgorithm"), 1.0);
    const std::string failure = generate_surfaces_in_child("spiky", true, options, generate);
    EXPECT_NE(failure.find("Perfect Match failed"), std::string::npos) << failure;
    // The simple algorithm's quads are brought back here.
    expect_quads(0.0, 100u);
}

TEST(GenerateSurfacesInChild, BlossomsMeshIsBroughtBackMadeOnce) {
    BlossomBox box("blossom_ok");
    int here = 0;  // calls of generate in this process: none, the child's mesh is taken
    const pid_t parent = getpid();
    EXPECT_EQ(generate_surfaces_in_child("box", true, box.options,
                                         [&] {
                                             if (getpid() == parent) ++here;
                                             gmsh::model::mesh::generate(2);
                                         }),
              "");
    EXPECT_EQ(here, 0);
    expect_quads(1.0, 20u);
}

TEST(GenerateSurfacesInChild, ACrashOfBlossomFallsBackToTheSimpleAlgorithm) {
    // Blossom also crashes without words of its own (a segmentation fault on a body with a
    // mirror on a thin stalk: test_cad); where the simple recombination goes through, it is used.
    BlossomBox box("blossom_crashes");
    GmshOptionScope& options = box.options;
    const auto crashes_with_blossom = [] {
        if (option("Mesh.RecombinationAlgorithm") == 1.0) std::raise(SIGSEGV);
        gmsh::model::mesh::generate(2);
    };
    EXPECT_EQ(generate_surfaces_in_child("the model", true, options, crashes_with_blossom), "crashes (signal 11)");
    expect_quads(0.0, 20u);
    // Where the simple one crashes too, one error says both, and nothing ends this process.
    options.set("Mesh.RecombinationAlgorithm", 1);
    test::expect_error<BackendError>(
        [&] { generate_surfaces_in_child("the model", true, options, [] { std::raise(SIGSEGV); }); },
        {"the model: quads cannot be made here: Gmsh's Blossom recombination crashes (signal 11) and with its "
         "simple recombination Gmsh crashes (signal 11)"});
}

/// Every entity's nodes (tag, coordinates) and elements (type, tag, nodes) of the current model.
struct ModelMesh {
    std::vector<std::size_t> node_tags;
    std::vector<double> xyz;
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> element_tags, element_nodes;
};
ModelMesh model_mesh() {
    ModelMesh m;
    std::vector<double> uvw;
    gmsh::model::mesh::getNodes(m.node_tags, m.xyz, uvw);
    gmsh::model::mesh::getElements(m.types, m.element_tags, m.element_nodes);
    return m;
}

/// A sphere and a box as OCC entities, to mesh.
void two_solids() {
    gmsh::model::occ::addSphere(0, 0, 0, 1);
    gmsh::model::occ::addBox(2, 0, 0, 1, 0.5, 0.25);
    gmsh::model::occ::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeMax", 0.3);
}

TEST(GenerateInChild, BringsBackTheMeshGmshWouldHaveMadeHere) {
    ModelMesh here, there;
    {
        GmshSession session("generated_here");
        two_solids();
        gmsh::model::mesh::generate(2);
        here = model_mesh();
    }
    {
        GmshSession session("generated_there");
        two_solids();
        generate_in_child("two solids", [] { gmsh::model::mesh::generate(2); });
        there = model_mesh();
    }
    ASSERT_GT(here.node_tags.size(), 100u);
    EXPECT_EQ(there.node_tags, here.node_tags);
    EXPECT_EQ(there.xyz, here.xyz);
    EXPECT_EQ(there.types, here.types);
    EXPECT_EQ(there.element_tags, here.element_tags);
    EXPECT_EQ(there.element_nodes, here.element_nodes);
}

TEST(GenerateInChild, ReplacesTheWholeMeshTheModelHad) {
    // A mesh already there (here a coarser one) is replaced, not added to: no node of it stays.
    GmshSession session("regenerated");
    two_solids();
    gmsh::option::setNumber("Mesh.MeshSizeMax", 0.6);
    gmsh::model::mesh::generate(2);
    const std::size_t coarse = model_mesh().node_tags.size();
    gmsh::option::setNumber("Mesh.MeshSizeMax", 0.2);
    generate_in_child("two solids", [] { gmsh::model::mesh::generate(2); });
    const ModelMesh fine = model_mesh();
    gmsh::model::mesh::generate(2);
    EXPECT_EQ(fine.node_tags, model_mesh().node_tags);
    EXPECT_GT(fine.node_tags.size(), coarse);
}

TEST(GenerateInChild, ACrashAnAbortOrAStopEndsOnlyTheChild) {
    GmshSession session("generate_fails");
    two_solids();
    test::expect_error<BackendError>(
        [] { generate_in_child("the model", [] { std::raise(SIGSEGV); }); },
        {"the model: Gmsh crashes (signal 11) meshing the surfaces (in a child process: nothing else is lost"});
    test::expect_error<BackendError>(
        [] { generate_in_child("the model", [] { []() noexcept { throw_out_of_the_loop(); }(); }); },
        {"the model: Gmsh aborts (out of the loop)"});
    // Meshing that would not end (Gmsh's refinement on a surface it parametrizes badly) is
    // stopped where the caller's progress says so, and nothing of it reaches this model (this
    // child computes nothing: it is stopped after DeadlineProgress::kWallFactor times 0.1 s).
    DeadlineProgress deadline(0.1);
    EXPECT_THROW(generate_in_child(
                     "the model",
                     [] {
                         for (;;) pause();
                     },
                     &deadline),
                 Cancelled);
    EXPECT_TRUE(model_mesh().node_tags.empty());
}

}  // namespace
}  // namespace strata
