#!/usr/bin/env bash
# motion.travel: a duty factor x speed sweep whose travel is two treads
# (tests/sweep/travel.yaml). Every scenario's trunk, read from its kept run's /base/position,
# moves by the same vector, two treads across and two risers up (the stairs' geometry, not
# the program's distance); the cycles follow from the travel, the fewest whose strides of the
# given stroke cover it. travel beside motion.cycles is one line, exit 2, nothing written.
source "$(dirname "$0")/common.sh"
mpi 2 sweep "$SRC/tests/sweep/travel.yaml" -o travel.h5 --keep-runs 2> travel.log ||
  { cat travel.log; fail "sweep"; }
"$PY" - travel.h5 <<'PY'
import math, sys
import numpy as np
from hexdyn import results as hr
sw = hr.open_sweep(sys.argv[1])
assert sw.status_names == ["ok"] * 8, list(zip(sw.status_names, sw.table["message"]))
terrain = sw.config["terrain"]
b, h = terrain["tread_depth"], terrain["riser_height"]
stroke = sw.config["gait"]["stroke"]
want = np.array([0.0, 2 * b, 2 * h])  # two treads across, two risers up
for i in range(sw.size):
    run = sw.run(i)
    p = np.asarray(run["/base/position"])
    moved = p[-1] - p[0]
    duty = sw.scenario(i)["gait.duty_factor"]
    assert np.allclose(moved, want, rtol=0, atol=1e-9), (i, moved, want)
    assert abs(sw.table["distance"][i] - math.hypot(2 * b, 2 * h)) < 1e-9, i
    # The cycles: the fewest whose strides s0/beta (across) cover the two treads.
    cycles = len(np.asarray(run["/gait/cycle_start"]))
    assert cycles == math.ceil(2 * b / (stroke / duty) - 1e-9), (i, duty, cycles)
print("travel: every scenario covers", want)
PY

set +e
"$HEXDYN" run "$SRC/configs/sweeps/stairs_base.yaml" --set motion.travel.treads=2 -o conflict.h5 \
  2> conflict.log
status=$?
set -e
[ "$status" = 2 ] || { cat conflict.log; fail "travel with cycles: exit $status"; }
[ "$(wc -l < conflict.log)" = 1 ] || { cat conflict.log; fail "travel with cycles: not one line"; }
grep -q "motion.travel: got {treads: 2} and motion.cycles 3, expected one of them" conflict.log ||
  { cat conflict.log; fail "travel with cycles: message"; }
[ ! -e conflict.h5 ] || fail "travel with cycles: output written"
echo "travel: ok"
