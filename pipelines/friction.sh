#!/usr/bin/env bash
# The grip study end to end (docs/validation/friction.md): install what is missing, build, run
# the sweep configs/friction/stairs.yaml (the paper stairs, duty factor x peak speed x riser,
# 48 scenarios with kept runs) under mpirun with 2 ranks (HEXDYN_RANKS to change), and draw
# into results/friction/:
#   friction_required.png          the required friction, support and touchdown transients,
#                                  with its binding leg, against the published ranges
#   friction_transient_energy.png  the share of the energy spent in touchdown transients
#   friction.csv                   the values, one line per scenario (per-leg peaks too)
#   friction_table.txt             the same as a Markdown table
#
#   bash pipelines/friction.sh           # about a minute on 2 cores
#   bash pipelines/friction.sh --quick   # configs/friction/stairs_quick.yaml, one rank, seconds,
#                                        # into results/friction/quick/
# --hexdyn PATH runs that binary (its build tree's Python package) without installing or
# building; --out DIR writes there instead (the ctest test pipeline.friction_quick does both).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
hexdyn_study_args friction 17 "$@"
hexdyn_pipeline_start friction "$hexdyn" "$out" "$quick"
name=stairs
launch=(mpirun --oversubscribe -np "${HEXDYN_RANKS:-2}")
if ((quick)); then
  name=stairs_quick
  launch=()
fi
echo "friction: the paper stairs, duty factor x peak speed x riser" >&2
"${launch[@]}" "$hexdyn" sweep "$HEXDYN_ROOT/configs/friction/$name.yaml" -o "$out/friction.h5" \
  --keep-runs 2> "$out/friction.log" || { cat "$out/friction.log" >&2; exit 1; }
tail -n 1 "$out/friction.log" >&2
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_friction.py" "$out/friction.h5" "$out" \
  --name friction --table > "$out/friction_table.txt"
echo "friction: results in $out:" >&2
ls -1 "$out" >&2
