#!/usr/bin/env bash
# The Snakemake workflow (examples/pipeline) on two small sphere variants, two jobs at once:
# both meshes and reports are made, the table has one row per case with cells that add up,
# and a second run does nothing (every output up to date).
#   tests/pipeline/run_pipeline.sh STRATA
set -euo pipefail
strata=$(readlink -f "$1")
cd "$(dirname "$0")/../.."
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run() {
  snakemake -j2 --snakefile examples/pipeline/Snakefile --configfile tests/pipeline/tiny.yaml \
    --config out="$out" strata="$strata" "$@"
}
run -q
for c in sphere_h1e-3 sphere_h1e-4; do
  test -s "$out/$c/mesh.cgr" || { echo "no mesh for $c"; exit 1; }
  test -s "$out/$c/benchmark.tsv" || { echo "no benchmark for $c"; exit 1; }
done
/usr/bin/python3 - "$out" <<'PY'
import csv, json, sys
out = sys.argv[1]
rows = list(csv.DictReader(open(f"{out}/table.csv")))
assert [r["case"] for r in rows] == ["sphere_h1e-3", "sphere_h1e-4"], rows
for r in rows:
    rep = json.load(open(f"{out}/{r['case']}/mesh.cgr.report.json"))
    types = ("tetrahedra", "pyramids", "prisms", "hexahedra")
    assert int(r["cells"]) == sum(int(r[t]) for t in types) == sum(rep["cells"].values()), r
    assert int(r["prisms"]) > 0 and int(r["tetrahedra"]) > 0, r
    assert 0 < float(r["min_sj"]) <= 1 and float(r["seconds"]) > 0, r
# the layers asked differ, and so do the meshes
assert rows[0]["prisms"] != rows[1]["prisms"], rows
md = open(f"{out}/table.md").read().splitlines()
assert len(md) == 4 and md[0].startswith("| case |"), md
PY
# A second run: nothing to do.
second=$(run -n 2>&1)
echo "$second" | grep -q "Nothing to be done" || { echo "second run would do something:"; echo "$second"; exit 1; }
echo "pipeline: two cases meshed, table checked, rerun is a no-op"
