#!/usr/bin/env bash
# The paper scenario end to end: install what is missing, build the hexdyn binary and the
# Python module (only them: the tests and benchmarks are built by pipelines/test.sh; after
# it, PYTHONPATH=build/python /usr/bin/python3 imports hexdyn), run configs/paper.yaml and
# draw the figures and the animation (paper.mp4, through ffmpeg) into results/paper/.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
hexdyn_install
hexdyn_build hexdyn hexdyn_python

out="$HEXDYN_ROOT/results/paper"
mkdir -p "$out"
"$HEXDYN_BUILD/hexdyn" run "$HEXDYN_ROOT/configs/paper.yaml" -o "$out/paper.h5"
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_kinematics.py" "$out/paper.h5" "$out"
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_paper.py" "$out/paper.h5" "$out"
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_actuators.py" "$out/paper.h5" "$out"
# Grip per leg: utilised and required friction, the scene's mu, slip (docs/theory/grip.md).
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_grip.py" "$out/paper.h5" "$out"
# The motion, side view, 10 frames per second at 640 x 448 pixels (docs/user/animation.md).
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/animate.py" "$out/paper.h5" -o "$out/paper.mp4" --fps 10
# The paper's statements against this run (docs/validation/paper.md).
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/paper_statements.py" "$out/paper.h5"
echo "paper: results in $out:" >&2
ls -1 "$out" >&2
