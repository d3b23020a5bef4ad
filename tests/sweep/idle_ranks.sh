#!/usr/bin/env bash
# Idle ranks do not spin: a one-scenario sweep on 3 ranks, where one process works and the
# others wait for it; each waiting process may use at most 10 % of a core over a 2 s window
# (one waiting in a blocking MPI call would use ~100 %). The scenario lasts 10 s on purpose
# (HEXDYN_TEST_HOLD_SECONDS), so the window falls within it on an idle machine as on a busy
# one. The measurement is bench/bench_sweep_scale.py --idle, which prints every process's
# share.
source "$(dirname "$0")/common.sh"
"$PY" "$SRC/bench/bench_sweep_scale.py" --hexdyn "$HEXDYN" --idle --max-idle 0.10 || fail "idle ranks: see the measurement above"
echo "idle ranks: ok"
