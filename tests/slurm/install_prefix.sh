#!/usr/bin/env bash
# `cmake --install` into a temporary prefix (tests/slurm.cmake):
#   install_prefix.sh CMAKE BUILD_DIR WORK_DIR [PYTHON]
#
# The installed tree alone, without the repository: P/bin/hexdyn runs the installed paper
# scene, the installed analysis checks the file and imports the installed Python package
# hexdyn (P/lib/python3.X/dist-packages, on PYTHONPATH as a module sets it), whose reader
# finds the schema header next to itself,
# and the installed slurm_sweep.sbatch, run as a plain script (HEXDYN_LAUNCHER=mpirun,
# 2 tasks) from a directory without build/, finds hexdyn on PATH and the installed plot
# script through HEXDYN_SHARE, as under a cluster module.
set -euo pipefail
CMAKE="$1"
BUILD="$(realpath "$2")"
WORK="$3"
PY="${4:-/usr/bin/python3}"
fail() {
  echo "FAILED: $*" >&2
  exit 1
}
rm -rf "$WORK"
mkdir -p "$WORK/run"
cd "$WORK"
P="$WORK/prefix"
"$CMAKE" --install "$BUILD" --prefix "$P" > install.log 2>&1 || { cat install.log >&2; fail "cmake --install"; }
S="$P/share/hexdyn"
for f in bin/hexdyn share/hexdyn/configs/paper.yaml share/hexdyn/configs/sweeps/smoke.yaml \
         share/hexdyn/pipelines/slurm_sweep.sbatch \
         share/hexdyn/analysis/check_result.py share/hexdyn/analysis/plot_sweep.py \
         share/hexdyn/src/hexdyn/io/schema.hpp; do
  [ -f "$P/$f" ] || fail "not installed: $f"
done
[ -x "$S/pipelines/slurm_sweep.sbatch" ] || fail "installed slurm_sweep.sbatch is not executable"

SITE="$P/$("$PY" -c 'import sys; print("lib/python%d.%d/dist-packages" % sys.version_info[:2])')"
for f in __init__.py atomic_file.py data.py energy.py h5copy.py h5files.py results.py schema.py xr.py \
         _version.py _schema.py; do
  [ -f "$SITE/hexdyn/$f" ] || fail "not installed: $SITE/hexdyn/$f"
done

# What the installed module file sets (docs/user/sweeps.md#an-installed-hexdyn), read from
# its prepend_path and setenv lines as Lmod would apply them; no PYTHONPATH of our own.
LUA="$S/modulefiles/hexdyn.lua"
[ -f "$LUA" ] || fail "not installed: $LUA"
unset PYTHONPATH HEXDYN_SHARE
while IFS='|' read -r verb name rel; do
  value="$P/$rel"
  case "$verb" in
    prepend_path) export "$name=$value${!name:+:${!name}}" ;;
    setenv) export "$name=$value" ;;
  esac
done < <(sed -nE 's/^(prepend_path|setenv)\("([A-Z_]+)", pathJoin\(prefix, "([^"]*)"\)\)$/\1|\2|\3/p' "$LUA")
[ "${PYTHONPATH:-}" = "$SITE" ] || fail "the module file puts ${PYTHONPATH:-nothing} on PYTHONPATH, not $SITE"
[ "${HEXDYN_SHARE:-}" = "$S" ] || fail "the module file sets HEXDYN_SHARE=${HEXDYN_SHARE:-}, not $S"
grep -q "^local prefix = \"$P\"$" "$LUA" || fail "the module file names another prefix than $P"
cd "$WORK/run"
version="$(hexdyn --version)" || fail "hexdyn --version"
echo "installed: $version" >&2
hexdyn run "$S/configs/paper.yaml" -o paper.h5 2> run.log || { cat run.log >&2; fail "installed hexdyn run paper.yaml"; }
"$PY" "$S/analysis/check_result.py" paper.h5 --dynamics --expect-mass 6.7
mkdir -p grip
"$PY" "$S/analysis/plot_grip.py" paper.h5 grip > grip.log 2>&1 ||
  { cat grip.log >&2; fail "installed analysis/plot_grip.py under the module file's environment"; }
"$PY" -c "import hexdyn; r = hexdyn.open_result('paper.h5'); print('hexdyn from', hexdyn.results.__file__)" \
  | grep -q "from $SITE/hexdyn/results.py" || fail "hexdyn not imported from the prefix"

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
env -u HEXDYN_BIN HEXDYN_LAUNCHER=mpirun SLURM_NTASKS=2 SLURM_SUBMIT_DIR="$WORK/run" HEXDYN_PYTHON="$PY" \
  bash "$S/pipelines/slurm_sweep.sbatch" "$S/configs/sweeps/smoke.yaml" sweep/smoke.h5 2> sweep.log ||
  { cat sweep.log >&2; fail "installed slurm_sweep.sbatch"; }
grep -q "mpirun -np 2 .*$P/bin/hexdyn sweep" sweep.log || { cat sweep.log >&2; fail "the job script did not take hexdyn from PATH"; }
grep -q "on 2 ranks" sweep.log || { cat sweep.log >&2; fail "the sweep did not run on 2 ranks"; }
n=$(find sweep -name '*.png' | wc -l)
[ "$n" -gt 0 ] || { cat sweep.log >&2; fail "no heatmaps from the installed plot_sweep.py"; }
echo "install prefix: ok ($version; $n heatmaps from the installed job script)"
