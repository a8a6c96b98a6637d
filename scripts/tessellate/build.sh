#!/usr/bin/env bash
# Build tessellate_cad (OpenCASCADE's own STL export of a CAD file, for test data such as
# examples/data/onera_m6_brepmesh_needles.stl) and export_iges (its IGES export in faces mode,
# for tests/data/cad_*_trimmed_faces.igs). Not part of Strata's build: it needs
# OpenCASCADE's headers, which Strata does not (Gmsh reads CAD for it). Installs them if missing.
#   scripts/tessellate/build.sh [OUT_DIR]   -> OUT_DIR/tessellate_cad, OUT_DIR/export_iges (default build/)
# Then: tessellate_cad examples/data/onera_m6_sharp_te.stp out.stl 2 30
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-$here/../../build}
if [ ! -f /usr/include/opencascade/BRepMesh_IncrementalMesh.hxx ]; then
  sudo=$([ "$(id -u)" = 0 ] || echo sudo)
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
    libocct-modeling-algorithms-dev libocct-data-exchange-dev >/dev/null
fi
mkdir -p "$out"
g++ -O2 -std=c++17 -isystem /usr/include/opencascade "$here/tessellate_cad.cpp" -o "$out/tessellate_cad" \
  -lTKSTEP -lTKXSBase -lTKBRep -lTKMesh -lTKSTL -lTKernel -lTKMath -lTKTopAlgo -lTKG3d -lTKGeomBase
g++ -O2 -std=c++17 -isystem /usr/include/opencascade "$here/export_iges.cpp" -o "$out/export_iges" \
  -lTKIGES -lTKSTEP -lTKXSBase -lTKBRep -lTKernel -lTKMath -lTKTopAlgo -lTKG3d -lTKGeomBase
echo "built $out/tessellate_cad and $out/export_iges"
