#pragma once
/// \file
/// The paper's first example rebuilt (Thompson, Chalasani & Soni, section 5.1; ALGORITHM.md
/// section 7): a notional Apollo command + service module as a body of revolution about the
/// x axis, meshed with 1580 structured quadrilaterals and 20 triangles around a 20-valent
/// nose node, open at the nozzle exit lip.

#include <strata/core/surface_mesh.h>
#include <strata/module/layers.h>

namespace strata {

/// Nodes around the circumference (and triangles around the nose apex).
inline constexpr int kApolloSectors = 20;
/// Rings of nodes behind the nose apex; ring 1 closes the triangle fan, ring 80 is the
/// nozzle exit lip. 79 bands of 20 quads between them: 1580 quads.
inline constexpr int kApolloRings = 80;

/// The surface, metres, x along the axis from the nose apex (x = 0) aft. Meridian, nose to
/// tail (the stack as it flies, command module apex first; the CM's spherical heat shield is
/// its aft face, mated to the service module and so not part of the outer surface):
///   - nose cap: sphere of radius 0.6 m tangent to the cone (the CM's blunt forward end);
///   - command module cone: 33° half angle, widening aft;
///   - toroidal shoulder, radius 0.2 m, blending the cone into the service module;
///   - service module cylinder, radius 1.95 m, 4.7 m long;
///   - aft rim rounded with radius 0.15 m, flat base down to radius 0.55 m;
///   - engine nozzle bell, 2.8 m long, radius 0.55 → 1.25 m (20° at its root, so a 70° concave
///     corner with the base; 7.7° at the lip), ending at the exit lip x = const.
/// 80 stations along the meridian by arc length, clustered at the shoulder, the aft rim, the
/// base/nozzle corner and the lip. Node 0 is the apex, node 1 + (i − 1)·20 + j is station i,
/// sector j (angle 2πj/20 from +y towards +z). Faces point out of the body; one patch
/// "apollo", kind Wall. The only open boundary is the exit lip, a loop of 20 nodes in the
/// plane x = x_exit, which extrude_layers keeps its nodes in.
SurfaceMesh apollo_surface();

/// The example's layer parameters, the paper's choices where it states them: 30 layers, the
/// hyperbolic-tangent distribution with a first height of 1 mm and a total thickness of
/// 0.3 m (outermost layer 23 mm; the thickness stays well below the nose-cap and nozzle
/// radii), at least the paper's ten point-Jacobi sweeps per layer and up to 50 while the
/// residual stays high (the concave base/nozzle corner takes 30–45 in the outer layers),
/// everything else at the module's defaults.
LayerParams apollo_layer_params();

}  // namespace strata
