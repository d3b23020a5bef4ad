#!/usr/bin/env bash
# Installs the Debian 12 packages hexdyn needs (only those missing) and builds it in
# build/ (Release). Sourced by the other pipelines, each building only what it runs
# (`hexdyn_build hexdyn` builds the binaries hexdyn and hexdyn-sweep, `hexdyn_python` the
# Python module); run on its own, and from pipelines/test.sh, it builds the default build
# (everything but the benchmarks, which the target `benchmarks` builds).
set -euo pipefail
HEXDYN_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export HEXDYN_ROOT
HEXDYN_BUILD="${HEXDYN_BUILD:-$HEXDYN_ROOT/build}"
export HEXDYN_BUILD
# Python analysis runs with Debian's interpreter: another python3 may come first on PATH.
export HEXDYN_PYTHON=/usr/bin/python3
# The Python package hexdyn (reader and module) from the build tree, for the analysis scripts.
export PYTHONPATH="$HEXDYN_BUILD/python${PYTHONPATH:+:$PYTHONPATH}"

HEXDYN_PACKAGES=(
  build-essential cmake pkg-config git
  libeigen3-dev coinor-libipopt-dev libhdf5-dev hdf5-tools libgsl-dev catch2
  libopenmpi-dev openmpi-bin libyaml-cpp-dev libbenchmark-dev liburdfdom-dev libssl-dev
  python3 python3-h5py python3-numpy python3-matplotlib python3-yaml
  python3-dev pybind11-dev python3-pybind11 python3-scipy
  # the required friction's second computation: HiGHS (scipy) and cvxopt's SOCP
  # (ctest python.required_friction, tests/python/test_required_friction.py)
  python3-cvxopt
  python3-xarray python3-h5netcdf python3-netcdf4 python3-pandas netcdf-bin udunits-bin
  clang-format
  # the Python lint of ctest format.python_lint (tests/format/check_python.sh)
  pyflakes3
  # analysis/animate.py: GIF through Pillow, MP4 through ffmpeg (pipelines/paper.sh writes one)
  python3-pil ffmpeg
  # DART 6.12's Python bindings: the drive train's armature and friction terms checked
  # against DART's (ctest dynamics.drive_train_against_dart, tests/python/test_drive_dart.py)
  python3-dartpy
)

hexdyn_install() {
  local missing=()
  for p in "${HEXDYN_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if ((${#missing[@]})); then
    echo "setup: installing ${missing[*]}" >&2
    local sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
  fi
}

# hexdyn_build [TARGET...]: configures build/ and builds the named targets (and what they
# need), or the default build -- libraries, hexdyn, the Python module and the tests -- when
# none is named (the benchmarks: `hexdyn_build benchmarks`, docs/dev/benchmarks.md).
hexdyn_build() {
  cmake -S "$HEXDYN_ROOT" -B "$HEXDYN_BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
  local targets=()
  for t in "$@"; do targets+=(--target "$t"); done
  cmake --build "$HEXDYN_BUILD" -j"$(nproc)" "${targets[@]}"
}

# The start the study pipelines share (designs.sh, friction.sh): NAME for messages and the
# results folder, their --hexdyn PATH (an executable of a build directory, used as it is; empty:
# install what is missing and build hexdyn and the Python module in HEXDYN_BUILD), their --out
# DIR (empty: results/NAME, or results/NAME/quick when QUICK is 1). Sets `hexdyn` (the
# executable) and `out` (an absolute directory, created); as root, lets Open MPI run.
hexdyn_pipeline_start() {
  local name="$1" given="$2" out_given="$3" quick="$4"
  if [[ -n "$given" ]]; then
    [[ -x "$given" ]] || {
      echo "$name.sh: error: --hexdyn: got '$given', expected an executable" >&2
      exit 2
    }
    HEXDYN_BUILD="$(cd "$(dirname "$given")" && pwd)"
    export HEXDYN_BUILD
    export PYTHONPATH="$HEXDYN_BUILD/python:$PYTHONPATH"
    hexdyn="$HEXDYN_BUILD/$(basename "$given")"
  else
    hexdyn_install
    hexdyn_build hexdyn hexdyn_python
    hexdyn="$HEXDYN_BUILD/hexdyn"
  fi
  out="$out_given"
  if [[ -z "$out" ]]; then
    out="$HEXDYN_ROOT/results/$name"
    if ((quick)); then out="$out/quick"; fi
  fi
  mkdir -p "$out"
  out="$(cd "$out" && pwd)"
  if [ "$(id -u)" -eq 0 ]; then
    # Open MPI refuses to run as root unless told twice.
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  fi
}

# The options of a study pipeline (friction.sh, replay.sh): NAME for messages, HELP the last
# line of the script's comment header (printed by -h), then the script's arguments. Sets
# `quick` (--quick: 1), `hexdyn` (--hexdyn PATH) and `out` (--out DIR) for
# hexdyn_pipeline_start; an unknown argument stops the script with one line, status 2.
hexdyn_study_args() {
  local name="$1" help="$2"
  shift 2
  quick=0
  hexdyn=""
  out=""
  while (($#)); do
    case "$1" in
      --quick) quick=1 ;;
      --hexdyn) hexdyn="${2:-}"; shift ;;
      --out) out="${2:-}"; shift ;;
      -h|--help) sed -n "2,${help}p" "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
      *) echo "$name.sh: error: unknown argument '$1' (expected --quick, --hexdyn PATH, --out DIR)" >&2
         exit 2 ;;
    esac
    shift
  done
}

if [[ "${BASH_SOURCE[0]}" == "$0" ]]; then
  hexdyn_install
  hexdyn_build
fi
