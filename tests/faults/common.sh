# shellcheck shell=bash
# Shared set-up of the fault-injection tests (tests/faults.cmake), sourced by each script:
#   SCRIPT HEXDYN SOURCE_DIR WORK_DIR MPIEXEC PYTHON
# On top of tests/sweep/common.sh (strict mode, a fresh WORK, mpi, fail, compare): checks
# of the one-line outcome every fault must have (docs/user/faults.md).
# shellcheck source=../sweep/common.sh
source "$(dirname "${BASH_SOURCE[0]}")/../sweep/common.sh"
set +e  # each step's exit status is checked by hand
SMOKE="$SRC/configs/sweeps/smoke.yaml"
SLOW="$SRC/tests/faults/slow.yaml"
PAPER="$SRC/configs/paper.yaml"

# Exit status 77 is ctest's SKIP_RETURN_CODE (tests/faults.cmake).
need_root() {
  if [ "$(id -u)" != 0 ]; then
    echo "SKIPPED: this test needs root ($*); run ctest as root to include it"
    exit 77
  fi
}

# expect_status WHAT GOT WANT
expect_status() {
  [ "$2" = "$3" ] || fail "$1: exit status $2, expected $3 (log: $(tr '\n' '|' < "${4:-/dev/null}"))"
}

# one_line LOG PATTERN: exactly one line of hexdyn's (error or interruption) in LOG, and it
# matches the extended regex PATTERN.
one_line() {
  local n
  n=$(grep -cE '^hexdyn: (error|internal error|run interrupted|envelope interrupted|sweep interrupted|write interrupted)' "$1")
  [ "$n" = 1 ] || fail "$1: $n lines of hexdyn's error or interruption, expected 1: $(tr '\n' '|' < "$1")"
  grep -qE "$2" "$1" || fail "$1: no line matches '$2': $(tr '\n' '|' < "$1")"
  if grep -q 'HDF5-DIAG\|Segmentation\|slist' "$1"; then fail "$1: HDF5 or crash output"; fi
}

# refused WHAT PATTERN ARGS...: `hexdyn ARGS` (under `ulimit -v $LIMIT_KB` when the script sets
# it, and `timeout 60` as a guard against a hang: a refusal comes before any work) exits with
# status 2 and exactly one line of hexdyn's error matching PATTERN. Nothing is left behind: no
# o.h5, no temporary file here, nothing in out/ (when the script has that folder), and every
# input is byte for byte as before: inputs_digest against $before when the script defines it,
# else the files listed in inputs.sha256, if any.
refused() {
  local what=$1 pattern=$2 log rc
  shift 2
  log="refused_${what//[^A-Za-z0-9_.-]/_}.log"
  (ulimit -v "${LIMIT_KB:-unlimited}" && exec timeout 60 "$HEXDYN" "$@") > "$log" 2>&1
  rc=$?
  [ "$rc" != 124 ] || fail "$what: no answer within 60 s"
  expect_status "$what" "$rc" 2 "$log"
  one_line "$log" "$pattern"
  [ ! -e o.h5 ] || fail "$what: an output was written"
  no_temporaries .
  if [ -d out ]; then
    [ -z "$(ls -A out)" ] || fail "$what: files left in out/: $(ls -A out)"
    no_temporaries out
  fi
  if declare -F inputs_digest > /dev/null; then
    [ "$(inputs_digest)" = "$before" ] || fail "$what: an input changed"
  elif [ -f inputs.sha256 ]; then
    sha256sum --quiet -c inputs.sha256 || fail "$what: an input changed"
  fi
}

# no_temporaries DIR: no .NAME.tmp.PID file is left in DIR.
no_temporaries() {
  local left
  left=$(find "$1" -maxdepth 1 -name '.*.tmp.*' | tr '\n' ' ')
  [ -z "$left" ] || fail "temporary files left in $1: $left"
}

# wait_for GLOB SECONDS: waits until a file matches GLOB (true) or the time is up (false).
wait_for() {
  local i
  for ((i = 0; i < $2 * 20; i++)); do
    # shellcheck disable=SC2086
    if compgen -G "$1" > /dev/null; then return 0; fi
    sleep 0.05
  done
  return 1
}

# work_processes: pids of the live processes whose command line names this test's WORK
# folder (mpirun, its ranks and their scenario children; zombies excluded).
work_processes() {
  local d state
  for d in /proc/[0-9]*; do
    [ "${d#/proc/}" = "$$" ] && continue
    grep -qaF -- "$WORK/" "$d/cmdline" 2> /dev/null || continue
    state=$(sed 's/^.*) //' "$d/stat" 2> /dev/null | cut -d' ' -f1)
    [ "$state" = Z ] || [ -z "$state" ] || basename "$d"
  done
}

# dead_pid: the pid of a process that has exited.
dead_pid() {
  local p
  p=$(sh -c 'echo $$')
  while kill -0 "$p" 2> /dev/null; do p=$(sh -c 'echo $$'); done
  echo "$p"
}
