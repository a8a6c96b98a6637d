#!/usr/bin/env bash
# The CAD shapes of examples/sweep and of the robust-layers issue meshed by `strata mesh` under
# five layer settings none of them was tuned on, printed as one Markdown table: a row per shape,
# a column per setting, each cell what OpenFOAM's checkMesh will say (the summary's `openfoam:`
# line) and the smallest scaled Jacobian of any cell, or the error the run stopped with. It
# finds what the case tables (issue_cases.sh, sweep_cases.sh: one setting each) cannot: a
# failure that only some settings meet. The first heights are shares of each shape's length L.
#
#   scripts/settings_sweep.sh [BUILD_DIR] [WORK_DIR]     (defaults: build, a temporary directory)
#
# Settings (columns):
#   coarse   10 layers from 1e-3 L at growth 1.3
#   fine     25 layers from 5e-5 L at growth 1.15
#   wall-fn  5 layers from 5e-3 L at growth 1.3 (a wall-function mesh)
#   mm       20 layers from 2e-4 L at growth 1.25, the model scaled to millimetres (--scale 1000)
#   quads    15 layers from 5e-4 L at growth 1.2 on quadrilateral walls (--quads)
#
# Exit status 0 whatever the meshes are like: this measures, the tests assert. About ten
# minutes on two cores.
set -euo pipefail

# shellcheck source=lib.sh
source "$(dirname "$0")/lib.sh"
measure_setup "$@"
s=$root/examples/sweep
d=$root/examples/data

# name|input and its own options|L
shapes=(
  "car|$s/car.geo --fuse|4.2"
  "wing with a winglet|$s/winglet.geo --fuse|3"
  "two-element wing|$s/slot.geo|1.5"
  "torus round a sphere|$s/torus.geo|2.6"
  "plate with holes|$s/holes.geo --fuse|2"
  "cup 0.01 thick|$s/shell.geo|1"
  "sphere over a floor (internal)|$s/ground.geo --internal|6"
  "pipe T-junction (internal)|$s/pipes.geo --internal|2"
  "sphere with three cones|$s/spiky.geo --fuse|1.6"
  "two bodies 3 mm apart|$s/twobodies.geo|1.6"
  "block with a hole of 1/500|$s/tinyhole.geo|1"
  "filleted box|$s/fillet.geo|2"
  "cylinder with a 1 mm fin|$s/thinfin.geo --fuse|3"
  "airliner with nacelles|$s/airliner.geo --fuse|10"
  "three-bladed propeller|$s/propeller.geo --fuse|2"
  "delta wing|$s/delta.geo|1"
  "half wing on a symmetry plane|$s/halfwing.geo|2"
  "ONERA M6 half model (mm)|$s/m6half.geo|1200"
  "rod through a plate at 15 degrees|$s/rodplate.geo --fuse|2"
  "sphere through a plate|$s/spherecap.geo --fuse|2"
  "six-pointed star prism|$s/star.geo|1"
  "spur gear|$s/gear.geo --fuse|1"
  "diamond wing through a body|$s/diamond.geo --fuse|2"
  "two spheres 0.0118 apart|$d/two_spheres_narrow_gap.geo --size 0.05|1"
  "sphere with a fin through it|$d/sphere_fin_through.geo --fuse|1"
  "box with a notch|$d/bl3d_4_box_notch_concave_corner.brep --patch surface_1=farfield --patch surface_2=farfield --patch surface_3=farfield --patch surface_4=farfield --patch surface_6=farfield|1"
  "body and fin in a box|$d/bl3d_5_body_fin_in_box.brep --patch surface_1=farfield --patch surface_2=farfield --patch surface_4=farfield --patch surface_6=farfield|1"
  "ONERA M6 (mm)|$d/onera_m6_sharp_te.stp --size 30|1200"
  "wing-fuselage (m)|$d/wing_fuselage.step --fuse|0.447"
  "NACA 0012 between walls (internal)|$d/naca0012_wing_between_walls.geo --internal|1"
)
settings=(
  "coarse|10 1e-3 1.3|"
  "fine|25 5e-5 1.15|"
  "wall-fn|5 5e-3 1.3|"
  "mm|20 2e-4 1.25|mm"
  "quads|15 5e-4 1.2|--quads"
)

header="| shape |"
rule="|---|"
for st in "${settings[@]}"; do
  header+=" ${st%%|*} |"
  rule+="---|"
done
echo "$header"
echo "$rule"
i=0
for sh in "${shapes[@]}"; do
  IFS='|' read -r name input length <<< "$sh"
  row="| $name |"
  for st in "${settings[@]}"; do
    IFS='|' read -r _ numbers extra <<< "$st"
    read -r layers share growth <<< "$numbers"
    read -r -a args <<< "$input"
    scale=1
    if [ "$extra" = mm ]; then
      scale=1000
      # --size is in the model's unit before --scale for CAD input (CadParams): it stays.
      args+=(--scale 1000)
    elif [ -n "$extra" ]; then
      args+=("$extra")
    fi
    h=$(python3 -c "print('%.6g' % ($length * $scale * $share))")
    i=$((i + 1))
    out=$work/run$i
    if "$strata" mesh "${args[@]}" --layers "$layers" --growth "$growth" --first-height "$h" \
        -o "$out.msh" > "$out.log" 2>&1; then
      row+=" $(python3 - "$out.log" "$out.msh.report.json" <<'EOF'
import json, re, sys
text = open(sys.argv[1]).read()
q = json.load(open(sys.argv[2]))["quality"]["min_scaled_jacobian"]["all"]
m = re.search(r"^openfoam: .*?: checkMesh would (say \"Mesh OK\"|fail it)", text, re.M)
verdict = "OK" if m and "OK" in m.group(1) else "fails"
for line in re.findall(r"^warning: checkMesh would fail: (.*)$", text, re.M):
    n = line.split()[0]
    worst = re.search(r"the worst ([0-9.e+-]+)", line)
    if "skewness" in line and worst:
        verdict += f" skewness {float(worst.group(1)):.4g} ({n})"
    elif "aspect ratio" in line and worst:
        verdict += f" aspect ratio {float(worst.group(1)):.4g} ({n})"
    elif "pyramid" in line:
        verdict += f" inverted faces ({n})"
    else:
        verdict += " " + line[:40]
print(f"{verdict}, {q:.2g}")
EOF
) |"
    else
      row+=" error: $(grep -m1 -i 'error' "$out.log" | sed "s/^strata: error: //; s/|/-/g; s|$root/||g" | cut -c1-90) |"
    fi
    rm -f "$out.msh"
  done
  echo "$row"
done
