#!/usr/bin/env bash
# Kill -9 of mpirun part-way through a sweep, then --resume: the final file equals an
# uninterrupted run's (timing fields excepted) and the resumed run computes exactly the
# scenarios that had no intact checkpoint record. Then the same with a damaged
# checkpoint: bytes flipped in one record and the journal cut short in another are
# named in warnings, those scenarios are computed again, and the file is still equal.
source "$(dirname "$0")/common.sh"
sweep="$SRC/tests/sweep/resume.yaml"
mpi 2 sweep "$sweep" -o ref.h5 --keep-runs 2> ref.log || { cat ref.log; fail "reference run"; }

# The interrupted run: killed once at least 6 scenarios are checkpointed.
"$MPIEXEC" --oversubscribe -np 2 "$HEXDYN" sweep "$sweep" -o cut.h5 --keep-runs -v 2> cut.log &
launcher=$!
cp=cut.h5.checkpoint
kill_after_rows "$launcher" "$cp" 6 cut.log
[ ! -e cut.h5 ] || fail "the killed sweep wrote its output file"
[ "$(find "$cp" -name '*.hxj' | wc -l)" -eq 1 ] || fail "expected one checkpoint journal, found: $(ls "$cp")"
"$PY" "$SRC/tests/sweep/journal_rows.py" "$cp" > before.txt
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

# --- A damaged checkpoint: a killed run again, then bytes flipped and a journal cut.
"$MPIEXEC" --oversubscribe -np 2 "$HEXDYN" sweep "$sweep" -o dmg.h5 --keep-runs 2> dmg.log &
launcher=$!
cp=dmg.h5.checkpoint
kill_after_rows "$launcher" "$cp" 8 dmg.log
journal=$(ls "$cp"/*.hxj)
"$PY" - "$journal" "$SRC/tests/sweep" > damaged.txt <<'PY'
# Flips a byte in the second record's payload and cuts the journal in the middle of its
# last record; prints the ids of the two damaged scenarios.
import sys
sys.path.insert(0, sys.argv[2])
from journal_rows import records
path = sys.argv[1]
data = bytearray(open(path, "rb").read())
recs = [(i, at) for k, i, at in records(bytes(data)) if k == 1]
assert len(recs) >= 4, recs
flip_index, flip_at = recs[1]
cut_index, cut_at = recs[-1]
data[flip_at + 60] ^= 0xFF
del data[cut_at + 50:]
open(path, "wb").write(data)
print(f"{flip_index:06d}")
print(f"{cut_index:06d}")
PY
"$PY" "$SRC/tests/sweep/journal_rows.py" "$cp" > intact.txt
mpi 2 sweep "$sweep" -o dmg.h5 --keep-runs --resume -v 2> dmg_resume.log || { cat dmg_resume.log; fail "resume of a damaged checkpoint"; }
for id in $(cat damaged.txt); do
  grep -q "warning: .*record of scenario $id" dmg_resume.log ||
    { cat dmg_resume.log; fail "no warning names damaged scenario $id"; }
  grep -q "scenario $id .*(rank" dmg_resume.log || { cat dmg_resume.log; fail "damaged scenario $id not computed again"; }
done
sed -n 's/^hexdyn: sweep: scenario \([0-9]*\) .*(rank.*/\1/p' dmg_resume.log | sort > dmg_computed.txt
[ -z "$(comm -12 intact.txt dmg_computed.txt)" ] || fail "resume recomputed intact records: $(comm -12 intact.txt dmg_computed.txt | tr '\n' ' ')"
compare ref.h5 dmg.h5
echo "resume after damage: ok ($(wc -l < damaged.txt) damaged records recomputed)"
