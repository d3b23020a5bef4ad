#!/usr/bin/env bash
# A scenario that kills its process (the test-only switch HEXDYN_TEST_CRASH_SCENARIO=k
# makes the process computing scenario k abort): it is tried twice, recorded with status
# `crashed`, and the sweep completes with every other scenario as an uninterrupted run
# has them — live on 2 ranks, and across --resume (a run killed after the crash was
# recorded; the resumed run, without the switch, does not compute it again).
source "$(dirname "$0")/common.sh"
sweep="$SRC/configs/sweeps/smoke.yaml"
mpi 2 sweep "$sweep" -o ref.h5 2> ref.log || { cat ref.log; fail "reference run"; }

check_crashed() {  # check_crashed FILE K REF: scenario K crashed, all others as in REF
  "$PY" - "$1" "$3" "$2" <<'PY'
import sys
import h5py
import numpy as np
k = int(sys.argv[3])
with h5py.File(sys.argv[1], "r") as f, h5py.File(sys.argv[2], "r") as r:
    status = f["scenarios/status"][()]
    codes = f["scenarios/status"].attrs["codes"]
    codes = codes.decode() if isinstance(codes, bytes) else codes
    assert "7 crashed" in codes, codes
    assert status[k] == 7, status
    message = f["scenarios/message"][k]
    message = message.decode() if isinstance(message, bytes) else message
    assert "crashed twice" in message and "signal 6" in message, message
    assert np.isnan(f["scenarios/energy"][k])
    others = [i for i in range(len(status)) if i != k]
    assert (status[others] == r["scenarios/status"][()][others]).all()
    assert np.array_equal(f["scenarios/energy"][()][others], r["scenarios/energy"][()][others])
PY
}

# Live: the crash is retried once, then recorded; the sweep completes.
HEXDYN_TEST_CRASH_SCENARIO=3 mpi 2 sweep "$sweep" -o live.h5 -v 2> live.log || { cat live.log; fail "live sweep with a crash"; }
[ "$(grep -c 'scenario 000003: its process was killed by signal 6' live.log)" -eq 1 ] || { cat live.log; fail "first crash not reported once"; }
grep -q "scenario 000003 crashed" live.log || { cat live.log; fail "no crashed row"; }
grep -q "(1 crashed)" live.log || { cat live.log; fail "summary line"; }
check_crashed live.h5 3 ref.h5 || fail "live file"

# Across --resume (a longer sweep, so that it can be killed part-way): kill the run once
# the crash is in the checkpoint, resume without the switch.
sweep="$SRC/tests/sweep/resume.yaml"
HEXDYN_TEST_CRASH_SCENARIO=1 mpi 2 sweep "$sweep" -o ref2.h5 2> ref2.log || { cat ref2.log; fail "second reference run"; }
HEXDYN_TEST_CRASH_SCENARIO=1 "$MPIEXEC" --oversubscribe -np 2 "$HEXDYN" sweep "$sweep" -o cut.h5 2> cut.log &
launcher=$!
deadline=$((SECONDS + 60))
while :; do
  "$PY" "$SRC/tests/sweep/journal_rows.py" cut.h5.checkpoint 2>/dev/null | grep -qx 000001 && break
  kill -0 "$launcher" 2>/dev/null || break  # finished before the kill: fine, resume finds all
  [ "$SECONDS" -lt "$deadline" ] || fail "no crashed record after 60 s"
  sleep 0.05
done
kill_launcher_and_ranks "$launcher"
if [ -e cut.h5 ]; then
  echo "note: the sweep completed before the kill; checking its file"
else
  mpi 2 sweep "$sweep" -o cut.h5 --resume -v 2> resume.log || { cat resume.log; fail "resume"; }
  if grep -q "scenario 000001 .*(rank" resume.log; then cat resume.log; fail "the crashed scenario was computed again on --resume"; fi
fi
check_crashed cut.h5 1 ref2.h5 || fail "resumed file"
echo "crash contained: ok"
