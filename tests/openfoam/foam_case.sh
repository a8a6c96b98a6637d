# Sourced by check_mesh.sh and check_polymesh.sh: an empty OpenFOAM case for checkMesh, and
# OpenFOAM's verdict on it.
#   new_foam_case           sets case_dir: a temporary case (removed on exit) with system/
#                           controlDict, fvSchemes and fvSolution, and an empty constant/
#   check_foam_case         runs checkMesh on case_dir, prints its figures; fails unless "Mesh OK."
#   require_tools TOOL...   exits with a message naming the first tool missing
#   strata_foam_case STRATA ARGS...
#                           a new case holding `strata mesh ARGS` as MSH 2.2 (case_dir/mesh.msh,
#                           its report beside it) converted by gmshToFoam
# Needs Debian's openfoam package (scripts/setup.sh installs it).
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}

new_foam_case() {
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
}

check_foam_case() {
  checkMesh -case "$case_dir" >"$case_dir/checkMesh.log" 2>&1 || true
  grep -E "cells:|non-orthogonality Max|Max skewness|Max aspect ratio" "$case_dir/checkMesh.log" || true
  if ! grep -q "^Mesh OK." "$case_dir/checkMesh.log"; then
    grep -E "\*\*\*|Failed|FATAL" "$case_dir/checkMesh.log" || tail -20 "$case_dir/checkMesh.log"
    exit 1
  fi
  echo "checkMesh: Mesh OK."
}

require_tools() {
  for tool in "$@"; do
    command -v "$tool" >/dev/null || { echo "$tool not found: scripts/setup.sh installs it (Debian's openfoam)"; exit 1; }
  done
}

# gmshToFoam needs -keepOrientation: without it, it "corrects" the orientation of hexahedra
# and prisms by its own test, which turns thin, curved layer cells inside out (1733 of the
# quad sphere's 15360 hexahedra).
strata_foam_case() {
  local strata=$1
  shift
  new_foam_case
  "$strata" mesh "$@" -o "$case_dir/mesh.msh" --msh-version 2.2 -q
  gmshToFoam -keepOrientation -case "$case_dir" "$case_dir/mesh.msh" >"$case_dir/gmshToFoam.log" 2>&1 ||
    { tail -20 "$case_dir/gmshToFoam.log"; exit 1; }
}
