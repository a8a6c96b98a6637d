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
# shellcheck source=foam_case.sh
source "$(dirname "$0")/foam_case.sh"
new_foam_case
"$strata" mesh "$@" -o "$case_dir/mesh.msh" --msh-version 2.2 -q
gmshToFoam -keepOrientation -case "$case_dir" "$case_dir/mesh.msh" >"$case_dir/gmshToFoam.log" 2>&1 ||
  { tail -20 "$case_dir/gmshToFoam.log"; exit 1; }
check_foam_case
