# shellcheck shell=bash
# A one-node Slurm on this machine for a test (sourced by tests/pipeline/run_slurm.sh): Debian's
# slurm-wlm 22.05 (slurmctld, slurmd) and munged, each in the foreground of a background job,
# with every file in the directory given (configuration, munge key and socket, state, spool,
# logs) and free ports of their own, so a system Slurm or munged, if any, is neither used nor
# disturbed. The daemons run as the current user (root in CI; another user works too) and so
# do the jobs.
#   slurm_start DIR    start munged, slurmctld and slurmd; return once the node is idle
#                      (exported: SLURM_CONF, which sbatch, squeue, scontrol ... read). DIR's
#                      parent directories must be open to all (munged checks its socket's path)
#   slurm_stop         cancel every job, stop the daemons, end any process left with this
#                      cluster's SLURM_CONF (a job's); safe to call twice, or before a start
slurm_dir=""
slurm_pids=()     # munged, slurmctld, slurmd, as started
slurm_names=()

# slurm_fail WHAT: the message, every log so far, exit 1.
slurm_fail() {
  echo "slurm: $1" >&2
  local log
  for log in "$slurm_dir"/log/*; do
    [ -s "$log" ] && { echo "--- $log ---" >&2; tail -n 40 "$log" >&2; }
  done
  exit 1
}

# slurm_free_ports N: N distinct TCP ports that nothing listens on now.
slurm_free_ports() {
  /usr/bin/python3 - "$1" <<'PY'
import socket, sys
socks = [socket.socket() for _ in range(int(sys.argv[1]))]
for s in socks:
    s.bind(("127.0.0.1", 0))
print(" ".join(str(s.getsockname()[1]) for s in socks))
PY
}

# slurm_write_conf: DIR/etc/slurm.conf for one node (this machine's CPUs and memory, as
# `slurmd -C` finds them) in one partition, at 127.0.0.1.
slurm_write_conf() {
  local user node name ports
  user=$(id -un)
  node=$(slurmd -C | head -n 1)           # NodeName=HOST CPUs=... RealMemory=...
  [[ $node == NodeName=* ]] || slurm_fail "slurmd -C printed no node line: $node"
  name=${node%% *}
  name=${name#NodeName=}
  read -r -a ports <<<"$(slurm_free_ports 2)"
  : >"$slurm_dir/etc/plugstack.conf"
  cat >"$slurm_dir/etc/slurm.conf" <<EOF
ClusterName=strata-test
SlurmctldHost=$(hostname -s)(127.0.0.1)
SlurmctldPort=${ports[0]}
SlurmdPort=${ports[1]}
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$slurm_dir/munge/munge.socket
StateSaveLocation=$slurm_dir/state
SlurmdSpoolDir=$slurm_dir/spool
SlurmctldPidFile=$slurm_dir/run/slurmctld.pid
SlurmdPidFile=$slurm_dir/run/slurmd.pid
MailProg=/bin/true
PlugStackConfig=$slurm_dir/etc/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=test Nodes=$name Default=YES MaxTime=INFINITE State=UP
EOF
}

# slurm_wait WHAT SECONDS CHECK...: run CHECK every 0.2 s until it succeeds; fail (with the logs)
# if a daemon has died or SECONDS have passed.
slurm_wait() {
  local what=$1 seconds=$2 deadline=$((SECONDS + $2)) i
  shift 2
  until "$@" >/dev/null 2>&1; do
    for i in "${!slurm_pids[@]}"; do
      kill -0 "${slurm_pids[i]}" 2>/dev/null || slurm_fail "${slurm_names[i]} exited while waiting for $what"
    done
    [ "$SECONDS" -lt "$deadline" ] || slurm_fail "still waiting for $what after $seconds s"
    sleep 0.2
  done
}

# slurm_launch NAME ARGS...: start the daemon NAME in the foreground of a background job, its
# output in DIR/log/NAME.log.
slurm_launch() {
  "$@" >"$slurm_dir/log/$1.log" 2>&1 &
  slurm_pids+=($!)
  slurm_names+=("$1")
}

slurm_node_idle() { [ "$(sinfo -h -N -o %t)" = idle ]; }

slurm_start() {
  local var sock
  slurm_dir=$1
  mkdir -p "$slurm_dir"/{etc,state,spool,run,log}
  # munged insists that everyone may reach its socket's directory, and no one else write there.
  chmod 755 "$slurm_dir"
  mkdir -m 755 "$slurm_dir/munge"
  # a surrounding Slurm job's or the user's settings (SLURM_*, SBATCH_* ...) would steer this one
  for var in $(compgen -e); do
    if [[ $var =~ ^(SLURM|SBATCH|SALLOC|SRUN|SQUEUE|SINFO|SCONTROL|SCANCEL)_ ]]; then unset "$var"; fi
  done
  export SLURM_CONF=$slurm_dir/etc/slurm.conf
  slurm_write_conf
  mungekey --create --keyfile="$slurm_dir/munge/munge.key"
  sock=$slurm_dir/munge/munge.socket
  slurm_launch munged --foreground --key-file="$slurm_dir/munge/munge.key" --socket="$sock" \
    --pid-file="$slurm_dir/run/munged.pid" --seed-file="$slurm_dir/munge/munged.seed"
  slurm_wait "munged to give a credential" 10 bash -c "munge -n -S '$sock' | unmunge -S '$sock'"
  slurm_launch slurmctld -D -c
  slurm_wait "slurmctld to answer" 30 scontrol ping
  slurm_launch slurmd -D
  slurm_wait "the node to be idle (sinfo)" 60 slurm_node_idle
}

# slurm_end PID: SIGTERM, and SIGKILL if it is still there 10 s later.
slurm_end() {
  local deadline=$((SECONDS + 10))
  kill "$1" 2>/dev/null || true
  while kill -0 "$1" 2>/dev/null && [ "$SECONDS" -lt "$deadline" ]; do sleep 0.1; done
  kill -9 "$1" 2>/dev/null || true
  wait "$1" 2>/dev/null || true
}

# slurm_leftovers: the processes of this cluster's jobs still there (slurmstepd, which outlives
# slurmd, and a job's own processes: both carry this cluster's SLURM_CONF).
slurm_leftovers() {
  local env pid
  for env in /proc/[0-9]*/environ; do
    pid=${env#/proc/}
    pid=${pid%/environ}
    grep -qzx "SLURM_CONF=$slurm_dir/etc/slurm.conf" "$env" 2>/dev/null || continue
    if [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = slurmstepd ] || grep -qz '^SLURM_JOB_ID=' "$env" 2>/dev/null; then
      echo "$pid"
    fi
  done
}

slurm_stop() {
  [ -n "$slurm_dir" ] || return 0
  local i pid deadline=$((SECONDS + 30))
  # jobs first (a running one needs slurmd and slurmctld to end), then the daemons
  if [ ${#slurm_pids[@]} -eq 3 ] && kill -0 "${slurm_pids[1]}" 2>/dev/null; then
    timeout 10 scancel --user="$(id -un)" 2>/dev/null || true
    while [ -n "$(timeout 5 squeue -h -o %i 2>/dev/null)" ] && [ "$SECONDS" -lt "$deadline" ]; do sleep 0.2; done
  fi
  for ((i = ${#slurm_pids[@]} - 1; i >= 0; i--)); do   # slurmd, slurmctld, munged
    slurm_end "${slurm_pids[i]}"
  done
  for pid in $(slurm_leftovers); do
    echo "slurm: ending a job's leftover process $pid ($(tr '\0' ' ' <"/proc/$pid/cmdline" 2>/dev/null))" >&2
    kill -9 "$pid" 2>/dev/null || true
  done
  slurm_pids=()
  slurm_names=()
  slurm_dir=""
}
