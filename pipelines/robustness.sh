#!/usr/bin/env bash
# Will it still climb? (docs/validation/robustness.md): robustness studies of the paper hexapod
# and of Solo-12 crawling up stairs. Installs what is missing, builds, then
#   - four sweeps of studies (configs/robustness/sweeps/): P(success) against the riser error
#     and against the friction coefficient, per gait, each scenario planned once and replayed
#     on 40 perturbed worlds, on 2 MPI ranks;
#   - the 1,000-replay study of configs/robustness/paper.yaml (every perturbation at once),
#     timed, and the convergence of its P(success) with the number of replays;
# and writes into results/robustness/:
#   robustness.png          P(success) with its Wilson 95 % interval against riser error and
#                           against friction, per gait and robot, and the failure classes
#   robustness.csv          one row per scenario: robot, sweep, gait, value, replays, P, interval,
#                           failures by class
#   convergence.csv         P(success) and its interval after the first n replays of the
#                           1,000-replay study
#   paper_1000.h5 and .log, the sweeps' files and logs
#
#   bash pipelines/robustness.sh          # about 5 minutes on 2 cores
# --quick: 3 replays per scenario, two values per axis, a 40-replay study (the ctest test
# pipeline.robustness_quick); --hexdyn PATH runs that binary without building; --out DIR.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
hexdyn_study_args robustness 22 "$@"
hexdyn_pipeline_start robustness "$hexdyn" "$out" "$quick"
configs="$HEXDYN_ROOT/configs/robustness"
ranks="${HEXDYN_RANKS:-2}"
replays=1000
((quick)) && replays=40
files=()
for name in paper_riser paper_friction solo12_riser solo12_friction; do
  sweep="$configs/sweeps/$name.yaml"
  if ((quick)); then  # the same sweep with 3 replays and the first and last value of each axis
    sweep="$out/$name.quick.yaml"
    "$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_robustness.py" --quick-sweep \
      "$configs/sweeps/$name.yaml" "$sweep"
  fi
  rm -f "$out/$name.h5"
  mpirun --oversubscribe -np "$ranks" "$hexdyn" sweep "$sweep" -o "$out/$name.h5" \
    2> "$out/$name.log" || { cat "$out/$name.log" >&2; exit 1; }
  tail -n 1 "$out/$name.log" >&2
  files+=("$out/$name.h5")
done
rm -f "$out/paper_1000.h5"
start=$SECONDS
"$hexdyn" robustness "$configs/paper.yaml" -o "$out/paper_1000.h5" -j "$ranks" \
  --set "robustness.replays=$replays" 2> "$out/paper_1000.log" ||
  { cat "$out/paper_1000.log" >&2; exit 1; }
tail -n 3 "$out/paper_1000.log" >&2
echo "robustness: $replays replays of configs/robustness/paper.yaml in $((SECONDS - start)) s" \
  "on $ranks threads" >&2
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_robustness.py" "$out" "$out/paper_1000.h5" \
  "${files[@]}"
echo "robustness: results in $out" >&2
