#!/usr/bin/env bash
# Snakemake's --cluster-status for Slurm (this profile's config.yaml): prints the state of the job
# whose id sbatch --parsable gave (ID or ID;CLUSTER) as success, failed or running. scontrol knows
# a job until MinJobAge (5 minutes by default) after it ended, sacct afterwards where the cluster
# keeps accounting; a job neither knows is reported failed.
#   slurm-status.sh JOBID
set -euo pipefail
id=${1%%;*}
state=""
if out=$(scontrol show job -o "$id" 2>&1); then
  state=${out#*JobState=}
  state=${state%% *}
elif [[ $out != *"Invalid job id"* ]]; then
  echo running                      # slurmctld did not answer: ask again at the next check
  exit 0
elif command -v sacct >/dev/null; then
  state=$(sacct -n -X -P -j "$id" -o State 2>/dev/null | head -n 1) || true
  state=${state%% *}               # "CANCELLED by UID"
fi
case "$state" in
  COMPLETED) echo success ;;
  PENDING | CONFIGURING | RUNNING | COMPLETING | SUSPENDED | REQUEUED | REQUEUE_FED | REQUEUE_HOLD | \
    RESIZING | SIGNALING | STAGE_OUT | RESV_DEL_HOLD) echo running ;;
  *)
    echo "slurm-status.sh: job $id is ${state:-unknown to scontrol and sacct}" >&2
    echo failed
    ;;
esac
