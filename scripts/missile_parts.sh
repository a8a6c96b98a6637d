#!/usr/bin/env bash
# Write the five-part missile (examples/data/missile_parts/*.geo: a body and four fins that pass
# into it, as separate solids) as five closed STL files with Strata's own surface stage (Gmsh),
# the input of the --fuse case for surface meshes (issue 10).
#   scripts/missile_parts.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
strata=${1:-build}/app/strata
for part in body fin1 fin2 fin3 fin4; do
  "$strata" surface examples/data/missile_parts/$part.geo -o examples/data/missile_parts/$part.stl -q
done
