#!/bin/bash
# Sizes (docs/user/faults.md#sizes): every size that grows with the input is
# bounded before anything is planned or allocated. Each bomb runs under `ulimit -v` (2 GB of
# address space) and `timeout 60`: one line of hexdyn's naming the key and the limit, exit
# status 2, no output and no temporary file, every input unchanged (sha256sum). The bombs: an
# output step that overflowed an int (4e-9 s) or took gigabytes (1e-7, 1e-8 s), 100,000 gait
# cycles, a speed of 1e-300 m/s, a 400-byte YAML alias bomb (in a scene, a sweep, an envelope
# file), an envelope of 1300^3 or 2^32 cells. Then `hexdyn validate` of a sweep of 10^5
# scenarios answers with every count right (its speed is bench/validate_scale.py's claim).
# shellcheck source=common.sh
source "$(dirname "$0")/common.sh"

LIMIT_KB=2000000  # ulimit -v: 2 GB of address space
mkdir out
cp "$PAPER" paper.yaml
# The paper scene given by speed, for the cycle and speed bombs.
"$PY" - "$PAPER" > by_speed.yaml << 'EOF'
import sys
text = open(sys.argv[1]).read()
text = text.replace("  cycle_durations: [3.0, 2.6, 3.0]",
                    "  peak_speed: 0.1\n  ramp_duration: 0.8\n  cycles: 3")
assert "peak_speed: 0.1" in text
print(text, end="")
EOF

# A billion laughs: 9 levels of 10 aliases, 10^9 nodes once expanded, under `auto:`.
bomb() {
  local i j line
  echo "auto:"
  echo " a0: &0 [x,x,x,x,x,x,x,x,x,x]"
  for i in 1 2 3 4 5 6 7 8; do
    line=" a$i: &$i ["
    for j in 1 2 3 4 5 6 7 8 9 10; do line+="*$((i - 1))"; [ "$j" = 10 ] || line+=","; done
    echo "$line]"
  done
}
{ cat paper.yaml; bomb; } > bomb_scene.yaml
[ "$(bomb | wc -c)" -lt 400 ] || fail "the alias bomb is not small"
{ echo "base: paper.yaml"; echo "axes:"; echo "  - key: gait.duty_factor"; echo "    values: [1/2]"
  bomb | sed 's/^auto:/name: x\nextra:/'; } > bomb_sweep.yaml
{ echo "base: paper.yaml"; echo "riser: {from: 0.0, to: 0.1}"; echo "duty_factor: [1/2]"
  echo "peak_speed: [0.1]"; bomb | sed 's/^auto:/name:/'; } > bomb_envelope.yaml

# values N FROM STEP: a YAML flow list of N numbers.
values() {
  "$PY" -c "import sys; n, a, d = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]); \
print('[' + ', '.join('%.10g' % (a + d * i) for i in range(n)) + ']')" "$@"
}
envelope_file() {  # W B V: a stair envelope of W x B x V cells
  echo "base: $SRC/configs/sweeps/stairs_base.yaml"
  echo "riser: {from: 0.0, to: 0.1}"
  echo "tread_depth: $(values "$1" 0.2 1e-5)"
  echo "duty_factor: $(values "$2" 0.5 1e-4)"
  echo "peak_speed: $(values "$3" 0.05 1e-5)"
}
envelope_file 1300 1300 1300 > cells_1300.yaml
envelope_file 4096 1024 1024 > cells_2p32.yaml
printf 'base: %s\naxes:\n  - key: terrain.riser_height\n    range: {from: 0.0, to: 0.14, count: 1000}\n  - key: motion.peak_speed\n    range: {from: 0.05, to: 0.2, count: 100}\n' \
  "$SRC/configs/sweeps/stairs_base.yaml" > million.yaml

