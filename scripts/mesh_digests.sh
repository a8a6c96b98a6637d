#!/usr/bin/env bash
# Print one SHA-256 per output of the strata program on the cases of
# tests/hybrid/test_hybrid_cases.cpp and the README's examples, so a refactoring can be shown
# to leave every mesh byte-identical: run it before and after, then diff the two listings.
#   scripts/mesh_digests.sh [BUILD_DIR] > digests.txt
# Each case runs `strata mesh` (Cobalt60 with its .bc map, and MSH 4.1), a few run `strata
# surface` and `strata layers` too, and two run again with --threads 1.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
strata="$build/app/strata"
data=examples/data
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

run() {  # run NAME SUBCOMMAND INPUT EXT [options...]
  local name=$1 cmd=$2 input=$3 ext=$4
  shift 4
  "$strata" "$cmd" "$input" -o "$out/$name.$ext" -q "$@"
  for f in "$out/$name.$ext" "$out/$name.$ext.bc"; do
    [ -f "$f" ] && echo "$(sha256sum < "$f" | cut -c1-64)  $(basename "$f")"
  done
  return 0
}

hemi=(--size 10 --curvature 24 --size-min 0.05 --patch surface_1=farfield --patch surface_2=symmetry
      --patch surface_3=other)
box=(--patch surface_1=farfield --patch surface_2=farfield --patch surface_4=farfield --patch surface_6=farfield)
for ext in cgr msh; do
  run sphere_stl mesh $data/sphere.stl $ext --layers 10 --first-height 1e-3
  run m6_step mesh $data/onera_m6_sharp_te.stp $ext --size 60 --layers 10 --first-height 0.02
  run hemisphere_cylinder mesh $data/hemisphere_cylinder_halfdomain.stp $ext "${hemi[@]}" --layers 15 --first-height 0.002
  run body_fin_box mesh $data/bl3d_5_body_fin_in_box.brep $ext "${box[@]}" --layers 20 --first-height 5e-4 --growth 1.15
  run wing_fuselage mesh $data/wing_fuselage.step $ext --fuse --layers 5 --first-height 5e-5
  run m6_mixed mesh $data/onera_m6_mixed_quadtri.msh $ext --layers 5 --first-height 0.01
  run two_spheres mesh $data/two_spheres_narrow_gap.geo $ext --size 0.05 --layers 30 --first-height 1e-4 --growth 1.2
  run naca0012_walls mesh $data/naca0012_wing_between_walls.geo $ext --internal --layers 30 --first-height 1e-4 --growth 1.2
done
run readme_m6 mesh $data/onera_m6_sharp_te.stp cgr --size 30 --layers 20 --first-height 0.02 --growth 1.2
run readme_m6_half mesh $data/onera_m6_pyhyp_quads.msh cgr --layers 20 --first-height 1e-5 --growth 1.15 --farfield box
run body_fin_box_t1 mesh $data/bl3d_5_body_fin_in_box.brep cgr "${box[@]}" --layers 20 --first-height 5e-4 --growth 1.15 --threads 1
run m6_mixed_t1 mesh $data/onera_m6_mixed_quadtri.msh cgr --layers 5 --first-height 0.01 --threads 1
run m6_surface surface $data/onera_m6_sharp_te.stp msh --size 40 --curvature 8
run glider_surface surface $data/wing_fuselage.step msh --fuse --quads
run m6_mixed_surface surface $data/onera_m6_mixed_quadtri.msh msh
run sphere_layers layers $data/sphere.stl msh --layers 5 --first-height 1e-3 --msh-version 2.2
run m6_half_layers layers $data/onera_m6_pyhyp_quads.msh msh --layers 20 --first-height 1e-5 --growth 1.15
