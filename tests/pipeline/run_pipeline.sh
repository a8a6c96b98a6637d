#!/usr/bin/env bash
# The Snakemake workflow (examples/pipeline) on two small sphere variants, two jobs at once:
# both meshes and reports are made, the table has one row per case with cells that add up,
# and a second run does nothing (every output up to date).
#   tests/pipeline/run_pipeline.sh STRATA
set -euo pipefail
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pipeline_setup "$tmp" "$1"
pipeline_run -j2 -q
pipeline_check
pipeline_check_rerun -j2
echo "pipeline: two cases meshed, table checked, rerun is a no-op"
