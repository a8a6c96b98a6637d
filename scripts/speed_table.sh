#!/usr/bin/env bash
# Speed on the real-geometry stand-ins (issue 55): the whole `strata mesh` per stage on the
# vehicles of examples/sweep and the paper's fighter, at 2 threads and at 1 (the layer stage's
# cells per second at each), with its peak memory; then `strata layers` on Gmsh-meshed spheres of
# ~100k and ~1M triangles against Gmsh 4.8's own extrudeBoundaryLayer on the same surface, in the
# same run (scripts/gmsh_peer.py). Prints two Markdown tables (docs/CASES.md, "Speed").
#
#   scripts/speed_table.sh [BUILD_DIR] [WORK_DIR]     (defaults: build, a temporary directory)
#   ROWS="airliner fighter" scripts/speed_table.sh    only those rows of the first table
#   SPHERES="100000" scripts/speed_table.sh           only those spheres (triangles asked)
#   FILLS="airliner" scripts/speed_table.sh           the tetrahedral fill table's rows (default:
#                                                      every row of the first table; "none": no table)
#
# One run per figure, on a machine with nothing else running: for a ratio that survives a noisy
# machine, time a row with farm-bench instead. Exit status 0 whatever the meshes are like.
set -euo pipefail

# shellcheck source=lib.sh
source "$(dirname "$0")/lib.sh"
measure_setup "$@"
s=$root/examples/sweep
py=/usr/bin/python3
L20="--layers 20 --growth 1.2 --curvature 12"

# name|arguments (paths as given)
declare -A cases=(
  [airliner]="airliner with nacelles (10 long)|$s/airliner.geo --fuse $L20 --first-height 1e-3 --size 0.08"
  [liftingbody]="lifting body with chines and fins (10)|$s/liftingbody.geo --fuse $L20 --first-height 1e-3 --size 0.05"
  [rocket]="sounding rocket (2.65)|$s/rocket.geo --fuse $L20 --first-height 2.65e-4 --size 0.03"
  [fighter]="the paper's fighter, half model (examples/fighter)|$root/examples/fighter/fighter.geo --layers 30 --first-height 1e-4 --growth 1.2"
  [m6]="ONERA M6 STEP, fine (--size 10)|$root/examples/data/onera_m6_sharp_te.stp --size 10 --layers 20 --first-height 0.02 --growth 1.2"
)
read -r -a rows <<< "${ROWS:-airliner liftingbody rocket fighter m6}"
read -r -a spheres <<< "${SPHERES:-100000 1000000}"

# One `strata mesh` run: "$work/NAME-THREADS.log" (summary) and ".time" (/usr/bin/time).
run_mesh() {
  local name=$1 threads=$2
  shift 2
  /usr/bin/time -f "%e %M" -o "$work/$name-$threads.time" \
    "$strata" mesh "$@" --threads "$threads" -o "$work/$name-$threads.cgr" > "$work/$name-$threads.log" 2>&1
}

echo "| case | wall faces | cells: layer / pyramid / tet | surface s | layers s at 2 threads (cells/s) | at 1 thread (cells/s) | tetrahedra s (tets/s) | validation s | write s (MB/s) | whole s | peak MB (bytes/cell) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for key in "${rows[@]}"; do
  name=${cases[$key]%%|*}
  read -r -a args <<< "${cases[$key]#*|}"
  if ! run_mesh "$key" 2 "${args[@]}" || ! run_mesh "$key" 1 "${args[@]}"; then
    echo "| $name | failed: $(grep -m1 -i error "$work/$key-2.log" "$work/$key-1.log" | cut -c1-100) |"
    continue
  fi
  $py "$root/scripts/speed_row.py" "$name" "$work/$key-2" "$work/$key-1"
done

# The tetrahedral fill by each mesher (2 threads): TetGen's run is the first table's.
read -r -a fills <<< "${FILLS:-${rows[*]}}"
if [ "${fills[0]:-none}" != none ]; then
  echo
  echo "| case | --tets | tetrahedra s | tetrahedra (per s) | worst tetrahedron | worst free tetrahedron after the improvement | below 0.2 after it | non-orthogonality / skewness max | whole s |"
  echo "|---|---|---|---|---|---|---|---|---|"
  for key in "${fills[@]}"; do
    name=${cases[$key]%%|*}
    read -r -a args <<< "${cases[$key]#*|}"
    [ -f "$work/$key-2.log" ] || run_mesh "$key" 2 "${args[@]}" || true
    $py "$root/scripts/speed_row.py" tets "$name" tetgen "$work/$key-2" || echo "| $name | tetgen | failed |"
    if run_mesh "$key-hxt" 2 "${args[@]}" --tets hxt; then
      $py "$root/scripts/speed_row.py" tets "$name" hxt "$work/$key-hxt-2"
    else
      echo "| $name | hxt | failed: $(grep -m1 -i error "$work/$key-hxt-2.log" | cut -c1-100) |"
    fi
  done
fi

echo
echo "| sphere (Gmsh, unit radius) | triangles | prisms | strata layers, 2 threads: s (cells/s) | 1 thread: s | Gmsh extrudeBoundaryLayer + generate(3): s | Gmsh / Strata |"
echo "|---|---|---|---|---|---|---|"
for n in "${spheres[@]}"; do
  surface=$work/sphere$n.msh
  triangles=$($py "$root/scripts/gmsh_peer.py" sphere "$n" "$surface")
  layers=(--layers 10 --first-height 1e-3 --growth 1.2)
  times=()
  for threads in 2 1; do
    start=$(date +%s.%N)
    "$strata" layers "$surface" "${layers[@]}" --threads "$threads" -o "$work/strata$n.msh" > "$work/strata$n.log" 2>&1
    times+=("$(echo "$(date +%s.%N) - $start" | bc)")
  done
  read -r gmsh_s prisms <<< "$($py "$root/scripts/gmsh_peer.py" extrude "$surface" 10 1e-3 1.2 "$work/gmsh$n.msh")"
  printf '| %s | %s | %s | %.2f (%.2g) | %.2f | %.2f | %.1f |\n' "~$n" "$triangles" "$prisms" "${times[0]}" \
    "$(echo "$prisms / ${times[0]}" | bc -l)" "${times[1]}" "$gmsh_s" "$(echo "$gmsh_s / ${times[0]}" | bc -l)"
  rm -f "$work/strata$n.msh" "$work/gmsh$n.msh"
done
