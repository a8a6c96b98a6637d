#pragma once
/// \file
/// The Gmsh-API entry point: hybrid-mesh the current Gmsh model in place, between a Gmsh
/// user's `gmsh::model::mesh::generate(2)` and `gmsh::write(...)`.
///
///     gmsh::initialize();
///     gmsh::model::occ::addSphere(0, 0, 0, 1);
///     gmsh::model::occ::synchronize();
///     gmsh::model::mesh::generate(2);
///     strata::HybridParams params;
///     params.layers.distribution.layers = 10;
///     strata::mesh_current_gmsh_model(params);
///     gmsh::write("sphere_hybrid.msh");

#include <strata/core/progress.h>
#include <strata/hybrid/hybrid_mesh.h>
#include <strata/surface/prepare.h>

namespace strata {

struct FirstHeightChoice;  // strata/frontend/pipeline.h

/// Replace the current Gmsh model's surface mesh by a hybrid volume mesh built on it.
///
/// Reads the model's 3-node triangles and 4-node quadrangles with one patch per 2D physical
/// group (surface_from_gmsh_model: a surface in no group gets "surface_<tag>"), assigns patch
/// kinds (a name containing "farfield" or "symmetry" gets that kind, every other patch is a
/// wall; \p prepare.patch_kinds overrides), merges coincident nodes, checks and orients the
/// surface (prepare_mesh), and builds the hybrid mesh with \p params (a surface without a
/// farfield patch gets a generated one, \p params.farfield): the pipeline's run() on the surface
/// given (frontend/pipeline.h), as the strata program and the Python package do on files. Where
/// the model's surfaces are all CAD (none discrete), its walls are prepared for the layers as a CAD
/// file's are (prepare_for_layers): where the layers would step at a gap or fan at a sharp edge,
/// the model is meshed again with Gmsh (its own sizes, smaller ones at those places, a size
/// callback set for the while); \p prepare.cad.step_quality and max_aspect_ratio 0 leave its mesh
/// as it is. Then the model's mesh is replaced:
/// all of its mesh (every dimension) and all of its physical groups are removed, and the
/// hybrid mesh is added as add_volume_to_gmsh_model does: one discrete volume with a 3D
/// physical group "fluid", one discrete surface and one named 2D physical group per patch
/// (the input's patch names, plus "farfield" if generated). The model's geometric entities
/// (CAD, if any) are kept, without mesh.
///
/// Gmsh must be initialised by the caller: InputError "Gmsh is not initialised: call
/// gmsh::initialize() first" otherwise. Gmsh's lock is held throughout, so other Strata calls
/// on other threads wait. If reading or meshing fails (InputError, TopologyError, BackendError
/// naming the model), the model is left as it was (its mesh put back where it was meshed again); only a Gmsh failure
/// while adding the new mesh can leave it partly replaced. \p progress as for build_hybrid_mesh.
/// With no first height asked (automatic_first_height), the one chosen from the walls goes into
/// \p first_height where given.
HybridReport mesh_current_gmsh_model(const HybridParams& params, const PrepareParams& prepare = {},
                                     Progress* progress = nullptr, FirstHeightChoice* first_height = nullptr);

}  // namespace strata
