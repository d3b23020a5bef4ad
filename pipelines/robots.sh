#!/usr/bin/env bash
# The real robots from their URDF end to end (docs/validation/robots.md): install what is
# missing, build, and for the Trossen PhantomX Mark IV and Kraby write into
# results/robots/<robot>/:
#   - the stairs run (configs/robots/<robot>_stairs.yaml) and its figures, with the joint
#     torques recomputed from the original URDF (analysis/urdf_dynamics.py);
#   - the stair-height sweep (configs/sweeps/<robot>_risers.yaml) under mpirun with 2 ranks
#     (HEXDYN_RANKS to change) and its heatmaps;
#   - the climbable envelope (configs/envelope/<robot>.yaml), its plot and table.
# About 2 minutes on 2 cores.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
hexdyn_install
hexdyn_build hexdyn  # and hexdyn-sweep; the plots read files with no compiled part
if [ "$(id -u)" -eq 0 ]; then
  # Open MPI refuses to run as root unless told twice.
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi

for robot in phantomx_mark4 kraby; do
  out="$HEXDYN_ROOT/results/robots/$robot"
  mkdir -p "$out"
  echo "robots: $robot" >&2
  "$HEXDYN_BUILD/hexdyn" run "$HEXDYN_ROOT/configs/robots/${robot}_stairs.yaml" -o "$out/stairs.h5" -v \
    2> "$out/stairs.log"
  "$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/urdf_dynamics.py" "$out/stairs.h5" "$HEXDYN_ROOT/robots/$robot.urdf" \
    | tee "$out/urdf_dynamics.txt"
  "$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_kinematics.py" "$out/stairs.h5" "$out"
  "$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_paper.py" "$out/stairs.h5" "$out"
  "$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/robot_summary.py" "$out/stairs.h5" | tee "$out/summary.txt"

  mpirun --oversubscribe -np "${HEXDYN_RANKS:-2}" "$HEXDYN_BUILD/hexdyn" sweep \
    "$HEXDYN_ROOT/configs/sweeps/${robot}_risers.yaml" -o "$out/risers.h5"
  "$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_sweep.py" "$out/risers.h5" "$out/risers" \
    --rows terrain.riser_height --cols motion.peak_speed

  "$HEXDYN_BUILD/hexdyn" envelope "$HEXDYN_ROOT/configs/envelope/$robot.yaml" -o "$out/envelope.h5" \
    2> "$out/envelope.log"
  "$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_envelope.py" "$out/envelope.h5" "$out" --check --table \
    | tee "$out/envelope.txt"
done
echo "robots: results in $HEXDYN_ROOT/results/robots:" >&2
(cd "$HEXDYN_ROOT/results/robots" && find . -type f | sort) >&2
