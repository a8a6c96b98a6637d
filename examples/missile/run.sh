#!/usr/bin/env bash
# The paper's second example (section 5.2), the finned missile on a sting, half model:
# 30 layers alone (the paper's all-prism near-body mesh), then the complete hybrid mesh, then
# the picture of the layers' outer surface at the fin-body junction (the paper's figure 7;
# needs the packages gmsh and xvfb). Outputs in out/missile_*.
#   examples/missile/run.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
strata=${1:-build}/app/strata
mkdir -p out
opts=(--patch outflow=other --layers 30 --first-height 1e-5 --growth 1.2)
"$strata" layers examples/missile/missile.geo -o out/missile_layers.msh "${opts[@]}"
"$strata" mesh examples/missile/missile.geo -o out/missile.msh "${opts[@]}"
if command -v gmsh >/dev/null && command -v xvfb-run >/dev/null; then
  # Only the layers' outer surface (entity 9, "layer_top"), near the fins.
  scripts/render.sh out/missile_layers.msh out/missile_fin_junction.png -55 0 -35 \
    'Mesh.VolumeFaces = 0; Hide {:} Show { Surface{9}; } General.ScaleX = 5; General.ScaleY = 5; General.ScaleZ = 5; General.TranslationX = -0.12; General.TranslationY = 0.06;'
  echo "wrote out/missile_fin_junction.png"
fi
