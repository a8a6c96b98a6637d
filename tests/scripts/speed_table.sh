#!/usr/bin/env bash
# scripts/speed_table.sh on its smallest rows (the rocket; a ~20k-triangle sphere against Gmsh's
# own boundary layer): both tables come out, every figure a number, no row failed. Its figures
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
rocket=$(grep '^| sounding rocket' "$out") || fail "no rocket row"
sphere=$(grep '^| ~20000 ' "$out") || fail "no sphere row"
# Every cell after the name holds a number (with thousands separators, a rate in brackets).
for row in "$rocket" "$sphere"; do
  cells=$(echo "$row" | awk -F'|' '{for (i = 3; i < NF; ++i) print $i}')
  while read -r c; do
    [[ $c =~ ^[0-9][0-9,./\ ()e+]*$ ]] || fail "not a figure: '$c' in $row"
  done <<< "$cells"
done
[ "$(echo "$rocket" | awk -F'|' '{print NF}')" = 13 ] || fail "the rocket row has not 11 columns"
[ "$(echo "$sphere" | awk -F'|' '{print NF}')" = 9 ] || fail "the sphere row has not 7 columns"
echo "speed table: OK"
