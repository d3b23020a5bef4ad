#!/usr/bin/env bash
# The smoke sweep end to end: install what is missing, build the binaries (only them), run
# configs/sweeps/smoke.yaml under mpirun with 2 ranks (HEXDYN_RANKS to change) and draw
# the heatmaps into results/sweeps/smoke/.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
hexdyn_install
hexdyn_build hexdyn  # and hexdyn-sweep; the plots read files with no compiled part

out="$HEXDYN_ROOT/results/sweeps/smoke"
mkdir -p "$out"
if [ "$(id -u)" -eq 0 ]; then
  # Open MPI refuses to run as root unless told twice.
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
mpirun --oversubscribe -np "${HEXDYN_RANKS:-2}" "$HEXDYN_BUILD/hexdyn" sweep \
  "$HEXDYN_ROOT/configs/sweeps/smoke.yaml" -o "$out/smoke.h5" --keep-runs
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_sweep.py" "$out/smoke.h5" "$out"
echo "sweep_smoke: results in $out:" >&2
ls -1 "$out" >&2
