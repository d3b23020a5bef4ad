#!/usr/bin/env bash
# Every scene of a folder runs alone: `hexdyn run <scene>` exits 0 and writes its file.
#
#   scenes_run.sh HEXDYN FOLDER
#
# The quadruped study's scenes (configs/quadrupeds/) are the bases of its sweeps, which set
# each scenario's riser and speed; a newcomer runs them alone too, and there each must compute
# at its own settings (docs/validation/quadrupeds.md). A scene that fails is named with the
# program's one-line error; every scene is tried before the test fails.
set -uo pipefail
hexdyn=$1
folder=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0
count=0
for scene in "$folder"/*.yaml; do
  count=$((count + 1))
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
if [ "$count" -eq 0 ]; then
  echo "FAIL no scene in $folder"
  exit 1
fi
echo "$((count - failed)) of $count scenes ran"
[ "$failed" -eq 0 ]
