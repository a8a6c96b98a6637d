#!/usr/bin/env bash
# The sweep of examples/sweep (shapes Strata was not tuned on: its README), each meshed by
# `strata mesh` with 30 layers at growth 1.2 from a first height of 1e-4 of the model's length
# (the STLs as a CAD tool exports them: kept as they are from 1e-3, and with --remesh from
# 1e-4), printed as case_table.sh's Markdown table. The README's sweep table is its output.
#
#   scripts/sweep_cases.sh [BUILD_DIR] [WORK_DIR]     (defaults: build, a temporary directory)
#
# Exit status 0 whatever the meshes are like: this measures, the tests assert.
set -euo pipefail

# shellcheck source=lib.sh
source "$(dirname "$0")/lib.sh"
measure_setup "$@"
s=$root/examples/sweep
L="--layers 30 --growth 1.2"

cases=(
  "car (4.2 long)|$s/car.geo --fuse $L --first-height 4.2e-4"
  "wing with a winglet (3 long)|$s/winglet.geo --fuse $L --first-height 3e-4"
  "two-element wing, narrow slot (1.5)|$s/slot.geo $L --first-height 1.5e-4"
  "torus round a sphere (2.6)|$s/torus.geo $L --first-height 2.6e-4"
  "plate with holes and a boss (2)|$s/holes.geo --fuse $L --first-height 2e-4"
  "cup 0.01 thick (1)|$s/shell.geo $L --first-height 1e-4"
  "sphere 2 mm over a floor, internal (6)|$s/ground.geo --internal $L --first-height 6e-4"
  "pipe T-junction, internal (2)|$s/pipes.geo --internal $L --first-height 2e-4"
  "sphere with three cones (1.6)|$s/spiky.geo --fuse $L --first-height 1.6e-4"
  "two bodies 3 mm apart (1.6)|$s/twobodies.geo $L --first-height 1.6e-4"
  "block with a hole of 1/500 (1)|$s/tinyhole.geo $L --first-height 1e-4"
  "filleted box (2)|$s/fillet.geo $L --first-height 2e-4"
  "cylinder with a 1 mm fin (3)|$s/thinfin.geo --fuse $L --first-height 3e-4"
  "airliner with nacelles (10)|$s/airliner.geo --fuse $L --first-height 1e-3"
  "three-bladed propeller (2)|$s/propeller.geo --fuse $L --first-height 2e-4"
  "car on its wheels in a wind tunnel (4.2)|$s/car_ground.geo $L --first-height 4.2e-4"
  "sounding rocket with a nozzle cavity (2.65)|$s/rocket.geo --fuse $L --first-height 2.65e-4"
  "delta wing with sharp leading edges (1)|$s/delta.geo $L --first-height 1e-4"
  "half wing on a symmetry plane (2)|$s/halfwing.geo $L --first-height 2e-4"
  "ONERA M6 half model on a symmetry plane (1200 mm)|$s/m6half.geo $L --first-height 0.12"
  "rod through a plate at 15 degrees (2)|$s/rodplate.geo --fuse $L --first-height 2e-4"
  "sphere through a plate, acute beneath it (2)|$s/spherecap.geo --fuse $L --first-height 2e-4"
  "six-pointed star prism (1)|$s/star.geo $L --first-height 1e-4"
  "spur gear, gaps narrower than the layers (1)|$s/gear.geo --fuse $L --first-height 1e-4"
  "diamond wing through a body (2)|$s/diamond.geo --fuse $L --first-height 2e-4"
  "half body STL, open along its symmetry plane (2)|$s/halfbody.stl $L --first-height 2e-4"
  "car STL|$s/car_brepmesh.stl --fuse $L --first-height 4.2e-3"
  "car STL --remesh|$s/car_brepmesh.stl --fuse --remesh $L --first-height 4.2e-4"
  "winglet STL|$s/winglet_brepmesh.stl --fuse $L --first-height 3e-3"
  "winglet STL --remesh|$s/winglet_brepmesh.stl --fuse --remesh $L --first-height 3e-4"
  "two-element wing STL|$s/slot_brepmesh.stl $L --first-height 1.5e-3"
  "two-element wing STL --remesh|$s/slot_brepmesh.stl --remesh $L --first-height 1.5e-4"
  "plate STL|$s/holes_brepmesh.stl --fuse $L --first-height 2e-3"
  "plate STL --remesh|$s/holes_brepmesh.stl --fuse --remesh $L --first-height 2e-4"
  "three cones STL|$s/spiky_brepmesh.stl --fuse $L --first-height 1.6e-3"
  "three cones STL --remesh|$s/spiky_brepmesh.stl --fuse --remesh $L --first-height 1.6e-4"
  "rocket STL|$s/rocket_brepmesh.stl --fuse $L --first-height 2.65e-3"
  "rocket STL --remesh|$s/rocket_brepmesh.stl --fuse --remesh $L --first-height 2.65e-4"
)

# shellcheck source=case_table.sh
source "$root/scripts/case_table.sh"
case_table "$strata" "$work" "${cases[@]}"
