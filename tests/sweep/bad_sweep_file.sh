#!/usr/bin/env bash
# A bad sweep file fails before any work: exit status 2, one line from hexdyn (the same
# "FILE: path: got X, expected Y" form as `hexdyn run`), and neither the output file nor
# a checkpoint is created, plainly and under mpirun. A checkpoint left by an interrupted
# sweep is not overwritten without --resume.
source "$(dirname "$0")/common.sh"
base="$SRC/configs/sweeps/stairs_base.yaml"
printf 'base: %s\naxes:\n  - key: gait.duty\n    values: [0.5, 0.75]\n' "$base" > unknown_key.yaml
printf 'base: %s\naxes:\n  - key: gait.duty_factor\n    range: {from: 0.5, to: 0.75, count: 1}\n' "$base" > bad_range.yaml
printf 'base: %s\naxes: [\n' "$base" > syntax.yaml

check() {  # check FILE LINE_START LAUNCHER...: prints the exit status
  local file="$1" start="$2"
  shift 2
  set +e
  "$@" sweep "$file" -o out.h5 > out.txt 2> err.txt
  local status=$?
  set -e
  local lines
  lines=$(grep -c '^hexdyn' err.txt || true)
  [ "$lines" -eq 1 ] || { cat err.txt >&2; fail "$file: $lines hexdyn lines on stderr, expected 1"; }
  grep '^hexdyn' err.txt | grep -qF -- "$start" || { cat err.txt >&2; fail "$file: expected a line starting: $start"; }
  [ "$(grep '^hexdyn' err.txt | cut -c1-${#start})" = "$start" ] || { cat err.txt >&2; fail "$file: line does not start with: $start"; }
  [ "$status" -ne 0 ] || fail "$file: exit status 0"
  if [ -e out.h5 ] || [ -e out.h5.checkpoint ]; then fail "$file: output or checkpoint created"; fi
  echo "$status"
}

for launcher in plain mpi; do
  if [ "$launcher" = plain ]; then run=("$HEXDYN"); else run=(mpi 2); fi
  s=$(check unknown_key.yaml "hexdyn: error: unknown_key.yaml: axes[0].key: got gait.duty, expected a key of the base scene $base (near: gait.duty_factor," "${run[@]}")
  [ "$launcher" = mpi ] || [ "$s" -eq 2 ] || fail "plain start: exit status $s, expected 2"
  s=$(check bad_range.yaml "hexdyn: error: bad_range.yaml: axes[0].range.count: got 1, expected an integer in [2, 100000]" "${run[@]}")
  [ "$launcher" = mpi ] || [ "$s" -eq 2 ] || fail "plain start: exit status $s, expected 2"
  s=$(check syntax.yaml "hexdyn: error: syntax.yaml:3:" "${run[@]}")
  [ "$launcher" = mpi ] || [ "$s" -eq 2 ] || fail "plain start: exit status $s, expected 2"
done

# An interrupted sweep's checkpoint without --resume: refused, left as it is.
mkdir out.h5.checkpoint
printf 'journal' > out.h5.checkpoint/journal-0001.hxj
set +e
"$HEXDYN" sweep "$SRC/configs/sweeps/smoke.yaml" -o out.h5 2> err.txt
status=$?
set -e
[ "$status" -eq 2 ] || { cat err.txt; fail "existing checkpoint: exit status $status, expected 2"; }
grep -q "out.h5.checkpoint: the checkpoint of an interrupted sweep exists; continue it with --resume" err.txt || { cat err.txt; fail "existing checkpoint message"; }
if [ "$(cat out.h5.checkpoint/journal-0001.hxj)" != journal ] || [ -e out.h5 ]; then fail "existing checkpoint touched"; fi
echo "bad sweep file: ok"
