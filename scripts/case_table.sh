# Shared by issue_cases.sh and sweep_cases.sh: case_table STRATA WORK_DIR "name|args" ...
# meshes each case with `strata mesh ARGS` on 2 threads and again on 1, and prints one Markdown
# table: cells by type, the smallest scaled Jacobian per type, the share of wall nodes with every
# layer, what OpenFOAM's checkMesh will say (the summary's `openfoam:` line, which
# tests/openfoam/check_figures.sh holds to checkMesh's own figures; in brackets the faces or
# cells over its limit), whether the 1- and 2-thread outputs are the same bytes, and the
# wall-clock seconds of the 2-thread run.

case_table() {
  local strata=$1 work=$2
  shift 2
  echo "| case | cells: hex, prism, pyramid, tet | min scaled Jacobian: hex / prism / pyramid / tet | wall nodes with every layer | checkMesh | 1 = 2 threads | s |"
  echo "|---|---|---|---|---|---|---|"
  local i=0 c name args out start seconds same
  for c in "$@"; do
    name=${c%%|*}
    read -r -a args <<< "${c#*|}"
    i=$((i + 1))
    out=$work/case$i
    start=$(date +%s.%N)
    if ! "$strata" mesh "${args[@]}" --threads 2 -o "$out.msh" > "$out.log" 2>&1; then
      echo "| $name | failed: $(grep -m1 -i error "$out.log" | cut -c1-120) | | | | | |"
      continue
    fi
    seconds=$(echo "$(date +%s.%N) - $start" | bc)
    "$strata" mesh "${args[@]}" --threads 1 -o "$out.t1.msh" -q > /dev/null 2>&1 || true
    if cmp -s "$out.msh" "$out.t1.msh"; then same=yes; else same=NO; fi
    python3 - "$out.log" "$out.msh.report.json" "$name" "$same" "$seconds" <<'EOF'
import json, re, sys
log, report, name, same, seconds = sys.argv[1:]
text = open(log).read()
r = json.load(open(report))
cells = r["cells"]
q = r["quality"]["min_scaled_jacobian"]
def fmt(t):
    if cells.get(t, 0) == 0:
        return "-"
    v = q[t]
    return f"{v:.2g}" if v < 0.01 else f"{v:.3f}"
nodes = sum(p["nodes"] for p in r["patches"])
whole = sum(p["all_layers"] for p in r["patches"])
m = re.search(r"^openfoam: .*?: checkMesh would (say \"Mesh OK\"|fail it)", text, re.M)
verdict = "Mesh OK" if m and "OK" in m.group(1) else "fails"
why = []
for w in re.finditer(r"^warning: checkMesh would fail: (\d+) (faces with a skewness|cells with an aspect ratio|[a-z ]+?)[ ,].*?the worst ([0-9.e+-]+)", text, re.M):
    kind = "skewness" if "skew" in w.group(2) else "aspect ratio" if "aspect" in w.group(2) else w.group(2)
    why.append(f"{kind} {w.group(3)} ({w.group(1)})")
if why:
    verdict += ": " + ", ".join(why)
print(f"| {name} | {cells.get('hexahedron', 0):,}, {cells.get('prism', 0):,}, {cells.get('pyramid', 0):,}, "
      f"{cells.get('tetrahedron', 0):,} | {fmt('hexahedron')} / {fmt('prism')} / {fmt('pyramid')} / "
      f"{fmt('tetrahedron')} | {100.0 * whole / nodes:.1f} % | {verdict} | {same} | {float(seconds):.1f} |")
EOF
    rm -f "$out.msh" "$out.t1.msh"
  done
}
