#!/bin/bash
# Signals: SIGTERM and SIGINT (Slurm's time limit and scancel, Ctrl-C) to `hexdyn
# run` with a big output, to `hexdyn envelope`, to a sweep while it computes and during its
# final write (1 rank) (mpirun's sweep: signals_mpirun.sh): exit status 128 + signal, one line
# saying what was kept and how to resume, no temporary file left, and a --resume that ends
# with the file of an uninterrupted sweep and nothing left behind.
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"

# signal_run SIG STATUS WAIT_FOR: hexdyn run with a 217 MB output, signalled once WAIT_FOR
# (a file glob, or a number of seconds) is there (no required friction: the signals are the
# point, and its 139031 samples would add a second to each run).
signal_run() {
  local log="run_$1.log" pid rc
  "$HEXDYN" run "$PAPER" -o big.h5 --set output.impact_samples=8000 \
    --set output.required_friction=false 2> "$log.all" &
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
# Every other signal whose default action ends a process: the same clean end.
signal_run HUP 129 '.big.h5.tmp.*'
signal_run QUIT 131 1.5
signal_run USR1 138 '.big.h5.tmp.*'
signal_run USR2 140 1.5
signal_run ALRM 142 '.big.h5.tmp.*'
signal_run PIPE 141 1.5

# Python's Result.write: a signal whose default would end Python ends it cleanly too.
export PYTHONPATH="${PYTHONPATH:-$(dirname "$HEXDYN")/python}"
"$PY" -c '
import hexdyn, sys
r = hexdyn.run(sys.argv[1], {"output.impact_samples": 8000, "output.required_friction": False})
print("computed", flush=True)
r.write("py.h5")
' "$PAPER" > py.log 2>&1 &
pid=$!
wait_for '.py.h5.tmp.*' 60 || fail "Python: the write never started: $(cat py.log)"
kill -HUP "$pid"
wait "$pid"
expect_status "Python write SIGHUP" $? 129 py.log
one_line py.log "^hexdyn: write interrupted by SIGHUP: nothing written to py.h5"
[ ! -e py.h5 ] || fail "Python write SIGHUP: a file was published"
no_temporaries .

# Ctrl-C in hexdyn.run: KeyboardInterrupt long before the scene would end, for each back end.
for solver in active-set ipopt; do
  rm -f ctrlc.ready
  "$PY" -c '
import hexdyn, signal, sys, time
signal.signal(signal.SIGINT, signal.default_int_handler)  # a background job starts ignoring it
open("ctrlc.ready", "w").close()  # the handler is in place: Ctrl-C now interrupts
t = time.monotonic()
try:
    hexdyn.run(sys.argv[1], {"output.impact_samples": 8000, "allocation.solver": sys.argv[2]})
except KeyboardInterrupt:
    print("KeyboardInterrupt", flush=True)
    sys.exit(42)
print("finished after", time.monotonic() - t, "s")
' "$PAPER" "$solver" > ctrlc.log 2>&1 &
  pid=$!
  # Not a fixed delay: on a busy machine the import alone may take longer, and a Ctrl-C
  # before the handler is in place is ignored (a background job starts ignoring SIGINT).
  wait_for ctrlc.ready 120 || fail "Ctrl-C in hexdyn.run ($solver): the script never started: $(cat ctrlc.log)"
  sleep 0.5  # the scene computes for about 5 s (active set) or 15 s (Ipopt)
  kill -INT "$pid"
  wait "$pid"
  # 42: KeyboardInterrupt before the scene ended (how soon: bench/interrupt_latency.py).
  expect_status "Ctrl-C in hexdyn.run ($solver)" $? 42 ctrlc.log
done

# signal_envelope SIG STATUS: the envelope signalled while it computes.
signal_envelope() {
  "$HEXDYN" envelope "$SRC/tests/faults/slow_envelope.yaml" -o e.h5 > env.log 2>&1 &
  local pid=$!
  sleep 0.8  # slow_envelope.yaml computes for about 20 s
  kill -"$1" "$pid"
  wait "$pid"
  expect_status "envelope $1" $? "$2" env.log
  one_line env.log "^hexdyn: envelope interrupted by SIG$1: nothing written to e.h5"
  [ ! -e e.h5 ] || fail "envelope $1: a file was written"
  no_temporaries .
}
signal_envelope TERM 143
signal_envelope USR2 140

# A sweep on 1 rank: SIGTERM while it computes, SIGINT during its final write, then a
# resume that completes.
resume_line="continue with: hexdyn sweep $SLOW -o s.h5 --keep-runs --resume$"
# signal_sweep SIG STATUS ARGS...: the sweep signalled once its own first journal exists (its
# first scenarios are done): its line, the checkpoint kept, no output.
signal_sweep() {
  local sig=$1 status=$2
  shift 2
  local before i
  before=$(compgen -G 's.h5.checkpoint/journal-*' | wc -l)
  "$HEXDYN" sweep "$SLOW" -o s.h5 --keep-runs "$@" > s1.log 2>&1 &
  local pid=$!
  for ((i = 0; i < 1200; i++)); do  # a journal of its own (a resume finds the earlier ones)
    [ "$(compgen -G 's.h5.checkpoint/journal-*' | wc -l)" -gt "$before" ] && break
    sleep 0.05
  done
  [ "$i" -lt 1200 ] || fail "the sweep wrote no journal: $(cat s1.log)"
  kill -"$sig" "$pid"
  wait "$pid"
  expect_status "sweep SIG$sig" $? "$status" s1.log
  one_line s1.log "^hexdyn: sweep interrupted by SIG$sig: [0-9]+ finished scenarios kept in the checkpoint s.h5.checkpoint.*$resume_line"
  [ -d s.h5.checkpoint ] && [ ! -e s.h5 ] || fail "sweep SIG$sig: checkpoint not kept, or an output written"
  no_temporaries .
}
signal_sweep TERM 143
signal_sweep HUP 129 --resume  # a closed terminal

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