inputs_digest() { sha256sum ./*.yaml "$SRC/configs/sweeps/stairs_base.yaml" "$PAPER"; }
before=$(inputs_digest)


uniform() { echo --set output.grid=uniform --set "output.sample_step=$1" --set "output.event_step=$1"; }
# shellcheck disable=SC2046  # word splitting of uniform's options is intended
{
  refused step_4e-9 "paper.yaml: output.sample_step: got 4e-09 s, up to .* expected at most 1000000 samples .*--allow-large does not lift it" \
    run paper.yaml -o out/r.h5 $(uniform 4e-9)
  refused step_1e-7 "output.sample_step: got 1e-07 s" run paper.yaml -o out/r.h5 $(uniform 1e-7)
  refused step_1e-8 "output.sample_step: got 1e-08 s" run paper.yaml -o out/r.h5 $(uniform 1e-8) --allow-large
  refused step_validate "output.sample_step: got 1e-08 s" validate paper.yaml $(uniform 1e-8)
}
refused impact_samples "output.impact_samples: got 100000 .*expected at most 1000000 samples" \
  run paper.yaml -o out/r.h5 --set output.impact_samples=100000 --allow-large
refused cycles "by_speed.yaml: motion.cycles: got 100000, expected an integer in \[1, 10000\]" \
  run by_speed.yaml -o out/r.h5 --set motion.cycles=100000
refused cycles_samples "motion.cycles: got 10000 cycles, up to .* output samples" \
  run by_speed.yaml -o out/r.h5 --set motion.cycles=10000 --allow-large
refused travel "motion.travel: got 10000 m, .* cycles of gait.stroke, expected at most 10000 cycles" \
  run by_speed.yaml -o out/r.h5 --set motion.cycles=null --set motion.travel.distance=10000
refused speed "motion.peak_speed: got 1e-300 m/s, a motion of .* expected a motion of at most 1e\+05 s" \
  run by_speed.yaml -o out/r.h5 --set motion.peak_speed=1e-300
refused alias_scene "bomb_scene.yaml:[0-9]+: auto.a[0-9]+\[[0-9]+\]: got more than 1000000 YAML nodes once aliases" \
  run bomb_scene.yaml -o out/r.h5
refused alias_validate "auto.a[0-9]+\[[0-9]+\]: got more than 1000000 YAML nodes" validate bomb_scene.yaml
refused alias_sweep "bomb_sweep.yaml:[0-9]+: extra.a[0-9]+\[[0-9]+\]: got more than 1000000 YAML nodes" \
  validate bomb_sweep.yaml
refused alias_envelope "bomb_envelope.yaml:[0-9]+: name.a[0-9]+\[[0-9]+\]: got more than 1000000 YAML nodes" \
  envelope bomb_envelope.yaml -o out/e.h5
refused cells_1300 "cells_1300.yaml: tread_depth: got 1300 values, 2197000000 cells .*expected at most 10000 cells" \
  envelope cells_1300.yaml -o out/e.h5
refused cells_2p32 "cells_2p32.yaml: tread_depth: got 4096 values, 4294967296 cells .*expected at most 10000 cells" \
  envelope cells_2p32.yaml -o out/e.h5

# A sweep file holding the bomb, run as a sweep (hexdyn-sweep; without the address-space
# limit, which Open MPI's start-up may exceed): the same line, nothing written.
timeout 60 "$HEXDYN" sweep bomb_sweep.yaml -o out/s.h5 > alias_sweep_run.log 2>&1
expect_status alias_sweep_run $? 2 alias_sweep_run.log
one_line alias_sweep_run.log "bomb_sweep.yaml:[0-9]+: extra.a[0-9]+\[[0-9]+\]: got more than 1000000 YAML nodes"
[ -z "$(ls -A out)" ] || fail "alias_sweep_run: files left in out/: $(ls -A out)"

# 10^5 scenarios (axes of 1000 and 100 values): every scenario validated, the counts right.
# How long 10^6 take is a benchmark's claim (bench/validate_scale.py), not this test's: the
# timeout only guards against a hang.
(ulimit -v "$LIMIT_KB" && exec timeout 600 "$HEXDYN" validate million.yaml) > million.log 2>&1
rc=$?
[ "$rc" != 124 ] || fail "validate of 10^5 scenarios: no answer within 600 s"
expect_status million "$rc" 0 million.log
grep -q "million.yaml: valid sweep .*, 100000 scenarios over terrain.riser_height (1000) motion.peak_speed (100)" million.log ||
  fail "validate of 10^5 scenarios: $(cat million.log)"
[ "$(inputs_digest)" = "$before" ] || fail "million: an input changed"
echo "sizes: every bomb refused in one line naming its key, 10^5 scenarios validated"
