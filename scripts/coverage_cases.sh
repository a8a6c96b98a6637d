#!/usr/bin/env bash
# Boundary-layer coverage on vehicles as issue 54 states it: the stand-ins written for it
# (lifting body, cone-cylinder-flare, airliner without nacelles) and the sweep's vehicles (airliner
# with nacelles, rocket, car on its wheels, propeller, the fused wing-fuselage), each meshed by
# `strata mesh` at a surface size an engineer would pick for it, with LAYERS layers at growth 1.2
# from a first height of 1e-4 of its length; one Markdown row per case (coverage_row.py: wall
# nodes, share with every layer, the same proximity aside, mean thickness reached, short nodes by
# reason, checkMesh, smallest scaled Jacobians, seconds). PATCHES=1 adds a row per wall patch.
#
#   scripts/coverage_cases.sh [BUILD_DIR] [WORK_DIR] [LAYERS]   (defaults: build, a temporary directory, 20)
#
# Exit status 0 whatever the meshes are like: this measures, the tests assert.
set -euo pipefail

# shellcheck source=lib.sh
source "$(dirname "$0")/lib.sh"
measure_setup "${1:-}" "${2:-}"
layers=${3:-20}
s=$root/examples/sweep
L="--layers $layers --growth 1.2"
C="--curvature 12"

# name (length)|arguments: first height 1e-4 of the length
cases=(
  "lifting body with chines and fins (10)|$s/liftingbody.geo --fuse $L --first-height 1e-3 --size 0.05 $C"
  "cone-cylinder-flare (2.37)|$s/ccf.geo --fuse $L --first-height 2.37e-4 --size 0.025 $C"
  "airliner without nacelles (10)|$s/airliner_tail.geo --fuse $L --first-height 1e-3 --size 0.08 $C"
  "airliner with nacelles (10)|$s/airliner.geo --fuse $L --first-height 1e-3 --size 0.08 $C"
  "sounding rocket (2.65)|$s/rocket.geo --fuse $L --first-height 2.65e-4 --size 0.03 $C"
  "car on its wheels in a wind tunnel (4.2)|$s/car_ground.geo $L --first-height 4.2e-4 --size 0.15 $C"
  "three-bladed propeller (2)|$s/propeller.geo --fuse $L --first-height 2e-4 --size 0.025 $C"
  "wing-fuselage STEP, fused (0.447 m)|$root/examples/data/wing_fuselage.step --fuse $L --first-height 4.47e-5 --size 0.005 $C"
)

row=$root/scripts/coverage_row.py
patches=()
[ "${PATCHES:-0}" = 1 ] && patches=(--patches)
python3 "$row" --header
i=0
for c in "${cases[@]}"; do
  name=${c%%|*}
  read -r -a args <<< "${c#*|}"
  i=$((i + 1))
  out=$work/coverage$i
  start=$(date +%s.%N)
  if ! nice "$strata" mesh "${args[@]}" --threads 2 -o "$out.msh" > "$out.log" 2>&1; then
    echo "| $name | failed: $(grep -m1 -i error "$out.log" | cut -c1-120) | | | | | | | |"
    continue
  fi
  seconds=$(echo "$(date +%s.%N) - $start" | bc)
  python3 "$row" "$out.log" "$out.msh.report.json" "$name" "$seconds" "${patches[@]}"
  rm -f "$out.msh"
done
