#!/usr/bin/env bash
# The smoke sweep under 2 ranks with --keep-runs, read back by hexdyn.results (bindings/python/hexdyn/results.py)
# (check_reader.py) and drawn by analysis/plot_sweep.py. Progress lines (--progress 0:
# one per finished scenario) give done/total, rate and time left.
source "$(dirname "$0")/common.sh"
mpi 2 sweep "$SRC/configs/sweeps/smoke.yaml" -o smoke.h5 --keep-runs --progress 0 2> smoke.log || { cat smoke.log; fail "sweep"; }
progress='^hexdyn: sweep: [1-8]/8 done, [0-9.e+]+ scenarios/s, ([0-9]+ (s|min)[^,]*, )?[0-9]+ (s|min)[^,]* elapsed$'
[ "$(grep -cE "$progress" smoke.log)" -ge 2 ] || { cat smoke.log; fail "progress lines"; }
grep -qE '^hexdyn: sweep: [1-7]/8 done, .* left, ' smoke.log || { cat smoke.log; fail "no time left in the progress lines"; }
"$PY" "$SRC/tests/sweep/check_reader.py" smoke.h5
"$PY" "$SRC/analysis/plot_sweep.py" smoke.h5 plots
for f in sweep_energy.png sweep_cost_of_transport.png sweep_peak_torque_gait.png \
         sweep_peak_torque_transient.png; do
  [ -s "plots/$f" ] || fail "plots/$f missing"
done
[ -z "$(find plots -name '.*')" ] || fail "temporary files left in plots/"
echo "reader and heatmaps: ok"
