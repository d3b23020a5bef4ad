#!/usr/bin/env bash
# The output grid's error control against a second computation: the 32 scenarios of the
# stair check grid (riser 0.02, 0.08 m x peak speed 0.05 ... 0.20 m/s x duty factor 1/2, 2/3,
# 3/4, 5/6, three treads of travel) at output.tolerance 1e-4, each against the same scenario
# on a converged grid (0.5 ms steps, 0.1 ms next to events, 400 intervals per transient,
# refined to 1e-6): every energy within 1e-4 and every peak torque within 1e-3, and the
# statuses alike (bench/grid_accuracy.py --check, docs/validation/grid-accuracy.md).
source "$(dirname "$0")/common.sh"
"$PY" "$SRC/bench/grid_accuracy.py" --grid check --tolerances 1e-4 --hexdyn "$HEXDYN" \
  --out "$WORK" --check > summary.txt 2> grid_accuracy.log || {
  cat summary.txt grid_accuracy.log
  fail "grid accuracy"
}
cat summary.txt
