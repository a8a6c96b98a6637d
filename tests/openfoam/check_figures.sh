#!/usr/bin/env bash
# Strata's own account of what checkMesh will say (the summary's "openfoam:" line, the report's
# quality.openfoam, core/solver_checks.h) against checkMesh itself on the same mesh: the largest
# non-orthogonality, its mean, the severely non-orthogonal faces, the largest skewness and the
# highly skew faces, the largest aspect ratio and the cells above 1000, and the verdict.
# Passes when they agree (values to 1e-4, checkMesh printing 6 digits; counts exactly).
#   check_figures.sh STRATA INPUT [strata mesh options...]
set -euo pipefail
strata=$1
shift
# shellcheck source=foam_case.sh
source "$(dirname "$0")/foam_case.sh"
require_tools gmshToFoam checkMesh python3
strata_foam_case "$strata" "$@"
checkMesh -case "$case_dir" >"$case_dir/checkMesh.log" 2>&1 || true
python3 - "$case_dir/mesh.msh.report.json" "$case_dir/checkMesh.log" <<'PY'
import json, re, sys
ours = json.load(open(sys.argv[1]))["quality"]["openfoam"]
log = open(sys.argv[2]).read()
def grab(pattern, default=None):
    m = re.search(pattern, log)
    if m is None:
        if default is None:
            sys.exit("checkMesh printed no match for " + pattern + ":\n" + log[-2000:])
        return default
    return float(m.group(1))
foam = {
    "max_non_orthogonality_deg": grab(r"non-orthogonality Max: (\S+)"),
    "mean_non_orthogonality_deg": grab(r"non-orthogonality Max: \S+ average: (\S+)"),
    "severely_non_orthogonal_faces": grab(r"severely non-orthogonal \(> 70 degrees\) faces: (\d+)", 0),
    "max_skewness": grab(r"Max skewness = ([0-9.eE+-]+)"),
    "skew_faces": grab(r"Max skewness = \S+ (\d+) highly skew", 0),
    "max_aspect_ratio": grab(r"[Mm]ax aspect ratio\s*[:=]\s*([0-9.eE+-]+)"),
    "high_aspect_cells": grab(r"number of cells (\d+)", 0),
}
bad = []
for key, value in foam.items():
    mine = ours[key]
    same = mine == value if key.endswith(("faces", "cells")) else abs(mine - value) <= 1e-4 * max(1.0, abs(value))
    print("%-30s strata %-12.6g checkMesh %-12.6g %s" % (key, mine, value, "" if same else "DIFFERENT"))
    if not same:
        bad.append(key)
verdict = "Mesh OK." in log
print("check_mesh_ok                  strata %-12s checkMesh %s" % (ours["check_mesh_ok"], verdict))
if ours["check_mesh_ok"] != verdict:
    bad.append("verdict")
sys.exit("differ: " + ", ".join(bad) if bad else 0)
PY
