#!/usr/bin/env bash
# Design studies end to end (docs/user/designs.md): install what is missing, build, run the
# studies under mpirun with 2 ranks (HEXDYN_RANKS to change) and draw their figures into
# results/designs/:
#   paper   the paper robot over femur x tibia length on three risers
#           (configs/designs/paper_femur_tibia.yaml; masses and inertias follow the lengths):
#           paper_femur_tibia.png, paper_femur_tibia_climb.png, paper_femur_tibia.csv
#   robots  the URDF robots as cases of one sweep over risers (configs/designs/robots.yaml,
#           kept runs for the effort limits) and the climbable envelope per robot
#           (configs/designs/robots_envelope.yaml, the same cases): robots.png,
#           robots_envelope.png, robots_envelope.csv, robots.csv
#   servos  the paper robot with five Dynamixel servos over duty factor x riser at equal
#           travel (configs/designs/paper_servos.yaml, kept runs): which servo climbs, and at
#           what electrical cost of transport: paper_servos.png, paper_servos_climb.png,
#           paper_servos_energy.png, paper_servos.csv, the answer on stderr
#
#   bash pipelines/designs.sh                # the three studies, a few minutes on 2 cores
#   bash pipelines/designs.sh --only paper   # one study (paper, robots or servos)
#   bash pipelines/designs.sh --quick        # reduced studies (*_quick.yaml), one rank, seconds,
#                                            # into results/designs/quick/
# --hexdyn PATH runs that binary (its build tree's Python package) without installing or
# building; --out DIR writes there instead (the ctest test pipeline.designs_quick does both).
set -euo pipefail
quick=0
only=""
hexdyn=""
out=""
while (($#)); do
  case "$1" in
    --quick) quick=1 ;;
    --only)
      only="${2:-}"; shift
      [[ "$only" == paper || "$only" == robots || "$only" == servos ]] ||
        { echo "designs.sh: error: --only: got '$only', expected paper, robots or servos" >&2; exit 2; } ;;
    --hexdyn) hexdyn="${2:-}"; shift ;;
    --out) out="${2:-}"; shift ;;
    -h|--help) sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "designs.sh: error: unknown argument '$1' (expected --quick, --only paper|robots|servos, --hexdyn PATH, --out DIR)" >&2
       exit 2 ;;
  esac
  shift
done
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
hexdyn_pipeline_start designs "$hexdyn" "$out" "$quick"
suffix=""
((quick)) && suffix="_quick"
cfg="$HEXDYN_ROOT/configs/designs"

# sweep NAME [ARGS...]: configs/designs/NAME.yaml into OUT/NAME.h5 (one rank for the reduced
# studies).
sweep() {
  local name="$1"
  shift
  local launch=()
  ((quick)) || launch=(mpirun --oversubscribe -np "${HEXDYN_RANKS:-2}")
  "${launch[@]}" "$hexdyn" sweep "$cfg/$name.yaml" -o "$out/$name.h5" "$@" 2> "$out/$name.log" ||
    { cat "$out/$name.log" >&2; exit 1; }
  tail -n 1 "$out/$name.log" >&2
}

if [[ -z "$only" || "$only" == paper ]]; then
  echo "designs: the paper robot, femur x tibia length" >&2
  sweep "paper_femur_tibia$suffix"
  "$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_designs.py" "$out/paper_femur_tibia$suffix.h5" "$out" \
    --name "paper_femur_tibia$suffix" >/dev/null
fi
if [[ -z "$only" || "$only" == robots ]]; then
  echo "designs: the URDF robots as cases" >&2
  sweep "robots$suffix" --keep-runs
  name="robots_envelope$suffix"
  "$hexdyn" envelope "$cfg/$name.yaml" -o "$out/$name.h5" 2> "$out/$name.log" ||
    { cat "$out/$name.log" >&2; exit 1; }
  tail -n 1 "$out/$name.log" >&2
  "$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_designs.py" "$out/robots$suffix.h5" "$out" --cases \
    --envelope "$out/$name.h5" --name "robots$suffix" >/dev/null
fi
if [[ -z "$only" || "$only" == servos ]]; then
  echo "designs: the paper robot with servos, duty factor x riser" >&2
  sweep "paper_servos$suffix" --keep-runs
  "$HEXDYN_PYTHON" "$HEXDYN_ROOT/analysis/plot_designs.py" "$out/paper_servos$suffix.h5" "$out" \
    --servos --name "paper_servos$suffix" >/dev/null
fi
echo "designs: results in $out:" >&2
ls -1 "$out" >&2
