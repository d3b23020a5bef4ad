#!/usr/bin/env bash
# The climbable envelope of the paper robot end to end: install what is missing, build the
# binary (only it), run configs/envelope/paper.yaml (docs/user/envelope.md) and draw the
# plot and the table into results/envelope/.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
hexdyn_install
hexdyn_build hexdyn  # and hexdyn-sweep; the plots read files with no compiled part

out="$HEXDYN_ROOT/results/envelope"
mkdir -p "$out"
"$HEXDYN_BUILD/hexdyn" envelope "$HEXDYN_ROOT/configs/envelope/paper.yaml" -o "$out/paper.h5" -v 2> "$out/paper.log"
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_envelope.py" "$out/paper.h5" "$out" --check --table | tee "$out/paper.txt"
echo "envelope: results in $out:" >&2
ls -1 "$out" >&2
