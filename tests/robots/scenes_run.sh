#!/usr/bin/env bash
# Every scene of the folders given runs alone: `hexdyn run <scene>` exits 0 and writes its file.
#
#   scenes_run.sh HEXDYN FOLDER...
#
# The quadruped study's scenes (configs/quadrupeds/) are the bases of its sweeps, which set
# each scenario's riser and speed; a newcomer runs them alone too, and there each must compute
# at its own settings (docs/validation/quadrupeds.md). A scene that fails is named with the
# program's one-line error; every scene is tried before the test fails. The test
# configs.scenes_run_alone runs it on the other folders of scenes a user runs as they are
# (configs/variants, configs/replay, configs/robustness).
set -uo pipefail
hexdyn=$1
shift
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0
shopt -s nullglob
scenes=()
for folder in "$@"; do scenes+=("$folder"/*.yaml); done
for scene in "${scenes[@]}"; do
  if ! "$hexdyn" run "$scene" -o "$work/r.h5" > /dev/null 2> "$work/err"; then
    echo "FAIL $(basename "$scene"): $(grep -v '^\[' "$work/err" | tail -1)"
    failed=$((failed + 1))
  elif [ ! -s "$work/r.h5" ]; then
    echo "FAIL $(basename "$scene"): exited 0 without writing its file"
    failed=$((failed + 1))
  else
    echo "ok   $(basename "$scene"): $(grep 'verdict' "$work/err")"
  fi
  rm -f "$work/r.h5"
done
count=${#scenes[@]}
if [ "$count" -eq 0 ]; then
  echo "FAIL no scene in $*"
  exit 1
fi
echo "$((count - failed)) of $count scenes ran"
[ "$failed" -eq 0 ]
