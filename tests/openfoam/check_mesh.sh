#!/usr/bin/env bash
# OpenFOAM's verdict on a Strata mesh: `strata mesh` to MSH 2.2, gmshToFoam, checkMesh; passes
# only on "Mesh OK.". Debian's openfoam package (scripts/setup.sh installs it).
#   check_mesh.sh STRATA INPUT [strata mesh options...]
# gmshToFoam needs -keepOrientation: without it, it "corrects" the orientation of hexahedra
# and prisms by its own test, which turns thin, curved layer cells inside out (1733 of the
# quad sphere's 15360 hexahedra).
set -euo pipefail
strata=$1
shift
for tool in gmshToFoam checkMesh; do
  command -v "$tool" >/dev/null || { echo "$tool not found: install Debian's openfoam (scripts/setup.sh does)"; exit 1; }
done
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
case_dir=$(mktemp -d)
trap 'rm -rf "$case_dir"' EXIT
mkdir -p "$case_dir/system"
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
"$strata" mesh "$@" -o "$case_dir/mesh.msh" --msh-version 2.2 -q
gmshToFoam -keepOrientation -case "$case_dir" "$case_dir/mesh.msh" >"$case_dir/gmshToFoam.log" 2>&1 ||
  { tail -20 "$case_dir/gmshToFoam.log"; exit 1; }
checkMesh -case "$case_dir" >"$case_dir/checkMesh.log" 2>&1 || true
grep -E "cells:|non-orthogonality Max|Max skewness|Max aspect ratio" "$case_dir/checkMesh.log" || true
if ! grep -q "^Mesh OK." "$case_dir/checkMesh.log"; then
  grep -E "\*\*\*|Failed|FATAL" "$case_dir/checkMesh.log" || tail -20 "$case_dir/checkMesh.log"
  exit 1
fi
echo "checkMesh: Mesh OK."
