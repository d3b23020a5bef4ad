#!/bin/bash
# B5-B7 (issue 22): SIGTERM and SIGINT (Slurm's time limit and scancel, Ctrl-C) to `hexdyn
# run` with a big output, to `hexdyn envelope`, to a sweep while it computes and during its
# final write (1 rank) (mpirun's sweep: signals_mpirun.sh): exit status 128 + signal, one line
# saying what was kept and how to resume, no temporary file left, and a --resume that ends
# with the file of an uninterrupted sweep and nothing left behind.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"

# signal_run SIG STATUS WAIT_FOR: hexdyn run with a 217 MB output, signalled once WAIT_FOR
# (a file glob, or a number of seconds) is there.
signal_run() {
  local log="run_$1.log" pid rc
  "$HEXDYN" run "$PAPER" -o big.h5 --set output.impact_samples=8000 2> "$log.all" &
  pid=$!
  if [[ "$3" =~ ^[0-9.]+$ ]]; then sleep "$3"; else wait_for "$3" 60 || fail "run: no $3"; fi
  kill -"$1" "$pid"
  wait "$pid"
  rc=$?
  grep -v relaxed "$log.all" > "$log"
  expect_status "run $1" "$rc" "$2" "$log"
  one_line "$log" "^hexdyn: run interrupted by SIG$1: nothing written to big.h5 .*no temporary file left"
  [ "$(cat big.h5)" = good ] || fail "run $1: the existing file was not kept"
  no_temporaries .
}
echo good > big.h5
signal_run TERM 143 1.5          # while it computes
signal_run INT 130 '.big.h5.tmp.*'  # while it writes

# envelope
"$HEXDYN" envelope "$SRC/tests/faults/slow_envelope.yaml" -o e.h5 > env.log 2>&1 &
pid=$!
sleep 0.8  # slow_envelope.yaml computes for about 20 s
kill -TERM "$pid"
wait "$pid"
expect_status envelope $? 143 env.log
one_line env.log "^hexdyn: envelope interrupted by SIGTERM: nothing written to e.h5"
[ ! -e e.h5 ] || fail "envelope: a file was written"
no_temporaries .

# A sweep on 1 rank: SIGTERM while it computes, SIGINT during its final write, then a
# resume that completes.
resume_line="continue with: hexdyn sweep $SLOW -o s.h5 --keep-runs --resume$"
"$HEXDYN" sweep "$SLOW" -o s.h5 --keep-runs > s1.log 2>&1 &
pid=$!
# While it computes: its first journal exists (the first scenarios are done).
wait_for 's.h5.checkpoint/journal-*' 60 || fail "the sweep wrote no journal: $(cat s1.log)"
kill -TERM "$pid"
wait "$pid"
expect_status "sweep SIGTERM" $? 143 s1.log
one_line s1.log "^hexdyn: sweep interrupted by SIGTERM: [0-9]+ finished scenarios kept in the checkpoint s.h5.checkpoint.*$resume_line"
[ -d s.h5.checkpoint ] && [ ! -e s.h5 ] || fail "sweep SIGTERM: checkpoint not kept, or an output written"
no_temporaries .

"$HEXDYN" sweep "$SLOW" -o s.h5 --keep-runs --resume > s2.log 2>&1 &
pid=$!
wait_for '.s.h5.tmp.*' 120 || fail "the sweep's final write never started: $(cat s2.log)"
kill -INT "$pid"
wait "$pid"
rc=$?
if grep -q '^hexdyn: sweep: wrote' s2.log; then
  echo "note: the final write ended before SIGINT; the late signal is checked instead"
  expect_status "sweep late SIGINT" "$rc" 130 s2.log
  grep -q "arrived after s.h5 was complete" s2.log || fail "no line about the late signal"
else
  expect_status "sweep SIGINT in the final write" "$rc" 130 s2.log
  one_line s2.log "^hexdyn: sweep interrupted by SIGINT: 252 finished scenarios kept.*$resume_line"
  [ ! -e s.h5 ] || fail "sweep SIGINT: an output was published"
  no_temporaries .
  "$HEXDYN" sweep "$SLOW" -o s.h5 --keep-runs --resume > s3.log 2>&1 || fail "resume: $(cat s3.log)"
fi
no_temporaries .
[ ! -e s.h5.checkpoint ] || fail "checkpoint left after the resume"

echo "signals: exit 128+signal, one line, temporaries removed, resumes complete"
