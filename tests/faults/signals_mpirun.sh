#!/bin/bash
# B5-B7 (issue 22) under mpirun: SIGTERM to mpirun while a 2-rank sweep computes. Rank 0
# keeps the checkpoint and says so in one line, no process is left, and a resume gives the
# file of an uninterrupted 1-rank sweep.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"

"$HEXDYN" sweep "$SLOW" -o s.h5 --keep-runs > s.log 2>&1 || fail "1-rank sweep: $(cat s.log)"
"$MPIEXEC" --oversubscribe -np 2 "$HEXDYN" sweep "$SLOW" -o m.h5 --keep-runs > m1.log 2>&1 &
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
mpi 2 sweep "$SLOW" -o m.h5 --keep-runs --resume > m2.log 2>&1 || fail "mpirun resume: $(cat m2.log)"
compare s.h5 m.h5 || fail "the resumed sweeps differ"
no_temporaries .
echo "signals_mpirun: one line, checkpoint kept, no process left, the resume completes"
