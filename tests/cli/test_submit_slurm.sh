#!/usr/bin/env bash
# `tidalcrust submit --slurm` on a real Slurm: a private one-node cluster
# (tests/support/slurm_test_cluster.sh) runs the 4-encounter quick-body sweep
# tests/support/sweep-small.toml; every checkpoint must have the state_hash of a local
# sequential `run`. One encounter task is requeued (scontrol requeue) while it computes its
# encounter: it must write its mid-stage checkpoint, resume from it and still end bit-identical.
# Then the 40 encounters of workflows/sweep-quick.toml through Slurm against `run --jobs 2`.
# Usage: test_submit_slurm.sh TIDALCRUST_EXE SOURCE_DIR. Exit 77 (skipped) when not root.
set -uo pipefail
exe=$1
source_dir=$2
workflow=$source_dir/tests/support/sweep-small.toml
fail() { echo "FAIL: $*" >&2; exit 1; }

if [ "$(id -u)" != 0 ]; then
  echo "SKIP: not root: the test cluster runs slurmctld and slurmd with SlurmUser=root"
  exit 77
fi
missing=()
for program in munged mungekey slurmctld slurmd sbatch squeue scontrol scancel sinfo; do
  command -v "$program" >/dev/null || missing+=("$program")
done
((${#missing[@]} == 0)) || fail "not installed: ${missing[*]} (Debian packages slurm-wlm and munge; make deps installs them)"

source "$source_dir/tests/support/slurm_test_cluster.sh"
work=$(mktemp -d /tmp/tidalcrust-slurm.XXXXXX)
chmod 755 "$work"  # munged needs its socket's folders searchable by all
cleanup() {
  slurm_cluster_stop
  if [ "${keep:-0}" = 1 ]; then echo "kept $work"; else rm -rf "$work"; fi
}
trap cleanup EXIT
trap 'exit 1' INT TERM
on_failure() { keep=1; for f in "$work"/cluster/log/* "$work"/sweep/slurm/logs/*.log; do
  [ -f "$f" ] && { echo "--- $f (last lines)"; tail -n 15 "$f"; }; done; }

slurm_cluster_start "$work/cluster" || { on_failure; fail "the test cluster did not start"; }
echo "cluster up: $SLURM_CONF"

# One task at a time, one CPU each: the requeued task is caught while it computes.
cd "$work" || fail "cannot enter $work"
submitted=$("$exe" submit "$workflow" --slurm --out "$work/sweep" --max-running 1 --cpus-per-task 1 --time 30:00) ||
  { on_failure; fail "submit exited $?: $submitted"; }
echo "$submitted"
body_job=$(sed -n 's/^body chain: job \([0-9]*\).*/\1/p' <<<"$submitted")
array_job=$(sed -n 's/^encounters: job array \([0-9]*\).*/\1/p' <<<"$submitted")
[ -n "$body_job" ] && [ -n "$array_job" ] || fail "submit did not report the job ids"
mapfile -t names < <("$exe" submit "$workflow" --slurm --dry-run --out "$work/sweep" |
  sed -n '/encounters-.*\.txt <==$/,/^# ==>/p' | grep -v '^#')
((${#names[@]} == 4)) || fail "expected 4 encounter names, got ${#names[*]}: ${names[*]}"

# The reference: the same sweep run locally, one encounter after another (meanwhile Slurm works).
"$exe" run "$workflow" --out "$work/local" --threads 1 --quiet >"$work/local.log" 2>&1 &
local_pid=$!

# Requeue the first task caught computing its encounter. SIGSTOP holds it there (so it cannot
# finish first); Slurm sends SIGCONT and SIGTERM when it requeues, it writes its mid-stage
# checkpoint and exits 130, and the requeued task resumes from that checkpoint.
# No deadlines (a slow machine is not a failure; ctest's timeout ends a hang): a wait gives up when
# a daemon died or the jobs it waits for left the queue.
jobs_queued() { [ -n "$(squeue -h -j "$1" 2>/dev/null)" ]; }
requeued=
for task in "${!names[@]}"; do
  name=${names[task]}
  lock=$work/sweep/$name/encounter.h5.lock
  until [ -f "$lock" ] && grep -q '^pid=' "$lock" 2>/dev/null; do
    slurm_cluster_alive_and true || { on_failure; fail "a Slurm daemon died while waiting for task $task"; }
    [ -f "$work/sweep/$name/encounter.h5" ] && break
    jobs_queued "$body_job,$array_job" || [ -f "$lock" ] || [ -f "$work/sweep/$name/encounter.h5" ] ||
      { on_failure; fail "the jobs left the queue before task $task started its encounter"; }
    sleep 0.2
  done
  [ -f "$work/sweep/$name/encounter.h5" ] && continue
  pid=$(sed -n 's/^pid=//p' "$lock")
  kill -STOP "$pid" 2>/dev/null || continue
  if [ -f "$work/sweep/$name/encounter.h5" ]; then kill -CONT "$pid"; continue; fi
  scontrol requeue "${array_job}_${task}" || { kill -CONT "$pid"; on_failure; fail "scontrol requeue ${array_job}_${task} failed"; }
  requeued=$task
  echo "requeued task $task ($name) while its encounter ran (pid $pid)"
  # Slurm makes a requeued job eligible only after a delay; let it start as soon as it is pending.
  slurm_wait_for 0 "task $task did not return to the queue" \
    slurm_cluster_alive_and bash -c "squeue -h -j ${array_job}_${task} -o %T | grep -qx PENDING"
  echo "requeued task: $(scontrol show job "${array_job}_${task}" | grep -o 'EligibleTime=[^ ]*')"
  scontrol update JobId="${array_job}_${task}" StartTime=now || fail "cannot reset the start time of task $task"
  break
done
[ -n "$requeued" ] || { on_failure; fail "every task had finished its encounter before it could be requeued"; }

wait "$local_pid" || { cat "$work/local.log"; fail "the local run failed"; }
echo "local run done"
while jobs_queued "$body_job,$array_job"; do
  slurm_cluster_alive_and true || { squeue; on_failure; fail "a Slurm daemon died before the jobs finished"; }
  sleep 1
done

state_hash() { "$exe" inspect "$1" --json | sed -n 's/.*"state_hash": *"\([0-9a-f]*\)".*/\1/p'; }
for file in body/build.h5 body/stretch.h5 body/relax.h5 "${names[@]/%//encounter.h5}"; do
  [ -f "$work/sweep/$file" ] || { on_failure; fail "Slurm did not write $file"; }
  a=$(state_hash "$work/local/$file") b=$(state_hash "$work/sweep/$file")
  [ -n "$a" ] && [ "$a" = "$b" ] || { on_failure; fail "$file: state_hash $b under Slurm, $a locally"; }
  echo "$file: $b (same as the local run)"
done
log=$work/sweep/slurm/logs/encounter-$requeued.log
grep -q "restart 1" "$log" || { on_failure; fail "$log shows no second start of the requeued task"; }
# SIGTERM from Slurm: the first attempt stopped at step N and wrote its mid-stage checkpoint there;
# the second resumed from exactly that step.
stopped=$(sed -n 's/.*: interrupted at step \([0-9]*\).*/\1/p' "$log" | head -n 1)
[ -n "$stopped" ] || { on_failure; fail "$log: the requeued task did not stop on Slurm's SIGTERM"; }
grep -q "resuming from .*/encounter.mid.h5 (step $stopped)" "$log" ||
  { on_failure; fail "$log: the requeued task did not resume from the checkpoint written at step $stopped"; }
echo "--- $log"; cat "$log"
echo "4 encounters under Slurm bit-identical to the local run, also the requeued one"

# The whole 40-encounter sweep of workflows/sweep-quick.toml (2 x 5 x 4) through Slurm, two tasks
# at a time, against `run --jobs 2` on this machine: every checkpoint has the same state_hash.
# Without the figures ([analysis] figures = false), which took most of each task's time and which
# the first part's tasks drew.
sweep=$work/sweep-quick.toml
{ cat "$source_dir/workflows/sweep-quick.toml"; printf '\n[analysis]\nfigures = false\n'; } >"$sweep"
submitted=$("$exe" submit "$sweep" --slurm --out "$work/sweep40" --max-running 2 --cpus-per-task 1 --time 30:00) ||
  { on_failure; fail "submit of sweep-quick exited $?: $submitted"; }
body_job=$(sed -n 's/^body chain: job \([0-9]*\).*/\1/p' <<<"$submitted")
array_job=$(sed -n 's/^encounters: job array \([0-9]*\).*/\1/p' <<<"$submitted")
[ -n "$body_job" ] && [ -n "$array_job" ] || fail "submit of sweep-quick did not report the job ids"
"$exe" run "$sweep" --out "$work/jobs40" --jobs 2 --quiet >"$work/jobs40.log" 2>&1 ||
  { cat "$work/jobs40.log"; fail "run --jobs 2 of sweep-quick failed"; }
while jobs_queued "$body_job,$array_job"; do
  slurm_cluster_alive_and true || { squeue; on_failure; fail "a Slurm daemon died before the sweep-quick jobs finished"; }
  sleep 1
done
mapfile -t names < <("$exe" submit "$sweep" --slurm --dry-run --out "$work/sweep40" |
  sed -n '/encounters-.*\.txt <==$/,/^# ==>/p' | grep -v '^#')
((${#names[@]} == 40)) || fail "expected 40 sweep-quick encounters, got ${#names[*]}"
for file in body/relax.h5 "${names[@]/%//encounter.h5}"; do
  [ -f "$work/sweep40/$file" ] || { on_failure; fail "Slurm did not write sweep-quick's $file"; }
  case $file in */encounter.h5)
    [ -f "$work/sweep40/${file%encounter.h5}analysis/summary.json" ] || fail "no summary.json beside sweep-quick's $file";;
  esac
  a=$(state_hash "$work/jobs40/$file") b=$(state_hash "$work/sweep40/$file")
  [ -n "$a" ] && [ "$a" = "$b" ] || { on_failure; fail "sweep-quick $file: state_hash $b under Slurm, $a with --jobs 2"; }
done
echo "PASS: 4 encounters (one requeued) and the 40 of sweep-quick under Slurm bit-identical to local runs"
