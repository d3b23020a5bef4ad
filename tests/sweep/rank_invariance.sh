#!/usr/bin/env bash
# The smoke sweep plainly (one rank, no mpirun) and under mpirun with 2 and 4 ranks,
# with --keep-runs: the three files are equal except timing fields (compare_sweeps.py).
# A kept run also equals `hexdyn run` of the base scene with the scenario's values as
# --set overrides: each scenario is the same library call as `hexdyn run`.
source "$(dirname "$0")/common.sh"
sweep="$SRC/configs/sweeps/smoke.yaml"
"$HEXDYN" sweep "$sweep" -o r1.h5 --keep-runs 2> r1.log || { cat r1.log; fail "1 rank"; }
mpi 2 sweep "$sweep" -o r2.h5 --keep-runs 2> r2.log || { cat r2.log; fail "2 ranks"; }
mpi 4 sweep "$sweep" -o r4.h5 --keep-runs 2> r4.log || { cat r4.log; fail "4 ranks"; }
grep -q "on 1 rank;" r1.log || fail "plain start is not one rank"
grep -q "on 2 ranks;" r2.log || fail "mpirun -np 2 is not 2 ranks"
grep -q "on 4 ranks;" r4.log || fail "mpirun -np 4 is not 4 ranks"
compare r1.h5 r2.h5
compare r1.h5 r4.h5
for f in r1 r2 r4; do [ ! -e "$f.h5.checkpoint" ] || fail "$f: checkpoint left behind"; done

# Scenario 000005 of the smoke sweep: riser 0.08 (1), speed 0.05 (0), duty 3/4 (1).
"$HEXDYN" run "$SRC/configs/sweeps/stairs_base.yaml" -o run5.h5 --set output.grid=uniform \
  --set motion.cycles=1 --set terrain.riser_height=0.08 --set motion.peak_speed=0.05 \
  --set gait.duty_factor=0.75 --set motion.posture=null \
  --set "motion.initial_position=[0.0, 0.412, 0.235]" 2> run5.log
compare --result run5.h5 r2.h5:/runs/000005
echo "rank invariance: ok"
