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
    PYTHONPATH=$(dirname "${BASH_SOURCE[0]}") python3 - "$out.log" "$out.msh.report.json" "$name" "$same" "$seconds" <<'EOF'
import json, sys
from report_figures import checkmesh_verdict, min_jacobian
log, report, name, same, seconds = sys.argv[1:]
r = json.load(open(report))
cells = r["cells"]
nodes = sum(p["nodes"] for p in r["patches"])
whole = sum(p["all_layers"] for p in r["patches"])
fmt = lambda t: min_jacobian(r, t)
print(f"| {name} | {cells.get('hexahedron', 0):,}, {cells.get('prism', 0):,}, {cells.get('pyramid', 0):,}, "
      f"{cells.get('tetrahedron', 0):,} | {fmt('hexahedron')} / {fmt('prism')} / {fmt('pyramid')} / "
      f"{fmt('tetrahedron')} | {100.0 * whole / nodes:.1f} % | {checkmesh_verdict(open(log).read())} | {same} | "
      f"{float(seconds):.1f} |")
EOF
    rm -f "$out.msh" "$out.t1.msh"
  done
}
