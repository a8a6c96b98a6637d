#!/usr/bin/env bash
# A real solver as the client of a Strata mesh with layers: `strata mesh ... -o CASE --foam-case`,
# then potentialFoam and simpleFoam (k-omega SST) on the case as Strata wrote it, only endTime
# lowered to ITERATIONS. Passes only if both run to their end ("End", exit 0) with no
# floating-point exception (OpenFOAM traps them: sigFpe's stack) and no FOAM FATAL, and simpleFoam's initial residuals of Ux and p fall
# by at least two orders of magnitude from its first iteration to its last. Prints the figures.
# Debian's openfoam package (scripts/setup.sh installs it).
#   run_simplefoam.sh STRATA ITERATIONS INPUT [strata mesh options...]
set -euo pipefail
strata=$1 iterations=$2
shift 2
# shellcheck source=foam_case.sh
source "$(dirname "$0")/foam_case.sh"
require_tools potentialFoam simpleFoam python3
case_dir=$(mktemp -d)
trap 'rm -rf "$case_dir"' EXIT
"$strata" mesh "$@" -o "$case_dir" --foam-case | grep -E '^(cells|case|run):'
sed -i "s/^endTime .*/endTime         $iterations;/" "$case_dir/system/controlDict"
grep -q "^endTime         $iterations;" "$case_dir/system/controlDict" || { echo "controlDict has no endTime"; exit 1; }

# run SOLVER: runs it on the case into SOLVER.log, fails unless it ran to its end cleanly.
run() {
  local solver=$1 start=$SECONDS status=0
  "$solver" -case "$case_dir" >"$case_dir/$solver.log" 2>&1 || status=$?
  echo "$solver: exit $status, $((SECONDS - start)) s"
  if [ "$status" != 0 ] || grep -qE "FOAM FATAL|sigFpe::sigHandler|printStack" "$case_dir/$solver.log" ||
    [ "$(grep -v '^\s*$' "$case_dir/$solver.log" | tail -1)" != "End" ]; then
    grep -E -A8 "FOAM FATAL|printStack" "$case_dir/$solver.log" || tail -30 "$case_dir/$solver.log"
    exit 1
  fi
}
run potentialFoam
run simpleFoam

python3 - "$case_dir/simpleFoam.log" <<'PY'
import math, re, sys
log = open(sys.argv[1]).read()
# Each iteration ("Time = N") and the initial residual of the first solve of each field in it.
steps = []
for block in re.split(r"^Time = ", log, flags=re.M)[1:]:
    first = {}
    for field, residual in re.findall(r"Solving for (\w+), Initial residual = ([0-9.eE+-]+)", block):
        first.setdefault(field, float(residual))
    steps.append((block.split()[0], first))
steps = [s for s in steps if "Ux" in s[1] and "p" in s[1]]
if len(steps) < 2:
    sys.exit("simpleFoam solved fewer than two iterations")
(t0, r0), (t1, r1) = steps[0], steps[-1]
converged = re.search(r"SIMPLE solution converged in (\d+) iterations", log)
print("simpleFoam: %d iterations%s" % (len(steps), " (converged: residualControl met)" if converged else ""))
bad = []
for field in ("Ux", "Uy", "Uz", "p", "k", "omega"):
    if field not in r0 or field not in r1:
        continue
    orders = math.log10(r0[field] / r1[field]) if r1[field] > 0 else float("inf")
    print("  %-6s initial residual %.3g (iteration %s) -> %.3g (iteration %s): %.1f orders" %
          (field, r0[field], t0, r1[field], t1, orders))
    if field in ("Ux", "p") and not orders >= 2:
        bad.append(field)
sys.exit("the residuals of %s fell by less than two orders" % ", ".join(bad) if bad else 0)
PY
