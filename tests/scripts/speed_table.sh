#!/usr/bin/env bash
# scripts/speed_table.sh on its smallest rows (the rocket, its fill by TetGen and by HXT; a
# ~20k-triangle sphere against Gmsh's own boundary layer): the tables come out, every figure a
# number, no row failed. Its figures
# are not judged here (speed is measured by the script, never by a test).
#   speed_table.sh BUILD_DIR
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out=$work/table.md
ROWS=rocket SPHERES=20000 bash "$root/scripts/speed_table.sh" "$1" "$work/run" > "$out"
cat "$out"
fail() { echo "FAIL: $*"; exit 1; }
grep -q failed "$out" && fail "a row failed"
rocket=$(grep '^| sounding rocket' "$out" | head -1) || fail "no rocket row"
tetgen=$(grep '^| sounding rocket (2.65) | tetgen |' "$out") || fail "no TetGen fill row"
hxt=$(grep '^| sounding rocket (2.65) | hxt |' "$out") || fail "no HXT fill row"
sphere=$(grep '^| ~20000 ' "$out") || fail "no sphere row"
# Every cell after the name holds a number (with thousands separators, a rate in brackets).
for row in "$rocket" "$sphere" "$tetgen" "$hxt"; do
  first=3
  [[ $row == *"| tetgen |"* || $row == *"| hxt |"* ]] && first=4
  cells=$(echo "$row" | awk -F'|' -v f=$first '{for (i = f; i < NF; ++i) print $i}')
  while read -r c; do
    [[ $c =~ ^[0-9][0-9,./\ ()e+-]*$ ]] || fail "not a figure: '$c' in $row"
  done <<< "$cells"
done
[ "$(echo "$rocket" | awk -F'|' '{print NF}')" = 13 ] || fail "the rocket row has not 11 columns"
[ "$(echo "$sphere" | awk -F'|' '{print NF}')" = 9 ] || fail "the sphere row has not 7 columns"
[ "$(echo "$hxt" | awk -F'|' '{print NF}')" = 11 ] || fail "the HXT fill row has not 9 columns"
echo "speed table: OK"
