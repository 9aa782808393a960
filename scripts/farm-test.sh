#!/usr/bin/env bash
# `make farm-test`: the render-farm and sweep recipes of docs/render-farm/ run under a real Slurm.
# Starts a one-node cluster on this machine (munged, slurmctld, slurmd as this script's own
# processes, configured in a temporary directory, always stopped by their process ids at the end,
# on failure and on Ctrl-C too), then:
#   1. render.slurm as an array of 4 tasks over 24 frames of the monkey's walk, then the dependent
#      video job: every frame byte-identical to one `pelage render` process, the video present;
#   2. the same with one task cancelled part-way (scancel) and requeued (scontrol requeue): --resume
#      completes the range to the same bytes;
#   3. sweep.slurm as an array (one stiffness value per task) and a dependent merge step: the same
#      CSV as one `pelage analyze --sweep` process.
# Each check prints what it compared and the wall time from submission to completion. A daemon
# that cannot start fails the test with its log; nothing passes without the jobs having run.
# Usage: scripts/farm-test.sh [BUILD_DIR]   (needs root: munged and slurmd run as root here)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=${1:-build}
bin=$(cd "$build/bin" && pwd)/pelage
[[ -x "$bin" ]] || { echo "farm-test: $bin is not built (make build first)" >&2; exit 2; }
[[ $(id -u) -eq 0 ]] || { echo "farm-test: needs root (munged and slurmd run as root)" >&2; exit 2; }

# Slurm and munge from Debian (the only packages this test needs beyond the build's).
missing=()
for p in slurm-wlm munge; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "farm-test: installing ${missing[*]}"
  DEBIAN_FRONTEND=noninteractive apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

work=$(mktemp -d /tmp/pelage-farm.XXXXXX)
pids=()
status=1
cleanup() {
  local p
  # The jobs first (their step daemons outlive slurmd otherwise), then the daemons.
  if [[ -n "${SLURM_CONF:-}" ]] && squeue -h 2>/dev/null | grep -q .; then
    scancel --full --quiet --user=root 2>/dev/null || true
    for _ in $(seq 100); do squeue -h 2>/dev/null | grep -q . || break; sleep 0.1; done
  fi
  for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null || true; done
  for p in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$p" 2>/dev/null || true
    wait "$p" 2>/dev/null || true
  done
  if ((status == 0)); then
    rm -rf "$work"
  else
    echo "farm-test: FAILED; the cluster's files and logs are in $work" >&2
  fi
}
trap cleanup EXIT
trap 'echo "farm-test: interrupted" >&2; exit 130' INT TERM

fail() {
  echo "farm-test: FAILED: $*" >&2
  exit 1
}

# A free TCP port on the loopback (ports of our own choosing, not Slurm's defaults).
free_port() {
  python3 - <<'EOF'
import socket
s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1]); s.close()
EOF
}

# ---- The cluster ----------------------------------------------------------------------------
mkdir -p "$work"/{munge,state,spool,logs,out}
chmod 700 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
socket=$work/munge/munge.socket
munged -F -f --key-file="$work/munge/munge.key" --socket="$socket" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munge/munged.log" \
  --seed-file="$work/munge/munged.seed" >"$work/logs/munged.out" 2>&1 &
pids+=($!)
for _ in $(seq 100); do [[ -S "$socket" ]] && break; sleep 0.05; done
[[ -S "$socket" ]] || fail "munged did not start: $(cat "$work/logs/munged.out" "$work/munge/munged.log" 2>/dev/null)"

