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
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
case_dir=$(mktemp -d)
trap 'rm -rf "$case_dir"' EXIT
mkdir -p "$case_dir/system" "$case_dir/constant"
cat >"$case_dir/system/controlDict" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }
application checkMesh; startFrom startTime; startTime 0; stopAt endTime; endTime 0; deltaT 1;
writeControl timeStep; writeInterval 1;
DICT
cat >"$case_dir/system/fvSchemes" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object fvSchemes; }
ddtSchemes { default steadyState; }
gradSchemes { default Gauss linear; }
divSchemes { default none; }
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
DICT
cat >"$case_dir/system/fvSolution" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }
DICT
"$strata" mesh "$@" -o "$case_dir/constant/polyMesh" -q
for t in "${types[@]}"; do
  patch=${t%%=*} type=${t#*=}
  awk -v p="$patch" -v t="$type" '$1 == p { inside = 1 } inside && $1 == "type" { found = ($2 == t ";"); exit }
       END { exit !found }' "$case_dir/constant/polyMesh/boundary" ||
    { echo "patch $patch is not of type $type:"; cat "$case_dir/constant/polyMesh/boundary"; exit 1; }
done
checkMesh -case "$case_dir" >"$case_dir/checkMesh.log" 2>&1 || true
grep -E "cells:|non-orthogonality Max|Max skewness|Max aspect ratio" "$case_dir/checkMesh.log" || true
if ! grep -q "^Mesh OK." "$case_dir/checkMesh.log"; then
  grep -E "\*\*\*|Failed|FATAL" "$case_dir/checkMesh.log" || tail -20 "$case_dir/checkMesh.log"
  exit 1
fi
echo "checkMesh: Mesh OK."
