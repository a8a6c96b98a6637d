#!/usr/bin/env bash
# The cases of issue 9 (robust layers), each meshed by `strata mesh` with the issue's settings,
# printed as one Markdown table: cells by type, the smallest scaled Jacobian per type, coverage
# (the share of wall nodes with every layer), what OpenFOAM's checkMesh will say (the summary's
# `openfoam:` line, which tests/openfoam/check_figures.sh holds to checkMesh's own figures),
# whether the 1- and 2-thread outputs are the same bytes, and the wall-clock time of the
# 2-thread run. The README's cases table is this script's output.
#
#   scripts/issue_cases.sh [BUILD_DIR] [WORK_DIR]     (defaults: build, a temporary directory)
#
# Exit status 0 whatever the meshes are like: this measures, the tests assert.
set -euo pipefail

# shellcheck source=lib.sh
source "$(dirname "$0")/lib.sh"
measure_setup "$@"
data=$root/examples/data

cases=(
  "two spheres 0.0118 apart|$data/two_spheres_narrow_gap.geo --size 0.05 --layers 30 --first-height 1e-4 --growth 1.2"
  "sphere with a fin through it, 30 layers|$data/sphere_fin_through.geo --fuse --layers 30 --first-height 1e-4 --growth 1.2"
  "the same, 10 layers from 1e-3|$data/sphere_fin_through.geo --fuse --layers 10 --first-height 1e-3 --growth 1.2"
  "box with a notch (concave corner)|$data/bl3d_4_box_notch_concave_corner.brep --patch surface_1=farfield --patch surface_2=farfield --patch surface_3=farfield --patch surface_4=farfield --patch surface_6=farfield --layers 30 --first-height 1e-4 --growth 1.2"
  "body and fin in a box|$data/bl3d_5_body_fin_in_box.brep --patch surface_1=farfield --patch surface_2=farfield --patch surface_4=farfield --patch surface_6=farfield --layers 30 --first-height 1e-4 --growth 1.2"
  "ONERA M6 sharp TE, 20 layers|$data/onera_m6_sharp_te.stp --size 30 --layers 20 --first-height 0.02 --growth 1.2"
  "ONERA M6 sharp TE, 30 layers|$data/onera_m6_sharp_te.stp --size 30 --layers 30 --first-height 0.02 --growth 1.2"
  "ONERA M6 mixed quads and triangles, 10 layers|$data/onera_m6_mixed_quadtri.msh --layers 10 --first-height 0.08 --growth 1.2"
  "wing-fuselage fused, 30 layers from 4.5e-5 (1e-4 of its 0.447 m)|$data/wing_fuselage.step --fuse --layers 30 --first-height 4.5e-5 --growth 1.2"
  "NACA 0012 between walls (internal)|$data/naca0012_wing_between_walls.geo --internal --layers 30 --first-height 1e-4 --growth 1.2"
  "M6 as a needle STL (BRepMesh), 20 layers|$data/onera_m6_brepmesh_needles.stl --layers 20 --first-height 0.1 --growth 1.2"
  "the same with --remesh|$data/onera_m6_brepmesh_needles.stl --remesh --layers 20 --first-height 0.1 --growth 1.2"
  "finned missile (the paper's), 30 layers|$root/examples/missile/missile.geo --patch outflow=other --layers 30 --first-height 1e-5 --growth 1.2"
  "fighter (the paper's), 30 layers|$root/examples/fighter/fighter.geo --layers 30 --first-height 1e-4 --growth 1.2"
)

# shellcheck source=case_table.sh
source "$root/scripts/case_table.sh"
case_table "$strata" "$work" "${cases[@]}"
