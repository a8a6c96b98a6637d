#!/usr/bin/env bash
# OpenFOAM's verdict on a Strata mesh: `strata mesh` to MSH 2.2, gmshToFoam, checkMesh; passes
# only on "Mesh OK.". Debian's openfoam package (scripts/setup.sh installs it).
#   check_mesh.sh STRATA INPUT [strata mesh options...]
set -euo pipefail
strata=$1
shift
# shellcheck source=foam_case.sh
source "$(dirname "$0")/foam_case.sh"
require_tools gmshToFoam checkMesh
strata_foam_case "$strata" "$@"
check_foam_case
