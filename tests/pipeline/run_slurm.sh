#!/usr/bin/env bash
# The Snakemake workflow (examples/pipeline) through Slurm, as docs/USAGE.md shows it: a one-node
# Slurm with its own munged (slurm_cluster.sh) is started in a temporary directory, and the two
# small sphere variants run with the workflow's Slurm profile (examples/pipeline/slurm). Checked:
# each mesh job ran as a Slurm job (the ids sbatch gave, COMPLETED in scontrol with the memory,
# time and CPUs the rules asked, their Slurm output naming each case once), the table as in
# run_pipeline.sh, a second run has nothing to do; the profile's status script sees a held job
# as running and a cancelled one as failed. The cluster is stopped and the directory removed
# on exit, whatever happened.
#   tests/pipeline/run_slurm.sh STRATA
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=common.sh
source "$here/common.sh"
# shellcheck source=slurm_cluster.sh
source "$here/slurm_cluster.sh"
PATH=$PATH:/usr/sbin                  # munged, slurmctld, slurmd (not on a user's PATH in Debian)
for p in munged mungekey slurmctld slurmd sbatch scontrol snakemake; do
  command -v "$p" >/dev/null || { echo "run_slurm.sh: no $p (scripts/setup.sh installs slurm-wlm, munge, snakemake)"; exit 1; }
done
status=$here/../../examples/pipeline/slurm/slurm-status.sh
start=$SECONDS
tmp=$(mktemp -d)
chmod 755 "$tmp"                      # munged: everyone may reach its socket's directory
trap 'slurm_stop; rm -rf "$tmp"' EXIT

# ask_status ID EXPECTED: what the profile's status script says of job ID.
ask_status() {
  local said
  said=$("$status" "$1" 2>/dev/null) || true
  [ "$said" = "$2" ] || { echo "slurm-status.sh $1: '$said', not '$2' ($(scontrol show job -o "$1"))"; exit 1; }
}

# check_jobs LOG: the jobs Snakemake submitted (LOG: its output) are the two mesh jobs, each ran
# to completion under Slurm with the resources tiny.yaml asks (1 thread, 500 MB, 5 minutes), and
# their Slurm outputs name both cases.
check_jobs() {
  local ids id job want cases=()
  ids=$(sed -n "s/^Submitted job [0-9]* with external jobid '\([0-9]*\)'\.$/\1/p" "$1")
  [ "$(echo "$ids" | wc -w)" -eq 2 ] || { echo "not two Slurm jobs submitted:"; cat "$1"; exit 1; }
  for id in $ids; do
    job=$(scontrol show job -o "$id")
    for want in JobState=COMPLETED ExitCode=0:0 JobName=snakejob.mesh. CPUs/Task=1 MinMemoryNode=500M \
      TimeLimit=00:05:00; do
      [[ " $job" == *" $want"* ]] || { echo "Slurm job $id: no $want in: $job"; exit 1; }
    done
    test -s ".snakemake/slurm-$id.out" || { echo "Slurm job $id left no output"; exit 1; }
    cases+=("$(sed -n 's/^ *wildcards: case=//p' ".snakemake/slurm-$id.out")")
  done
  [ "$(printf '%s\n' "${cases[@]}" | sort | xargs)" = "sphere_h1e-3 sphere_h1e-4" ] ||
    { echo "the Slurm jobs' outputs name the cases '${cases[*]}'"; exit 1; }
}

slurm_start "$tmp/slurm"
held=$(sbatch --parsable --hold --output=/dev/null --wrap true)
ask_status "$held" running
scancel "$held"
ask_status "$held" failed

pipeline_setup "$tmp" "$1"
pipeline_run --profile examples/pipeline/slurm >"$tmp/snakemake.log" 2>&1 ||
  { cat "$tmp/snakemake.log" .snakemake/slurm-*.out 2>/dev/null; slurm_fail "the workflow failed on Slurm"; }
check_jobs "$tmp/snakemake.log"
pipeline_check
pipeline_check_rerun --profile examples/pipeline/slurm
echo "pipeline on Slurm: two cases meshed as Slurm jobs, table checked, rerun is a no-op ($((SECONDS - start)) s)"