cpus=$(nproc)
memory=$(($(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 / 2))
host=$(hostname -s)
ctld_port=$(free_port)
slurmd_port=$(free_port)
export SLURM_CONF=$work/slurm.conf
cat >"$SLURM_CONF" <<EOF
# A one-node Slurm cluster for scripts/farm-test.sh (written afresh each run).
ClusterName=pelagefarm
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/logs/slurmctld.log
SlurmdLogFile=$work/logs/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
MpiDefault=none
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
MinJobAge=3600
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=farm Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -D -i -f "$SLURM_CONF" >"$work/logs/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N "$host" >"$work/logs/slurmd.out" 2>&1 &
pids+=($!)
ready=0
for _ in $(seq 200); do
  if sinfo -h -o '%t' 2>/dev/null | grep -qE '^(idle|mix|alloc)'; then
    ready=1
    break
  fi
  for p in "${pids[@]}"; do
    kill -0 "$p" 2>/dev/null ||
      fail "a daemon exited: $(tail -n 20 "$work"/logs/*.out "$work"/logs/*.log 2>/dev/null)"
  done
  sleep 0.1
done
((ready)) || fail "the node never became idle: $(sinfo 2>&1); $(tail -n 20 "$work"/logs/*.log 2>/dev/null)"
echo "farm-test: Slurm $(sinfo -V | awk '{print $2}'), node $host with $cpus CPUs, munged and daemons pids ${pids[*]}"

# ---- Helpers --------------------------------------------------------------------------------
now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$(now)" 'BEGIN {printf "%.1f", b - a}'; }

# Waits (at most $2 seconds) until job $1 (and its array tasks) left the queue.
wait_job() {
  local job=$1 limit=$2 start
  start=$(date +%s)
  while squeue -h -j "$job" 2>/dev/null | grep -q .; do
    (($(date +%s) - start < limit)) || fail "job $job still queued after ${limit} s: $(squeue -j "$job")"
    sleep 0.5
  done
}

# Every task of job $1 ended COMPLETED (the controller keeps finished jobs for MinJobAge).
check_completed() {
  local job=$1 states
  states=$(scontrol -o show job "$job" | grep -o 'JobState=[A-Z_]*' | sort | uniq -c | tr -s ' ')
  if scontrol -o show job "$job" | grep -o 'JobState=[A-Z_]*' | grep -qv 'JobState=COMPLETED'; then
    fail "job $job did not complete:$states; logs: $(tail -n 20 "$work"/logs/job-* 2>/dev/null)"
  fi
}

# Waits for job $1 (at most $2 seconds) and checks that every task of it completed.
finish_job() {
  wait_job "$1" "$2"
  check_completed "$1"
}

# Submits docs/render-farm/$1 as an array job of tasks 0..$2 (one CPU each), the NAME=VALUE pairs
# after them in its environment; prints its id.
array_job() {
  local script=$1 last=$2
  shift 2
  (cd docs/render-farm && env "$@" sbatch --parsable --export=ALL --array=0-"$last" \
    --cpus-per-task=1 --mem=1500M --output="$work/logs/job-%A_%a.log" "$script")
}

# Submits command $4 as a one-CPU job (memory $3, log job-$2-ID.log) that runs once job $1 completed;
# prints its id.
after_job() {
  sbatch --parsable --dependency=afterok:"$1" --cpus-per-task=1 --mem="$3" \
    --output="$work/logs/job-$2-%j.log" --wrap "$4"
}

# Frames of $1 byte-identical to $2's (the same names, 24 of them).
compare_frames() {
  local got=$1 ref=$2 n=0 f
  for f in "$ref"/frame_*.png; do
    cmp -s "$f" "$got/$(basename "$f")" || fail "$got/$(basename "$f") differs from $f"
    n=$((n + 1))
  done
  [[ $(find "$got" -name 'frame_*.png' | wc -l) -eq $n ]] || fail "$got has other frames than $ref"
  echo "$n"
}

args="monkey --clip walk --fps 30 --size 320x240 --camera side --follow --hairs 20000"
frames=23  # 0..23: 24 frames
# One process, the reference.
"$bin" --threads 2 render $args --frames 0:$frames --out "$work/out/reference" --quiet

# ---- 1. The render array and the dependent video ---------------------------------------------
start=$(now)
job=$(array_job render.slurm 3 FIRST=0 LAST=$frames OUT="$work/out/array" PELAGE="$bin" PELAGE_ARGS="$args")
video=$(after_job "$job" video 1500M \
  "$bin render $args --frames 0:$frames --out $work/out/array --resume --quiet --video $work/out/walk.mp4")
finish_job "$job" 600
finish_job "$video" 300
n=$(compare_frames "$work/out/array" "$work/out/reference")
[[ -s "$work/out/walk.mp4" ]] || fail "the video job left no $work/out/walk.mp4"
echo "farm-test: 1. render.slurm array job $job (4 tasks) + video job $video: $n frames" \
  "byte-identical to one process, walk.mp4 $(stat -c %s "$work/out/walk.mp4") bytes;" \
  "$(elapsed "$start") s from submission to completion"

# ---- 2. A task cancelled part-way, requeued, resumed ------------------------------------------
start=$(now)
out=$work/out/requeue
job=$(array_job render.slurm 3 FIRST=0 LAST=$frames OUT="$out" PELAGE="$bin" PELAGE_ARGS="$args")
# Task 0 renders frames 0..5: cancel it once it has written some of them but not all.
cancelled=0
for _ in $(seq 1200); do
  written=$( (find "$out" -name 'frame_0000[0-5].png' 2>/dev/null || true) | wc -l)
  if ((written >= 1 && written < 6)) && squeue -h -j "${job}_0" -t RUNNING | grep -q .; then
    scancel "${job}_0"
    cancelled=$written
    break
  fi
  squeue -h -j "${job}_0" | grep -q . || break
  sleep 0.05
done
((cancelled > 0)) || fail "task ${job}_0 finished before it could be cancelled part-way"
for _ in $(seq 100); do
  scontrol -o show job "${job}_0" | grep -q 'JobState=CANCELLED' && break
  sleep 0.1
done
scontrol requeue "${job}_0" || fail "scontrol requeue ${job}_0 failed"
# Slurm holds a requeued job back (BeginTime two minutes on); a retry need not wait here.
scontrol update JobId="${job}_0" StartTime=now || fail "cannot release the requeued ${job}_0"
finish_job "$job" 600
n=$(compare_frames "$out" "$work/out/reference")
skipped=$(grep -ho 'skipped [0-9]* complete' "$work/logs/job-${job}_0.log" | tail -n 1 || true)
echo "farm-test: 2. array job $job: task ${job}_0 cancelled after $cancelled of its 6 frames," \
  "requeued, resumed (${skipped:-no complete frame skipped}): $n frames byte-identical to one" \
  "process; $(elapsed "$start") s from submission to completion"

# ---- 3. A stiffness sweep as an array and its merge step ---------------------------------------
sweep=stiffness=0.1:0.9:5
sweep_args="monkey --clip tumble --frames 0:30 --hairs 20000"
"$bin" --threads 2 analyze $sweep_args --sweep "$sweep" --out "$work/out/sweep-reference.csv" --quiet
start=$(now)
job=$(array_job sweep.slurm 4 SWEEP="$sweep" OUT="$work/out/sweep" PELAGE="$bin" PELAGE_ARGS="$sweep_args")
merge=$(after_job "$job" merge 500M \
  "$bin analyze --merge \$(ls $work/out/sweep/part_*.csv) --out $work/out/sweep.csv")
finish_job "$job" 600
finish_job "$merge" 120
cmp -s "$work/out/sweep.csv" "$work/out/sweep-reference.csv" ||
  fail "the merged sweep differs from one process's: $(diff "$work/out/sweep.csv" "$work/out/sweep-reference.csv" | head -5)"
echo "farm-test: 3. sweep.slurm array job $job (5 values of $sweep) + merge job $merge: sweep.csv" \
  "($(wc -l <"$work/out/sweep.csv") lines) byte-identical to one \`pelage analyze --sweep\`;" \
  "$(elapsed "$start") s from submission to completion"

status=0
echo "farm-test: passed"
