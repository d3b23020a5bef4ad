#!/usr/bin/env bash
# The quadruped study end to end (docs/validation/quadrupeds.md): Solo-12 with the ODRI actuator
# module and ANYmal C with ANYdrive, each crawling (wave gait, beta = 3/4) and trotting
# (beta = 0.6) with the balanced trunk. Installs what is missing, builds, runs the eight sweeps
# of configs/quadrupeds/sweeps/ (per robot and gait: speed on flat ground, riser x speed on
# stairs; the scenes are configs/quadrupeds/*.yaml) one after the other on one rank, and draws
# into results/quadrupeds/:
#   quadrupeds_cot_speed.png   mechanical and electrical cost of transport against speed, flat
#   quadrupeds_cot_riser.png   the same against riser height on stairs, a line per speed
#   quadrupeds_envelope.png    the climbable envelope per gait: riser x speed, each scenario
#                              climbs (no relaxed sample outside touchdowns), relaxes or fails
#   quadrupeds_friction.png    the largest required friction outside touchdowns
#   quadrupeds_thermal.png     the peak winding temperature
#   quadrupeds.csv             every scenario: its robot, gait, terrain, riser, speed, status,
#                              relaxed counts and metrics (a failed one with its message)
#   quadrupeds_table.txt        the same as a Markdown table
#
#   bash pipelines/quadrupeds.sh           # 248 scenarios, about 2 min on one core
#   bash pipelines/quadrupeds.sh --quick   # configs/quadrupeds/sweeps/quick/, 16 scenarios with
#                                          # kept runs, into results/quadrupeds/quick/
# --hexdyn PATH runs that binary (its build tree's Python package) without installing or
# building; --out DIR writes there instead (the ctest test pipeline.quadrupeds_quick does both).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
hexdyn_study_args quadrupeds 22 "$@"
hexdyn_pipeline_start quadrupeds "$hexdyn" "$out" "$quick"
sweeps="$HEXDYN_ROOT/configs/quadrupeds/sweeps"
keep=()
if ((quick)); then
  sweeps="$sweeps/quick"
  keep=(--keep-runs)  # the test recomputes the table's values from the runs
fi
files=()
for robot in solo12 anymal_c; do
  for gait in crawl trot; do
    for terrain in flat stairs; do
      name="${robot}_${gait}_${terrain}"
      echo "quadrupeds: $name" >&2
      # A scenario that fails is a row of the sweep file (status, message); the sweep goes on.
      "$hexdyn" sweep "$sweeps/$name.yaml" -o "$out/$name.h5" "${keep[@]}" 2> "$out/$name.log" \
        || { cat "$out/$name.log" >&2; exit 1; }
      tail -n 1 "$out/$name.log" >&2
      files+=("$out/$name.h5")
    done
  done
done
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_quadrupeds.py" "$out" "${files[@]}"
echo "quadrupeds: results in $out:" >&2
ls -1 "$out" >&2
