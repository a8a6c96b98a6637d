#!/usr/bin/env bash
# OpenFOAM's verdict on Strata's own polyMesh writer: `strata mesh` straight to
# CASE/constant/polyMesh, then checkMesh; passes only on "Mesh OK.". Debian's openfoam package
# (scripts/setup.sh installs it). The same case through MSH 2.2 and gmshToFoam: check_mesh.sh.
#   check_polymesh.sh STRATA [--type PATCH=TYPE ...] INPUT [strata mesh options...]
# Each --type also requires the boundary file to give PATCH that type (e.g. symmetry=symmetry).
set -euo pipefail
strata=$1
shift
types=()
while [ "${1:-}" = "--type" ]; do
  types+=("$2")
  shift 2
done
command -v checkMesh >/dev/null || { echo "checkMesh not found: install Debian's openfoam (scripts/setup.sh does)"; exit 1; }
# shellcheck source=foam_case.sh
source "$(dirname "$0")/foam_case.sh"
new_foam_case
"$strata" mesh "$@" -o "$case_dir/constant/polyMesh" -q
for t in "${types[@]}"; do
  patch=${t%%=*} type=${t#*=}
  awk -v p="$patch" -v t="$type" '$1 == p { inside = 1 } inside && $1 == "type" { found = ($2 == t ";"); exit }
       END { exit !found }' "$case_dir/constant/polyMesh/boundary" ||
    { echo "patch $patch is not of type $type:"; cat "$case_dir/constant/polyMesh/boundary"; exit 1; }
done
check_foam_case
