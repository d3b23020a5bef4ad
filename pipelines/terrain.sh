#!/usr/bin/env bash
# Terrain as built (docs/validation/terrain.md): the examples of configs/terrain/ with the paper
# hexapod (configs/terrain/*.yaml) and ANYmal C (configs/terrain/anymal/*.yaml), and ascent
# against descent per gait (configs/terrain/sweeps/). Installs what is missing, builds, runs
# every example (a run that fails is reported with its one-line error, and the pipeline goes
# on), the two sweeps, and draws into results/terrain/:
#   terrain_up_down.png   joint energy, its positive and negative parts, and the peak joint
#                         torque against the signed riser, per robot and duty factor
#   terrain_runs.csv      every example run: robot, example, status, relaxed samples outside
#                         touchdowns, energy, positive and negative work, peak torque, message
#   terrain_table.txt     the same as a Markdown table
#   runs/ROBOT__EXAMPLE.h5 and .log, hexapod_up_down.h5, anymal_up_down.h5, rough_map.npy
#   (the rough height map, analysis/make_rough_map.py)
#
#   bash pipelines/terrain.sh            # 12 example runs and 30 scenarios, about a minute
# --hexdyn PATH runs that binary (its build tree's Python package) without installing or
# building; --out DIR writes there instead (the ctest test pipeline.terrain does both).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
hexdyn_study_args terrain 17 "$@"
hexdyn_pipeline_start terrain "$hexdyn" "$out" "$quick"
configs="$HEXDYN_ROOT/configs/terrain"
mkdir -p "$out/runs"
# The rough height map the rough_map examples stand on (seeded: the same file every time).
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/make_rough_map.py" "$out/rough_map.npy" >&2
for scene in "$configs"/*.yaml "$configs"/anymal/*.yaml; do
  example="$(basename "$scene" .yaml)"
  robot=paper_hexapod
  [[ "$(basename "$(dirname "$scene")")" == anymal ]] && robot=anymal_c
  stem="$out/runs/${robot}__${example}"
  rm -f "$stem.h5"
  map=()
  [[ "$example" == rough_map ]] && map=(--set "terrain.height_map.file=$out/rough_map.npy")
  # A run that cannot plan (a riser beyond the legs' reach) exits with one line: a result.
  if "$hexdyn" run "$scene" -o "$stem.h5" "${map[@]}" 2> "$stem.log"; then
    echo "terrain: $robot on $example: $(grep 'verdict' "$stem.log" | tail -n 1)" >&2
  else
    echo "terrain: $robot on $example: $(tail -n 1 "$stem.log")" >&2
  fi
done
sweeps=()
for name in hexapod_up_down anymal_up_down; do
  "$hexdyn" sweep "$configs/sweeps/$name.yaml" -o "$out/$name.h5" 2> "$out/$name.log" \
    || { cat "$out/$name.log" >&2; exit 1; }
  tail -n 1 "$out/$name.log" >&2
  sweeps+=("$out/$name.h5")
done
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_terrain.py" "$out" "${sweeps[@]}"
echo "terrain: results in $out" >&2
