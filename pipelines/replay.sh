#!/usr/bin/env bash
# Slip and impact against gait and speed (docs/validation/replay.md): install what is missing,
# build, plan the paper stairs (configs/replay/stairs.yaml: three treads of travel) once per
# duty factor x peak speed with `hexdyn run`, replay each plan with `hexdyn replay` on surfaces
# of several friction coefficients mu (contact.static_friction = contact.dynamic_friction), two
# processes at a time (HEXDYN_JOBS to change), and draw into results/replay/:
#   replay.csv              one line per replay: slip distance and energy, touchdown (normal
#                           damping) energy, their shares of the replay's joint energy, the
#                           joint energy against the inverse dynamics', drift at the end,
#                           whether the robot reached the top, wall times
#   replay_table.txt        the same as a Markdown table
#   replay_shares.png       slip and touchdown shares against duty factor and speed, per mu,
#                           the replays that did not reach the top marked
#   runs/, replays/         the result and replay files; logs/ what each command printed
#                           (the three folders are emptied first)
#
#   bash pipelines/replay.sh           # 4 duty factors x 3 speeds x 4 mu, about a minute
#   bash pipelines/replay.sh --quick   # 2 plans x 2 mu at replay.step 1e-3 s, seconds, into
#                                      # results/replay/quick/
# --hexdyn PATH runs that binary (its build tree's Python package) without installing or
# building; --out DIR writes there instead (the ctest test pipeline.replay_quick does both).
# The replays use the integrator settings the scene file sets (replay.step 2.5e-4 s,
# replay.tolerance 0.01: docs/validation/replay.md#speed-against-error).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
hexdyn_study_args replay 23 "$@"
hexdyn_pipeline_start replay "$hexdyn" "$out" "$quick"

# The axes: the grip study's duty factors (tripod, tetrapod, wave gaits; configs/friction/
# stairs.yaml), peak speeds around the paper's 0.1 m/s, and surfaces from slippery to grippy
# around the paper's mu = 0.3 (the plans' allocation keeps the paper's 0.3 pyramid throughout).
duties=(1/2 2/3 3/4 5/6)
speeds=(0.05 0.10 0.15)
mus=(0.2 0.3 0.5 0.8)
step=""  # the scene's replay.step
if ((quick)); then
  duties=(1/2 3/4)
  speeds=(0.15)
  mus=(0.2 0.8)
  step=1e-3  # the default step: four times fewer steps than the scene's
fi
jobs="${HEXDYN_JOBS:-2}"
rm -rf "$out/runs" "$out/replays" "$out/logs"
mkdir -p "$out/runs" "$out/replays" "$out/logs"
export hexdyn out step
export scene="$HEXDYN_ROOT/configs/replay/stairs.yaml"

# plan DUTY SPEED: one `hexdyn run`; replay DUTY SPEED MU: one `hexdyn replay` of its result.
# A failed command leaves its log in logs/ and no file; the others go on.
plan() {
  local name="d${1/\//_}_v$2"
  "$hexdyn" run "$scene" --set "gait.duty_factor=$1" --set "motion.peak_speed=$2" \
    -o "$out/runs/$name.h5" > "$out/logs/$name.log" 2>&1 ||
    echo "replay.sh: warning: hexdyn run failed for duty $1, speed $2 (logs/$name.log)" >&2
}
replay() {
  local name="d${1/\//_}_v$2"
  [[ -f "$out/runs/$name.h5" ]] || return 0
  "$hexdyn" replay "$out/runs/$name.h5" -o "$out/replays/${name}_mu$3.h5" \
    --set "contact.static_friction=$3" --set "contact.dynamic_friction=$3" \
    ${step:+--set "replay.step=$step"} > "$out/logs/${name}_mu$3.log" 2>&1 ||
    echo "replay.sh: warning: hexdyn replay failed for duty $1, speed $2, mu $3" \
      "(logs/${name}_mu$3.log)" >&2
}
export -f plan replay

echo "replay: ${#duties[@]} duty factors x ${#speeds[@]} speeds planned, each replayed at" \
  "mu = ${mus[*]}, $jobs at a time" >&2
start=$SECONDS
for d in "${duties[@]}"; do for v in "${speeds[@]}"; do echo "$d $v"; done; done |
  xargs -P "$jobs" -L 1 bash -c 'plan "$@"' _
for d in "${duties[@]}"; do for v in "${speeds[@]}"; do for m in "${mus[@]}"; do
  echo "$d $v $m"
done; done; done | xargs -P "$jobs" -L 1 bash -c 'replay "$@"' _
echo "replay: $(ls "$out/replays" | wc -l) replays in $((SECONDS - start)) s" >&2
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/replay_sweep.py" "$out/replays" "$out/replay.csv" \
  --table > "$out/replay_table.txt"
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_replay.py" "$out/replay.csv" "$out"
echo "replay: results in $out:" >&2
ls -1 "$out" >&2
