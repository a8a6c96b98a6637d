#!/usr/bin/env bash
# The paper's third example rebuilt (Thompson, Chalasani & Soni, section 5.3): a notional
# fighter, half model, with a chin inlet whose duct ends inside the aircraft
# (examples/fighter/fighter.geo). Three jobs into out/, from the root of the repository, then
# their figures:
#   1. the all-prism layers alone, at the paper's resolution   out/fighter_layers.msh
#   2. the complete hybrid mesh, same surface                  out/fighter.msh
#   3. the complete hybrid mesh, its walls meshed finer where  out/fighter_walls.msh
#      the first layer would be flatter than checkMesh accepts (--max-aspect-ratio, by default;
#      jobs 1 and 2 turn it off to keep the paper's 4,486 triangles)
#
#   examples/fighter/run.sh                 BUILD_DIR (default build) holds app/strata
#   CHECKMESH=1 examples/fighter/run.sh     also OpenFOAM's checkMesh on jobs 2 and 3 (2 fails
#                                           on aspect ratio, 3 passes)
#                                           (tests/openfoam/check_mesh.sh: gmshToFoam, checkMesh)
#   PICTURES=1 examples/fighter/run.sh      also the README's pictures, docs/images/fighter_*.png
#                                           (scripts/surface_picture.py, scripts/plane_picture.py)
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD_DIR=${BUILD_DIR:-build}
strata=$BUILD_DIR/app/strata
[ -x "$strata" ] || { echo "no $strata: build first (bash scripts/setup.sh build), or set BUILD_DIR"; exit 1; }
geo=examples/fighter/fighter.geo
# 30 layers, 1e-4 first height, growth 1.2 (0.118 thick): the two spheres' and the NACA
# wing's layers; here 1/130 of the fuselage length, 18 % of the inlet duct's height.
layers=(--layers 30 --first-height 1e-4 --growth 1.2)
paper=(--max-aspect-ratio 0)  # the paper's resolution: the walls as the script meshes them
mkdir -p out

# The figures of one job's summary: wall triangles, cells, smallest scaled Jacobian per
# type, the coverage table, the times.
figures() {
  local log=$1 wall=$2
  awk '/^  patch [0-9]+ .* wall / { n += $(NF-1) } END { printf "wall triangles: %d\n", n }' "$log"
  grep -E "^(cells|valid|time|warning|note|planes|layers|walls|surface):|^  (prism|pyramid|tetrahedron|hexahedron): " "$log" || true
  sed -n '/^coverage:/,/^  (full:/p' "$log" | grep -v "^  (full:"
  echo "wall clock: $wall s"
}

# run NAME strata-arguments...: runs strata, keeps its output in out/NAME.log, prints the figures.
run() {
  local name=$1
  shift
  echo "== $name: strata $*"
  local start end
  start=$(date +%s.%N)
  if ! "$strata" "$@" >"out/$name.log" 2>&1; then
    cat "out/$name.log"
    exit 1
  fi
  end=$(date +%s.%N)
  figures "out/$name.log" "$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')"
  echo
}

run fighter_layers layers "$geo" -o out/fighter_layers.msh "${layers[@]}" "${paper[@]}"
run fighter mesh "$geo" -o out/fighter.msh "${layers[@]}" "${paper[@]}"
run fighter_walls mesh "$geo" -o out/fighter_walls.msh "${layers[@]}"

if [ "${CHECKMESH:-0}" = 1 ]; then
  echo "== checkMesh: $geo at the paper's resolution"
  bash tests/openfoam/check_mesh.sh "$strata" "$geo" "${layers[@]}" "${paper[@]}" || echo "checkMesh: failed (above)"
  echo
  echo "== checkMesh: $geo, walls meshed finer for the first layer"
  bash tests/openfoam/check_mesh.sh "$strata" "$geo" "${layers[@]}" || echo "checkMesh: failed (above)"
  echo
fi

if [ "${PICTURES:-0}" = 1 ]; then
  pic="python3 scripts/surface_picture.py"
  walls=fuselage,canopy,inlet,wing,htail,vtail
  "$strata" surface "$geo" -o out/fighter_surface.msh -q
  # Figure 10 of the paper: the outer surface of the layers about the inlet (the half model
  # drawn with its mirror image).
  $pic out/fighter_layers.msh docs/images/fighter_inlet_layers.png --patches layer_top \
    --view 135 -25 --center 4.0 0.0 -0.5 --zoom 2.0 --mirror
  # Figure 11: the aft end; the wall where no layer covers it (the trailing edges) in red.
  $pic out/fighter_layers.msh docs/images/fighter_aft_layers.png --patches layer_top \
    --underlay out/fighter_surface.msh "$walls" 230,120,100 --view 130 35 --size 1200 700 \
    --center 13 0.8 0.5 --zoom 2.0
  # The hybrid mesh in the symmetry plane through the inlet and its duct.
  python3 scripts/plane_picture.py out/fighter.msh symmetry docs/images/fighter_inlet_symmetry.png \
    x z 3.6 9.6 -1.9 0.1 1200
  ls -l docs/images/fighter_*.png
fi
