#!/usr/bin/env bash
# A sweep of robustness studies (docs/user/robustness.md#in-a-sweep): each row has its study's
# replays, success fraction, Wilson interval and failure counts, equal to the study that
# `hexdyn robustness` makes of the same scenario's scene; the file is the same on 1 and 2
# ranks; killed part-way and resumed, it is the same file as an uninterrupted run's (timing
# fields excepted).
source "$(dirname "$0")/common.sh"
sweep="$SRC/tests/sweep/robustness.yaml"
mpi 1 sweep "$sweep" -o one.h5 2> one.log || { cat one.log; fail "1-rank robustness sweep"; }
mpi 2 sweep "$sweep" -o two.h5 2> two.log || { cat two.log; fail "2-rank robustness sweep"; }
compare one.h5 two.h5

# The interrupted run: killed once 2 scenarios are checkpointed, then resumed.
"$MPIEXEC" --oversubscribe -np 2 "$HEXDYN" sweep "$sweep" -o cut.h5 -v 2> cut.log &
launcher=$!
kill_after_rows "$launcher" cut.h5.checkpoint 2 cut.log
[ ! -e cut.h5 ] || fail "the killed sweep wrote its output file"
mpi 2 sweep "$sweep" -o cut.h5 --resume 2> resume.log || { cat resume.log; fail "resume"; }
compare one.h5 cut.h5
echo "robustness sweep: 1 rank = 2 ranks = killed and resumed"

# Scenario 4 (duty factor 2/3, riser sigma 0.0005) against the study of its scene alone.
"$HEXDYN" robustness "$SRC/configs/robustness/paper.yaml" -o alone.h5 -j 1 \
  --set robustness.replays=4 --set gait.duty_factor=2/3 \
  --set robustness.perturbations.riser_height.sigma=0.0005 2> alone.log ||
  { cat alone.log; fail "hexdyn robustness of scenario 4's scene"; }
"$PY" - one.h5 alone.h5 <<'PY'
import sys
import h5py
import numpy as np
with h5py.File(sys.argv[1], "r") as sw, h5py.File(sys.argv[2], "r") as rob:
    s = sw["scenarios"]
    i = 4
    assert s["status"][i] == 0, s["message"][i]
    reached = rob["replays/reached_top"][()]
    failure = rob["replays/failure"][()]
    assert s["replays"][i] == len(reached) == 4, (s["replays"][i], len(reached))
    assert s["p_success"][i] == reached.mean(), (s["p_success"][i], reached.mean())
    assert s["p_success_low"][i] == rob["summary/wilson_low"][()]
    assert s["p_success_high"][i] == rob["summary/wilson_high"][()]
    for code, name in enumerate(["slipped", "stubbed", "saturated", "fell", "drifted"], 1):
        assert s[f"replays_{name}"][i] == np.count_nonzero(failure == code), name
    assert (s["replays"][()] == 4).all()
print("robustness sweep: scenario 4 = its study alone")
PY
