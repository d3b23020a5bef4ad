#!/bin/bash
# Signals under mpirun: SIGTERM to mpirun while a 2-rank sweep computes. Rank 0
# keeps the checkpoint and says so in one line, no process is left, and a resume gives the
# file of an uninterrupted 1-rank sweep. Then SIGTERM to the worker rank alone: it tells
# rank 0, which says the same line (mpirun kills every rank left once one exits, so a
# worker that ended first would cut rank 0 off before its line).
# The smoke sweep, whose scenarios wait 1.5 s each on purpose while the signals are sent
# (HEXDYN_TEST_HOLD_SECONDS), so the job is mid-sweep on an idle machine as on a busy one.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"

"$HEXDYN" sweep "$SMOKE" -o s.h5 --keep-runs > s.log 2>&1 || fail "1-rank sweep: $(cat s.log)"
HEXDYN_TEST_HOLD_SECONDS=1.5 "$MPIEXEC" --oversubscribe -np 2 "$HEXDYN" sweep "$SMOKE" -o m.h5 \
  --keep-runs > m1.log 2>&1 &
pid=$!  # mpirun itself
wait_for 'm.h5.checkpoint/journal-*' 60 || fail "the 2-rank sweep wrote no journal: $(cat m1.log)"
sleep 0.3
kill -TERM "$pid"
wait "$pid"
rc=$?
[ "$rc" != 0 ] || fail "mpirun: exit status 0 after SIGTERM"
one_line m1.log "^hexdyn: sweep interrupted by SIGTERM: [0-9]+ finished scenarios kept in the checkpoint m.h5.checkpoint"
no_temporaries .
sleep 0.5
[ -z "$(work_processes)" ] || fail "processes left after mpirun's SIGTERM: $(work_processes)"
mpi 2 sweep "$SMOKE" -o m.h5 --keep-runs --resume > m2.log 2>&1 || fail "mpirun resume: $(cat m2.log)"
compare s.h5 m.h5 || fail "the resumed sweeps differ"
no_temporaries .

HEXDYN_TEST_HOLD_SECONDS=1.5 "$MPIEXEC" --oversubscribe -np 2 "$HEXDYN" sweep "$SMOKE" -o w.h5 \
  --keep-runs > w.log 2>&1 &
pid=$!
wait_for 'w.h5.checkpoint/journal-*' 60 || fail "the 2-rank sweep wrote no journal: $(cat w.log)"
worker=""
for p in $(cat "/proc/$pid/task/$pid/children"); do  # mpirun's children: the two ranks
  if grep -qaxF 'OMPI_COMM_WORLD_RANK=1' < <(tr '\0' '\n' < "/proc/$p/environ"); then worker=$p; fi
done
[ -n "$worker" ] || fail "no rank 1 among mpirun's children: $(cat w.log)"
kill -TERM "$worker"
wait "$pid"
rc=$?
[ "$rc" != 0 ] || fail "mpirun: exit status 0 after SIGTERM to rank 1"
one_line w.log "^hexdyn: sweep interrupted by SIGTERM: [0-9]+ finished scenarios kept in the checkpoint w.h5.checkpoint"
compgen -G 'w.h5.checkpoint/journal-*' > /dev/null || fail "the checkpoint of w.h5 was not kept"
[ ! -e w.h5 ] || fail "w.h5 written after SIGTERM to rank 1"
sleep 0.5
[ -z "$(work_processes)" ] || fail "processes left after SIGTERM to rank 1: $(work_processes)"
echo "signals_mpirun: one line, checkpoint kept, no process left, the resume completes; the same after SIGTERM to rank 1 alone"
