#!/usr/bin/env bash
# Kill -9 of mpirun part-way through a sweep, then --resume: the final file equals an
# uninterrupted run's (timing fields excepted) and the resumed run computes exactly the
# scenarios that had no checkpoint file.
source "$(dirname "$0")/common.sh"
sweep="$SRC/tests/sweep/resume.yaml"
mpi 2 sweep "$sweep" -o ref.h5 --keep-runs 2> ref.log || { cat ref.log; fail "reference run"; }

# The interrupted run: killed once at least 6 scenarios are checkpointed.
"$MPIEXEC" --oversubscribe -np 2 "$HEXDYN" sweep "$sweep" -o cut.h5 --keep-runs -v 2> cut.log &
launcher=$!
cp=cut.h5.checkpoint
deadline=$((SECONDS + 120))
while :; do
  n=$(find "$cp" -maxdepth 1 -name '[0-9]*.h5' 2>/dev/null | wc -l || true)
  [ "$n" -ge 6 ] && break
  kill -0 "$launcher" 2>/dev/null || { cat cut.log; fail "the sweep ended before it could be killed"; }
  [ "$SECONDS" -lt "$deadline" ] || fail "no checkpoint files after 120 s"
  sleep 0.05
done
ranks=$(children_of "$launcher")
kill -9 "$launcher"
wait "$launcher" 2>/dev/null || true
# The ranks lose their launcher and exit; wait for them (they are ours to stop if not).
for _ in $(seq 100); do
  alive=""
  for p in $ranks; do kill -0 "$p" 2>/dev/null && alive="$alive $p"; done
  [ -z "$alive" ] && break
  sleep 0.1
done
for p in $alive; do kill -9 "$p" 2>/dev/null || true; done
[ ! -e cut.h5 ] || fail "the killed sweep wrote its output file"
for f in "$cp"/[0-9]*.h5; do [ -e "$f" ] && basename "$f" .h5; done | sort > before.txt
before=$(wc -l < before.txt)
total=24
[ "$before" -lt "$total" ] || fail "every scenario was checkpointed before the kill"
echo "killed with $before of $total scenarios checkpointed"

mpi 2 sweep "$sweep" -o cut.h5 --keep-runs --resume -v 2> resume.log || { cat resume.log; fail "resume"; }
sed -n 's/^hexdyn: sweep: scenario \([0-9]*\) .*(rank.*/\1/p' resume.log | sort > computed.txt
computed=$(wc -l < computed.txt)
[ -z "$(comm -12 before.txt computed.txt)" ] || fail "resume recomputed checkpointed scenarios: $(comm -12 before.txt computed.txt | tr '\n' ' ')"
[ "$((before + computed))" -eq "$total" ] || fail "resume computed $computed, expected $((total - before))"
grep -q "$computed computed by this run, $before taken from the checkpoint" resume.log || { cat resume.log; fail "summary line"; }
"$PY" - cut.h5 "$before" <<'PY'
import sys
import h5py
with h5py.File(sys.argv[1], "r") as f:
    got = int(f["meta"].attrs["resumed_scenarios"])
assert got == int(sys.argv[2]), f"/meta resumed_scenarios {got}, expected {sys.argv[2]}"
PY
compare ref.h5 cut.h5
[ ! -e "$cp" ] || fail "checkpoint left behind after the resumed sweep completed"
echo "resume after kill: ok ($computed recomputed, $before from the checkpoint)"
