#!/bin/bash
# Orphans: kill -9 of a sweep's whole job (mpirun and its ranks), and of
# mpirun's process group alone (Open MPI gives each rank a group of its own): within
# 0.5 s no hexdyn process is left (ranks die with their launcher, scenario children with
# their rank, PR_SET_PDEATHSIG), and an immediate --resume (on 2 ranks) is admitted and
# completes.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"

# kill_job WHAT: starts the 2-rank smoke sweep in its own session, each scenario waiting 1 s
# on purpose (HEXDYN_TEST_HOLD_SECONDS, so the job is mid-sweep on an idle machine as on a busy
# one), and kills WHAT once the first journal exists.
kill_job() {
  local out="$WORK/$1.h5" mpirun_pid="" ranks="" p parent pgid left
  HEXDYN_TEST_HOLD_SECONDS=1.0 setsid "$MPIEXEC" --oversubscribe -np 2 "$HEXDYN" sweep "$SMOKE" \
    -o "$out" --keep-runs > "$1.log" 2>&1 &
  wait_for "$out.checkpoint/journal-*" 30 || fail "$1: no journal: $(cat "$1.log")"
  # The ranks: hexdyn-sweep processes whose parent is not one (those are scenario children).
  for p in $(work_processes); do
    [ "$(cat "/proc/$p/comm" 2> /dev/null)" = hexdyn-sweep ] || continue
    read -r _ parent _ <<< "$(sed 's/^.*) //' "/proc/$p/stat")"
    [ "$(cat "/proc/$parent/comm" 2> /dev/null)" = hexdyn-sweep ] && continue
    ranks="$ranks $p"
    mpirun_pid="$parent"
  done
  [ -n "$ranks" ] && [ -n "$mpirun_pid" ] || fail "$1: no rank found: $(work_processes | tr '\n' ' ')"
  if [ "$1" = whole_job ]; then
    # shellcheck disable=SC2086
    kill -9 "$mpirun_pid" $ranks
  else
    read -r _ _ pgid _ <<< "$(sed 's/^.*) //' "/proc/$mpirun_pid/stat")"
    kill -9 -- "-$pgid"  # mpirun's process group, which holds none of the ranks
  fi
  sleep 0.5
  left=$(work_processes | tr '\n' ' ')
  [ -z "$left" ] || fail "$1: processes left 0.5 s after kill -9: $left ($(ps -o pid,ppid,pgid,args -p "${left// /,}" 2> /dev/null))"
  mpi 2 sweep "$SMOKE" -o "$out" --keep-runs --resume > "$1.resume.log" 2>&1 ||
    fail "$1: the immediate resume failed: $(cat "$1.resume.log")"
}
kill_job whole_job
kill_job mpirun_group
wait 2> /dev/null
compare whole_job.h5 mpirun_group.h5 || fail "the resumed sweeps differ"
echo "orphans: no process left within 0.5 s, immediate resumes complete"
