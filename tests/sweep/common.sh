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
