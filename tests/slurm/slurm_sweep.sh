#!/usr/bin/env bash
# pipelines/slurm_sweep.sbatch under a real Slurm (tests/slurm.cmake):
#   slurm_sweep.sh HEXDYN SOURCE_DIR WORK_DIR [PYTHON]
#
# Starts a private single-node Slurm on this machine from Debian's packages (slurmctld,
# slurmd, munge; installed with apt-get when missing), submits the sweep job on
# tests/slurm/small.yaml with 2 tasks, cancels it with scancel once the checkpoint holds
# finished work, resubmits it, and checks that the final file equals a plain run's
# (compare_sweeps.py; --keep-runs, so every scenario's full result is compared) and that
# the resubmitted job took scenarios from the checkpoint.
# The first job starts its ranks as the script chooses them (HEXDYN_LAUNCHER=auto:
# srun --mpi=pmix where Slurm offers PMIx), the resubmitted one with
# HEXDYN_LAUNCHER=mpirun, so that both launch paths run.
#
# Nothing under /etc or /run is written: slurm.conf (SLURM_CONF), the munge key and
# socket, state, spool, logs and pid files live in a temporary directory, the daemons
# (munged, slurmctld, slurmd, run as root in the foreground, not through systemd) listen
# on free ports, and everything is stopped and removed on exit.
#
# Exit 77 (ctest: skipped) with the reason when this machine cannot run it: not root,
# no apt-get or the packages cannot be installed, or the daemons do not come up.
set -euo pipefail
HEXDYN="$(realpath "$1")"
SRC="$(realpath "$2")"
WORK="$3"
PY="${4:-/usr/bin/python3}"
SWEEP="$SRC/tests/slurm/small.yaml"
SBATCH_SCRIPT="$SRC/pipelines/slurm_sweep.sbatch"

skip() {
  echo "SKIPPED: $*" >&2
  exit 77
}
fail() {
  echo "FAILED: $*" >&2
  exit 1
}

[ "$(id -u)" -eq 0 ] || skip "the Slurm test starts slurmctld, slurmd and munged as root; running as uid $(id -u)"

# --- Debian's Slurm and munge ---------------------------------------------------------
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null ||
   ! command -v sbatch >/dev/null || ! command -v munged >/dev/null; then
  command -v apt-get >/dev/null || skip "Slurm is not installed and there is no apt-get to install it"
  echo "slurm test: installing slurmctld slurmd slurm-client munge" >&2
  { apt-get update -qq &&
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
      slurmctld slurmd slurm-client munge; } >&2 ||
    skip "could not install Debian's slurmctld slurmd slurm-client munge with apt-get"
fi

rm -rf "$WORK"
mkdir -p "$WORK"
cd "$WORK"
WORK="$(pwd)"

# --- A private Slurm -------------------------------------------------------------------
# Short path under /tmp: the munge socket path must fit a sockaddr_un (108 bytes).
RT="$(mktemp -d /tmp/hexdyn-slurm.XXXXXX)"
chmod 755 "$RT"  # munged wants its socket directory traversable by all
mkdir -p "$RT/key" "$RT/state" "$RT/spool" "$RT/log"
chmod 700 "$RT/key"
export SLURM_CONF="$RT/slurm.conf"
pids=()

