#!/usr/bin/env bash
# A sweep with unreachable footholds and an out-of-range value: those scenarios are rows
# with their status and message, the others are computed, and the sweep succeeds.
source "$(dirname "$0")/common.sh"
mpi 2 sweep "$SRC/tests/sweep/failing.yaml" -o failing.h5 2> failing.log || { cat failing.log; fail "sweep"; }
grep -q "2 with values out of range" failing.log || { cat failing.log; fail "no note of the invalid values"; }
"$PY" "$SRC/tests/sweep/check_failing.py" failing.h5
echo "failing scenario: ok"
