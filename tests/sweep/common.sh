# shellcheck shell=bash
# Shared set-up of the sweep tests (tests/sweep.cmake), sourced by each script:
#   SCRIPT HEXDYN SOURCE_DIR WORK_DIR MPIEXEC PYTHON
# Runs as root under Open MPI: the two OMPI_ALLOW_* variables permit it, and
# --oversubscribe allows more ranks than cores (4 ranks on a 2-core machine).
set -euo pipefail
HEXDYN="$1"
SRC="$2"
WORK="$3"
MPIEXEC="${4:-mpirun}"
PY="${5:-/usr/bin/python3}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
rm -rf "$WORK"
mkdir -p "$WORK"
cd "$WORK"

# mpi N ARGS...: hexdyn ARGS under N ranks.
mpi() {
  local n="$1"
  shift
  "$MPIEXEC" --oversubscribe -np "$n" "$HEXDYN" "$@"
}

fail() {
  echo "FAILED: $*" >&2
  exit 1
}

compare() {
  "$PY" "$SRC/tests/sweep/compare_sweeps.py" "$@"
}

# children_of PID: the process ids whose parent is PID (from /proc; no procps needed).
children_of() {
  local parent="$1" stat fields ppid
  for stat in /proc/[0-9]*/stat; do
    fields=$(sed 's/^.*) //' "$stat" 2>/dev/null) || continue
    read -r _ ppid _ <<< "$fields"  # after the command name: state, ppid, ...
    if [ "$ppid" = "$parent" ]; then basename "$(dirname "$stat")"; fi
  done
}

# kill_after_rows LAUNCHER CHECKPOINT N LOG: waits until CHECKPOINT's journals hold at least N
# records (tests/sweep/journal_rows.py), then kill -9 the launcher and waits for its ranks to
# go (they lose their launcher and exit; any left are killed). Fails if the sweep ends first
# (printing LOG) or nothing is checkpointed within 120 s.
kill_after_rows() {
  local launcher=$1 cp=$2 want=$3 log=$4 n deadline=$((SECONDS + 120))
  while :; do
    n=$("$PY" "$SRC/tests/sweep/journal_rows.py" "$cp" 2>/dev/null | wc -l || true)
    [ "$n" -ge "$want" ] && break
    kill -0 "$launcher" 2>/dev/null || { cat "$log"; fail "the sweep ended before it could be killed"; }
    [ "$SECONDS" -lt "$deadline" ] || fail "no checkpoint records after 120 s"
    sleep 0.1
  done
  kill_launcher_and_ranks "$launcher"
}

# kill_launcher_and_ranks LAUNCHER: kill -9 the launcher, then waits up to 10 s for its ranks
# to go (they lose their launcher and exit); any left are killed.
kill_launcher_and_ranks() {
  local launcher=$1 ranks alive p
  ranks=$(children_of "$launcher")
  kill -9 "$launcher" 2>/dev/null || true
  wait "$launcher" 2>/dev/null || true
  for _ in $(seq 100); do
    alive=""
    for p in $ranks; do kill -0 "$p" 2>/dev/null && alive="$alive $p"; done
    [ -z "$alive" ] && break
    sleep 0.1
  done
  for p in $alive; do kill -9 "$p" 2>/dev/null || true; done
}
