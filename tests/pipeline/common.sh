# shellcheck shell=bash
# What the workflow's tests (run_pipeline.sh, run_slurm.sh) share; sourced by them.
#   pipeline_setup DIR STRATA    make DIR/work the working directory, laid out as the repository's
#                                root (examples/ and tests/ linked) so that Snakemake's state
#                                (.snakemake/) stays in DIR; the outputs go to DIR/out
#   pipeline_run ARGS...         snakemake on tests/pipeline/tiny.yaml's two cases, with ARGS
#   pipeline_check               both meshes and timings made; the table, one row per case, agrees
#                                with the reports
#   pipeline_check_rerun ARGS... a second run (a dry run, with ARGS) has nothing to do
pipeline_out=""
pipeline_strata=""

pipeline_setup() {
  local repo
  repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
  pipeline_strata=$(readlink -f "$2")
  pipeline_out=$1/out
  mkdir "$1/work"
  ln -s "$repo/examples" "$repo/tests" "$1/work/"
  cd "$1/work" || exit 1
}

pipeline_run() {
  snakemake --snakefile examples/pipeline/Snakefile --configfile tests/pipeline/tiny.yaml \
    --config out="$pipeline_out" strata="$pipeline_strata" "$@"
}

pipeline_check() {
  local c
  for c in sphere_h1e-3 sphere_h1e-4; do
    test -s "$pipeline_out/$c/mesh.cgr" || { echo "no mesh for $c"; exit 1; }
    test -s "$pipeline_out/$c/benchmark.tsv" || { echo "no benchmark for $c"; exit 1; }
  done
  /usr/bin/python3 - "$pipeline_out" <<'PY'
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
}

pipeline_check_rerun() {
  local second
  second=$(pipeline_run -n "$@" 2>&1)
  echo "$second" | grep -q "Nothing to be done" || { echo "second run would do something:"; echo "$second"; exit 1; }
}
