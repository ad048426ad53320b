# A private one-node Slurm cluster for tests; source it, then:
#   slurm_cluster_start DIR   munged, slurmctld and slurmd with everything (key, socket, ports,
#                             state, spool, logs, pids) under DIR; exports SLURM_CONF; returns 1
#                             with a message when a daemon does not come up
#   slurm_cluster_stop        cancels the jobs still queued, stops the three daemons by the PIDs
#                             it started (never by name) and waits for them; safe to call twice
# The node is this machine's short hostname with CPUs = nproc; proctrack/linuxproc and
# task/none need no cgroups; no accounting database. Needs root (SlurmUser=root) and the Debian
# packages slurm-wlm and munge (Slurm 22.05, munge 0.5.15).

slurm_cluster_pids=()

# A TCP port nobody listens on (probed with bash's /dev/tcp), from a random start.
slurm_free_port() {
  local port
  for _ in $(seq 200); do
    port=$((20000 + RANDOM % 30000))
    if ! (echo >"/dev/tcp/127.0.0.1/$port") 2>/dev/null; then echo "$port"; return 0; fi
  done
  return 1
}

# slurm_wait_for SECONDS MESSAGE COMMAND...: polls COMMAND every 0.5 s until it succeeds; gives up
# with MESSAGE when COMMAND exits 2 (slurm_alive_and: a daemon died) or, for SECONDS > 0, after
# SECONDS. The test's waits use 0 (no deadline: a slow machine is not a failure; ctest's timeout
# ends a hang); only the cleanup bounds its wait.
slurm_wait_for() {
  local seconds=$1 message=$2; shift 2
  local deadline=$((SECONDS + seconds))
  local status
  until "$@" >/dev/null 2>&1; do
    status=$?
    if ((status == 2)); then echo "$message" >&2; return 1; fi
    if ((seconds > 0 && SECONDS >= deadline)); then echo "timed out after ${seconds} s: $message" >&2; return 1; fi
    sleep 0.5
  done
}

# slurm_alive_and PID COMMAND...: COMMAND succeeds; exits the wait loop early (status 2, with a
# message) when the daemon PID has died.
slurm_alive_and() {
  local pid=$1; shift
  kill -0 "$pid" 2>/dev/null || { echo "process $pid exited" >&2; return 2; }
  "$@"
}

# slurm_cluster_alive_and COMMAND...: slurm_alive_and for every daemon started.
slurm_cluster_alive_and() {
  local pid
  for pid in "${slurm_cluster_pids[@]}"; do
    kill -0 "$pid" 2>/dev/null || { echo "process $pid exited" >&2; return 2; }
  done
  "$@"
}

slurm_node_idle() { sinfo -h -N -o '%t' | grep -qx 'idle'; }

slurm_cluster_start() {
  local dir=$1 host cpus ctld_port slurmd_port
  host=$(hostname -s)
  cpus=$(nproc)
  # munged insists: the socket's folders searchable by all, the key readable by its owner only.
  mkdir -p "$dir"/{run,key,state,spool,log}
  chmod 755 "$dir" "$dir/run"
  chmod 700 "$dir/key"
  mungekey --create --keyfile="$dir/key/munge.key" || return 1
  munged --foreground --socket="$dir/run/munge.sock" --key-file="$dir/key/munge.key" \
    --pid-file="$dir/run/munged.pid" --log-file="$dir/log/munged.log" --seed-file="$dir/key/munged.seed" \
    >>"$dir/log/munged.out" 2>&1 &
  slurm_cluster_pids+=($!)
  slurm_wait_for 0 "munged did not create its socket (log: $dir/log/munged.log)" \
    slurm_alive_and "$!" test -S "$dir/run/munge.sock" || return 1
  ctld_port=$(slurm_free_port) && slurmd_port=$(slurm_free_port) || { echo "no free TCP port" >&2; return 1; }
  cat >"$dir/slurm.conf" <<CONF
ClusterName=tidalcrust-test
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/run/munge.sock
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
KillWait=30
MinJobAge=600
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF="$dir/slurm.conf"
  slurmctld -D -f "$SLURM_CONF" >>"$dir/log/slurmctld.out" 2>&1 &
  slurm_cluster_pids+=($!)
  slurmd -D -f "$SLURM_CONF" >>"$dir/log/slurmd.out" 2>&1 &
  slurm_cluster_pids+=($!)
  slurm_wait_for 0 "the node $host did not become idle (logs: $dir/log/slurmctld.log, $dir/log/slurmd.log)" \
    slurm_cluster_alive_and slurm_node_idle
}

slurm_cluster_stop() {
  ((${#slurm_cluster_pids[@]})) || return 0
  if [ -n "${SLURM_CONF:-}" ] && kill -0 "${slurm_cluster_pids[1]:-0}" 2>/dev/null; then
    scancel --full --quiet --user=root 2>/dev/null
    slurm_wait_for 40 "jobs still running after scancel" test -z "$(squeue -h 2>/dev/null)" || true
  fi
  local pid
  for ((i = ${#slurm_cluster_pids[@]} - 1; i >= 0; i--)); do
    pid=${slurm_cluster_pids[i]}
    kill -TERM "$pid" 2>/dev/null && wait "$pid" 2>/dev/null
  done
  slurm_cluster_pids=()
}