stop_all() {
  local status=$?
  set +e
  # Jobs first: slurmstepd outlives slurmd, so cancel and wait before stopping daemons.
  if [ -e "$RT/slurmctld.started" ]; then
    timeout 15 scancel --quiet --full -u root 2>/dev/null
    for _ in $(seq 100); do
      [ -z "$(timeout 5 squeue -h -o %i 2>/dev/null)" ] && break
      sleep 0.2
    done
  fi
  local p c
  # slurmstepd (reparented to init) inherits slurmd's SLURM_CONF: ours are those with it.
  for _ in $(seq 50); do
    local steps=""
    for c in /proc/[0-9]*/comm; do
      [ "$(cat "$c" 2>/dev/null)" = slurmstepd ] || continue
      p="${c%/comm}"
      { tr "\0" "\n" < "$p/environ"; } 2>/dev/null | grep -qx "SLURM_CONF=$SLURM_CONF" && steps="$steps ${p#/proc/}"
    done
    [ -z "$steps" ] && break
    sleep 0.2
  done
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do
    p=${pids[i]}
    kill "$p" 2>/dev/null
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$p" 2>/dev/null
    wait "$p" 2>/dev/null
  done
  if [ "$status" -ne 0 ] && [ "$status" -ne 77 ]; then
    for f in "$RT"/log/*.log "$WORK"/job-*.log; do
      [ -e "$f" ] && { echo "--- $f (last 30 lines)" >&2; tail -n 30 "$f" >&2; }
    done
  fi
  rm -rf "$RT"
  exit "$status"
}
trap stop_all EXIT
trap 'exit 130' INT TERM

# Two free TCP ports for slurmctld and slurmd (no clash with a system Slurm on 6817/6818).
read -r ctld_port slurmd_port < <("$PY" -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')

host="$(hostname -s)"
# The node line as slurmd detects it (NodeName=<host> CPUs=... RealMemory=...).
node_line="$(slurmd -C | head -n 1)"
[[ "$node_line" == NodeName=* ]] || skip "slurmd -C printed no node line: $node_line"
ncpus="$(sed -n 's/.* CPUs=\([0-9]*\).*/\1/p' <<< "$node_line")"
cat > "$SLURM_CONF" <<EOF
# Private single-node cluster of the hexdyn Slurm test (tests/slurm/slurm_sweep.sh).
ClusterName=hexdyntest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$RT/munge.socket
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$RT/state
SlurmdSpoolDir=$RT/spool
SlurmctldPidFile=$RT/slurmctld.pid
SlurmdPidFile=$RT/slurmd.pid
SlurmctldLogFile=$RT/log/slurmctld.log
SlurmdLogFile=$RT/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
SchedulerType=sched/backfill
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
SwitchType=switch/none
MinJobAge=600
$node_line NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF

dd if=/dev/urandom of="$RT/key/munge.key" bs=1 count=1024 status=none
chmod 400 "$RT/key/munge.key"
munged --foreground --socket="$RT/munge.socket" --key-file="$RT/key/munge.key" \
  --log-file="$RT/log/munged.log" --pid-file="$RT/munged.pid" --seed-file="$RT/munged.seed" \
  2> "$RT/log/munged.err" &
pids+=($!)
for _ in $(seq 50); do [ -S "$RT/munge.socket" ] && break; sleep 0.1; done
[ -S "$RT/munge.socket" ] || skip "munged did not start: $(tail -n 3 "$RT/log/munged.log" "$RT/log/munged.err" 2>/dev/null | tr '\n' ' ')"

slurmctld -D -i 2> "$RT/log/slurmctld.err" &
pids+=($!)
touch "$RT/slurmctld.started"
slurmd -D 2> "$RT/log/slurmd.err" &
pids+=($!)
t0=$SECONDS
state=""
while [ $((SECONDS - t0)) -lt 30 ]; do
  state="$(sinfo -h -N -o %t 2>/dev/null | head -n 1)"
  [ "$state" = idle ] && break
  sleep 0.3
done
if [ "$state" != idle ]; then
  tail -n 5 "$RT"/log/*.log "$RT"/log/*.err >&2 2>/dev/null || true
  skip "the private Slurm did not come up within 30 s (node state '${state:-none}'; daemon logs above)"
fi
echo "slurm test: Slurm $(sinfo -V | awk '{print $2}') up in $((SECONDS - t0)) s, node $host with $ncpus CPUs;" \
     "MPI plugins: $(srun --mpi=list 2>&1 | sed -n 's/^[[:space:]]\+//p' | tr '\n' ' ')" >&2

# --- The sweep: plain reference, then the job cancelled and resubmitted -----------------
t=$SECONDS
"$HEXDYN" sweep "$SWEEP" -o plain.h5 --keep-runs 2> plain.log || { cat plain.log >&2; fail "plain run"; }
echo "slurm test: plain run $((SECONDS - t)) s" >&2

export HEXDYN_BIN="$HEXDYN" HEXDYN_PLOT=0 HEXDYN_SWEEP_ARGS=--keep-runs
# Open MPI refuses root without these; mpirun runs 2 ranks on however many cores.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1

# job_state ID: PENDING, RUNNING, COMPLETED, CANCELLED, FAILED, ... (kept MinJobAge s).
job_state() {
  scontrol -o show job "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p'
}
# wait_state ID SECONDS STATE...: wait until the job is in one of STATE.
wait_state() {
  local id="$1" limit="$2" s
  shift 2
  local deadline=$((SECONDS + limit))
  while [ "$SECONDS" -lt "$deadline" ]; do
    s="$(job_state "$id")"
    for want in "$@"; do [ "$s" = "$want" ] && return 0; done
    sleep 0.2
  done
  fail "job $id is '${s:-gone}' after $limit s, expected one of: $*"
}
submit() {
  sbatch --parsable --ntasks=2 --time=10 --output="$WORK/job-%j.log" \
    "$SBATCH_SCRIPT" "$SWEEP" slurm.h5
}

# launcher_of ID: the launcher command the job's script chose (its log's first line).
launcher_of() {
  local line
  line="$(grep -m 1 "^slurm_sweep: job $1 " "job-$1.log")" || fail "job $1 log has no launcher line"
  line="${line#*): }"
  echo "${line%% "$HEXDYN" *}"
}

# Bytes of finished work in the checkpoint: its files but temporaries (hidden), the
# manifest and a lock. A scenario has finished once they grow after first appearing: a
# second per-scenario file (the format today), or a record after a per-rank journal's
# header.
data_bytes() {
  find slurm.h5.checkpoint -type f ! -name '.*' ! -name 'manifest*' ! -name 'lock*' \
    -printf '%s\n' 2>/dev/null | awk '{ s += $1 } END { print s + 0 }'
}
# wait_data_above ID BYTES: wait while the job runs until the data exceed BYTES.
wait_data_above() {
  local deadline=$((SECONDS + 90))
  while [ "$(data_bytes)" -le "$2" ]; do
    [ "$(job_state "$1")" = RUNNING ] || fail "job $1 is $(job_state "$1") before enough checkpoint progress"
    [ "$SECONDS" -lt "$deadline" ] || fail "no checkpoint progress of job $1 within 90 s"
    sleep 0.05
  done
}

t=$SECONDS
job1="$(HEXDYN_LAUNCHER=auto submit)"
wait_state "$job1" 60 RUNNING COMPLETED FAILED
wait_data_above "$job1" 0
wait_data_above "$job1" "$(data_bytes)"
sleep 0.5  # a record being appended is complete by then
scancel "$job1"
wait_state "$job1" 60 CANCELLED
# The job's processes are gone once the node has no job left.
for _ in $(seq 100); do [ -z "$(squeue -h -o %i)" ] && break; sleep 0.2; done
[ ! -e slurm.h5 ] || fail "the cancelled job wrote its output file"
echo "slurm test: job $job1 cancelled after $((SECONDS - t)) s with $(data_bytes) bytes of checkpoint" \
     "($(find slurm.h5.checkpoint -type f ! -name '.*' | wc -l) files)" >&2
launcher1="$(launcher_of "$job1")"

t=$SECONDS
job2="$(HEXDYN_LAUNCHER=mpirun submit)"
wait_state "$job2" 150 COMPLETED FAILED CANCELLED TIMEOUT NODE_FAIL OUT_OF_MEMORY
[ "$(job_state "$job2")" = COMPLETED ] || fail "resubmitted job $job2 ended $(job_state "$job2")"
echo "slurm test: resubmitted job $job2 completed in $((SECONDS - t)) s" >&2
launcher2="$(launcher_of "$job2")"

# Both jobs ran one sweep on 2 ranks (not 2 single-rank sweeps, as a PMI mismatch gives).
for j in "$job1" "$job2"; do
  grep -q "on 2 ranks" "job-$j.log" || fail "job $j did not run on 2 ranks: $(grep -m 2 'hexdyn: sweep' "job-$j.log")"
done
"$PY" "$SRC/tests/sweep/compare_sweeps.py" plain.h5 slurm.h5
"$PY" - slurm.h5 <<'PY'
import sys
import h5py
with h5py.File(sys.argv[1], "r") as f:
    n = int(f["meta"].attrs["scenarios"])
    resumed = int(f["meta"].attrs["resumed_scenarios"])
assert resumed > 0, "the resubmitted job took no scenario from the checkpoint"
assert resumed < n, f"all {n} scenarios were finished before scancel"
print(f"slurm test: resubmitted job took {resumed} scenario(s) from the checkpoint", file=sys.stderr)
PY
[ ! -e slurm.h5.checkpoint ] || fail "checkpoint left behind after the resubmitted job completed"
echo "slurm sweep: ok (first job: ${launcher1:-?}; resubmitted: ${launcher2:-?})"
