#!/usr/bin/env bash
# The speed-against-error study end to end: install what is missing, build, run the
# study (configs/study/study.yaml: output grids, fidelity choices, solver tolerances
# against a converged reference) into results/study/study.h5 and draw
# results/study/pareto.png; prints the table and the adaptive-grid verdict.
#
#   bash pipelines/study.sh            # the full study (a few minutes: Ipopt runs dominate)
#   bash pipelines/study.sh --quick    # reduced study (configs/study/quick.yaml), seconds,
#                                      # into results/study/quick/
# Runs are timed: leave the machine otherwise idle for meaningful wall times.
set -euo pipefail
quick=0
for arg in "$@"; do
  case "$arg" in
    --quick) quick=1 ;;
    -h|--help) sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "study.sh: error: unknown argument '$arg' (expected --quick)" >&2; exit 2 ;;
  esac
done
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
hexdyn_install
hexdyn_build hexdyn  # and hexdyn-sweep; the plots read files with no compiled part

if ((quick)); then
  study="$HEXDYN_ROOT/configs/study/quick.yaml"
  out="$HEXDYN_ROOT/results/study/quick"
else
  study="$HEXDYN_ROOT/configs/study/study.yaml"
  out="$HEXDYN_ROOT/results/study"
fi
mkdir -p "$out"
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/study.py" "$study" -o "$out/study.h5" \
  --hexdyn "$HEXDYN_BUILD/hexdyn"
"$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_study.py" "$out/study.h5" "$out"
echo "study: results in $out:" >&2
ls -1 "$out" >&2
