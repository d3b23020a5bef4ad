#!/usr/bin/env bash
# The layouts declared in src/hexdyn/io/schema.hpp, as hexdyn.results (bindings/python/hexdyn/results.py) has
# them from the generated module, equal what the C++ writers write: a result file (`hexdyn run`) and a sweep file
# with an axis of numbers, an axis of words, failed rows and kept runs hold every
# declared path with its units, shape and element type, and nothing undeclared.
source "$(dirname "$0")/common.sh"
"$HEXDYN" run "$SRC/configs/sweeps/stairs_base.yaml" --set motion.cycles=1 -o result.h5 2> run.log || { cat run.log; fail "run"; }
"$HEXDYN" sweep "$SRC/tests/sweep/schema.yaml" -o sweep.h5 --keep-runs 2> sweep.log || { cat sweep.log; fail "sweep"; }
"$PY" "$SRC/tests/sweep/check_schema.py" --result result.h5 --sweep sweep.h5
echo "schema declared = written: ok"
