#!/usr/bin/env bash
# Render a mesh to a PNG with Gmsh's own viewer under a virtual X server (for the README's
# pictures). Needs the packages gmsh and xvfb (not required to build or test Strata).
#   scripts/render.sh MESH.msh OUT.png [rotX rotY rotZ] [extra Gmsh commands]
set -euo pipefail
mesh=$(realpath "$1"); out=$(realpath -m "$2")
rx=${3:--60}; ry=${4:-0}; rz=${5:--30}; extra=${6:-}
geo=$(mktemp --suffix=.geo)
trap 'rm -f "$geo"' EXIT
cat >"$geo" <<GEO
Merge "$mesh";
General.GraphicsWidth = 1200; General.GraphicsHeight = 700; General.SmallAxes = 0;
Mesh.SurfaceFaces = 1; Mesh.VolumeFaces = 1; Mesh.Lines = 0; Mesh.Points = 0; Mesh.ColorCarousel = 0;
Mesh.Color.Triangles = {200,200,230}; Mesh.Color.Quadrangles = {230,210,170};
General.Trackball = 0; General.RotationX = $rx; General.RotationY = $ry; General.RotationZ = $rz;
$extra
Draw;
Print "$out";
Exit;
GEO
xvfb-run -a -s "-screen 0 1400x900x24" gmsh "$geo" >/dev/null 2>&1
test -s "$out"
