#!/usr/bin/env bash
# The whole pipeline's wall-clock time on the repository's cases: `strata mesh` with the default
# options (2 threads for the layers, one for TetGen), reading the input and writing `.cgr`,
# printed as the README's Speed table (input, options, cells by type, seconds). One run per row:
# for a ratio that survives a noisy machine use farm-bench on a row instead.
#
#   scripts/pipeline_times.sh [BUILD_DIR] [WORK_DIR]     (defaults: build, a temporary directory)
#
# Exit status 0 whatever the meshes are like (a failed row says so): this measures, the tests assert.
set -euo pipefail

# shellcheck source=lib.sh
source "$(dirname "$0")/lib.sh"
measure_setup "$@"
d=$root/examples/data

# "input shown|options shown|arguments" (the arguments' paths relative to examples/data)
rows=(
  "\`sphere.stl\`|\`--layers 10 --first-height 0.001\`|sphere.stl --layers 10 --first-height 0.001"
  "\`onera_m6_sharp_te.stp\` (the README's first command)|\`--size 30 --layers 20 --first-height 0.02 --growth 1.2\`|onera_m6_sharp_te.stp --size 30 --layers 20 --first-height 0.02 --growth 1.2"
  "\`wing_fuselage.step\` (in metres, as it declares)|\`--fuse --layers 5 --first-height 5e-5\`|wing_fuselage.step --fuse --layers 5 --first-height 5e-5"
  "\`bl3d_5_body_fin_in_box.brep\` (sides farfield)|\`--layers 20 --first-height 5e-4 --growth 1.15\`|bl3d_5_body_fin_in_box.brep --patch surface_1=farfield --patch surface_2=farfield --patch surface_4=farfield --patch surface_6=farfield --layers 20 --first-height 5e-4 --growth 1.15"
  "\`hemisphere_cylinder_halfdomain.stp\` (above: farfield, symmetry and outflow patches)|\`--size 10 --curvature 40 --size-min 0.02 --layers 20 --first-height 0.001 --growth 1.2\`|hemisphere_cylinder_halfdomain.stp --size 10 --curvature 40 --size-min 0.02 --patch surface_1=farfield --patch surface_2=symmetry --patch surface_3=other --layers 20 --first-height 0.001 --growth 1.2"
  "\`onera_m6_pyhyp_quads.msh\` (half model)|\`--layers 20 --first-height 1e-5 --growth 1.15 --farfield box\`|onera_m6_pyhyp_quads.msh --layers 20 --first-height 1e-5 --growth 1.15 --farfield box"
  "\`onera_m6_mixed_quadtri.msh\`|\`--layers 5 --first-height 0.01\`|onera_m6_mixed_quadtri.msh --layers 5 --first-height 0.01"
  "\`onera_m6_brepmesh_needles.stl\` (above: a needle STL)|\`--layers 20 --first-height 0.1\`|onera_m6_brepmesh_needles.stl --layers 20 --first-height 0.1"
  "the same, remeshed (above)|\`--remesh --layers 20 --first-height 0.1\`|onera_m6_brepmesh_needles.stl --remesh --layers 20 --first-height 0.1"
  "\`missile_parts/*.stl\` (five overlapping parts)|\`--fuse --layers 5 --first-height 1e-3\`|missile_parts/body.stl missile_parts/fin1.stl missile_parts/fin2.stl missile_parts/fin3.stl missile_parts/fin4.stl --fuse --layers 5 --first-height 1e-3"
  "the same, \`--fuse --remesh\`|the same|missile_parts/body.stl missile_parts/fin1.stl missile_parts/fin2.stl missile_parts/fin3.stl missile_parts/fin4.stl --fuse --remesh --layers 5 --first-height 1e-3"
  "\`wing_fuselage_brepmesh.stl\` (touching halves, above)|\`--fuse --remesh --layers 5 --first-height 0.1\`|wing_fuselage_brepmesh.stl --fuse --remesh --layers 5 --first-height 0.1"
  "\`blade_sharp_edge.geo\` (below)|\`--size 0.1 --layers 20 --first-height 1e-3\`|blade_sharp_edge.geo --size 0.1 --layers 20 --first-height 1e-3"
  "\`two_blades_narrow_gap.geo\` (below)|the same|two_blades_narrow_gap.geo --size 0.1 --layers 20 --first-height 1e-3"
  "\`fin_on_body.geo\` (below)|\`--fuse\`, the same|fin_on_body.geo --fuse --size 0.1 --layers 20 --first-height 1e-3"
  "\`two_spheres_narrow_gap.geo\` (above)|\`--size 0.05 --layers 30 --first-height 1e-4 --growth 1.2\`|two_spheres_narrow_gap.geo --size 0.05 --layers 30 --first-height 1e-4 --growth 1.2"
  "\`naca0012_wing_between_walls.geo\` (every patch a wall)|\`--internal --layers 30 --first-height 1e-4 --growth 1.2\`|naca0012_wing_between_walls.geo --internal --layers 30 --first-height 1e-4 --growth 1.2"
  "\`wing_fuselage.step --fuse\` (used to fold at layer 28 and stop)|\`--layers 30 --first-height 1e-4 --growth 1.2\`|wing_fuselage.step --fuse --layers 30 --first-height 1e-4 --growth 1.2"
  "\`onera_m6_mixed_quadtri.msh\` (used to stop at the pyramids)|\`--layers 10 --first-height 0.08 --growth 1.2\`|onera_m6_mixed_quadtri.msh --layers 10 --first-height 0.08 --growth 1.2"
  "\`examples/missile/missile.geo\` (the paper's finned missile, half model)|\`--patch outflow=other --layers 30 --first-height 1e-5 --growth 1.2\`|../missile/missile.geo --patch outflow=other --layers 30 --first-height 1e-5 --growth 1.2"
  "\`examples/fighter/fighter.geo\` (the paper's fighter, half model, inlet duct)|\`--layers 30 --first-height 1e-4 --growth 1.2\`|../fighter/fighter.geo --layers 30 --first-height 1e-4 --growth 1.2"
  "\`examples/fighter/fighter_fine.geo\` (3.2x the faces)|the same|../fighter/fighter_fine.geo --layers 30 --first-height 1e-4 --growth 1.2"
)

echo "| input | options | cells (hex, prism, pyramid, tet) | s |"
echo "|---|---|---|---|"
i=0
for row in "${rows[@]}"; do
  IFS='|' read -r shown options arguments <<< "$row"
  read -r -a words <<< "$arguments"
  args=()
  for w in "${words[@]}"; do
    if [[ $w != --* && -e $d/$w ]]; then args+=("$d/$w"); else args+=("$w"); fi
  done
  i=$((i + 1))
  out=$work/row$i
  start=$(date +%s.%N)
  if ! (cd "$work" && "$strata" mesh "${args[@]}" -o "$out.cgr" > "$out.log" 2>&1); then
    echo "| $shown | $options | failed: $(grep -m1 -i error "$out.log" | cut -c1-100) | |"
    continue
  fi
  seconds=$(echo "$(date +%s.%N) - $start" | bc)
  cells=$(grep -m1 '^cells:' "$out.log" |
    sed -E 's/^cells: (([0-9]+) hexahedra, )?(([0-9]+) prisms, )?(([0-9]+) pyramids, )?(([0-9]+) tetrahedra)?.*/\2,\4,\6,\8/' |
    awk -F, '{printf "%d, %d, %d, %d", $1, $2, $3, $4}')
  printf '| %s | %s | %s | %.1f |\n' "$shown" "$options" "$cells" "$seconds"
done
