#!/usr/bin/env bash
# A cases axis over two URDF robots with different forward axes
# (configs/sweeps/robots_cases.yaml, run from another folder: its URDF paths are relative to
# the sweep file): every scenario is computed; a kept run equals `hexdyn run` of the base
# scene with that case's keys as --set overrides, bit for bit; the file follows the
# declared layout and xarray opens it (h5netcdf and netcdf4) with the case labels as the
# axis's coordinate; a case that is not valid on the base scene stops the sweep before
# any work with one line naming it.
source "$(dirname "$0")/common.sh"
sweep="$SRC/configs/sweeps/robots_cases.yaml"
"$HEXDYN" validate "$sweep" > validate.log || { cat validate.log; fail "validate"; }
grep -q "4 scenarios over robot (2) terrain.riser_height (2)" validate.log ||
  { cat validate.log; fail "validate: axes"; }
mpi 2 sweep "$sweep" -o cases.h5 --keep-runs 2> cases.log || { cat cases.log; fail "sweep"; }

# Scenario 000003: the Kraby case (index 1) at the 0.04 m riser (index 1).
"$HEXDYN" run "$SRC/configs/robots/phantomx_mark4_stairs.yaml" -o run3.h5 \
  --set robot.urdf="$SRC/robots/kraby.urdf" --set robot.forward_axis=+y --set gait.stroke=0.025 --set gait.foothold_margin=0.015 \
  --set terrain.riser_height=0.04 --set motion.cycles=null --set motion.travel.treads=2 2> run3.log || { cat run3.log; fail "run"; }
compare --result run3.h5 cases.h5:/runs/000003
"$PY" "$SRC/tests/sweep/check_schema.py" --sweep cases.h5

"$PY" - cases.h5 "$SRC" <<'PY'
import os, sys
import numpy as np
import xarray as xr
from hexdyn import results as hr
path, src = sys.argv[1], sys.argv[2]
sw = hr.open_sweep(path)
assert sw.status_names == ["ok"] * 4, (sw.status_names, sw.table["message"])
robot = sw.axes[0]
assert robot.key == "robot" and list(robot.labels) == ["phantomx_mark4", "kraby"], robot
assert list(robot.cases) == ["robot.urdf", "robot.forward_axis", "gait.stroke",
                             "gait.foothold_margin"], robot.cases
assert robot.cases["robot.urdf"] == [os.path.join(src, "robots", n)
                                     for n in ("phantomx_mark4.urdf", "kraby.urdf")]
assert list(robot.cases["robot.forward_axis"]) == ["+x", "+y"]
assert np.array_equal(robot.cases["gait.stroke"], [0.0625, 0.025])
# Both robots climb the two treads of the sweep's motion.travel, whatever their stroke.
assert np.allclose(sw.table["distance"], 2 * np.hypot(0.25, sw.table["axis_1"]), rtol=0, atol=1e-9)
s3 = sw.scenario(3)
assert s3["robot"] == "kraby" and s3["robot.forward_axis"] == "+y" and s3["terrain.riser_height"] == 0.04
# Each kept run is the robot of its case (the URDF's total mass, not the base robot's).
masses = [float(sw.run(i)["/model/total_mass"]) for i in range(4)]
assert masses[0] == masses[1] and masses[2] == masses[3] and masses[0] != masses[2], masses
ds = sw.to_xarray()
assert list(ds["robot"].values) == ["phantomx_mark4", "kraby"]
assert ds["robot.forward_axis"].sel(robot="kraby") == "+y"
assert float(ds.energy.sel(robot="kraby", **{"terrain.riser_height": 0.04})) == sw.table["energy"][3]
df = sw.to_dataframe()
assert list(df["robot"]) == ["phantomx_mark4"] * 2 + ["kraby"] * 2 and list(df["gait.stroke"])[2] == 0.025
for engine in ("h5netcdf", "netcdf4"):
    with xr.open_dataset(path, engine=engine) as f:
        assert list(f["robot"].values) == ["phantomx_mark4", "kraby"], engine
        assert list(f["robot_key"].values) == list(robot.cases), engine
    with xr.open_dataset(path, engine=engine, group="axes/0") as g:
        assert g["case_values"].dims == ("robot", "robot_key"), (engine, g["case_values"].dims)
        assert g["case_values"].values[1, 1] == "+y", engine
        # The group alone carries its coordinates: the case labels and the keys they set.
        assert list(g["robot"].values) == ["phantomx_mark4", "kraby"], engine
        assert list(g["robot_key"].values) == list(robot.cases), engine
print("cases: reader ok")
PY

# A case whose robot cannot be read with its keys: one line before any work, no output.
sed -e 's#robot.forward_axis: +y#robot.forward_axis: +x#' \
    -e "s#\.\./\.\./robots/#$SRC/robots/#g" -e "s#base: \.\./#base: $SRC/configs/#" \
    "$sweep" > bad.yaml
set +e
"$HEXDYN" sweep bad.yaml -o bad.h5 2> bad.log
status=$?
"$HEXDYN" validate bad.yaml > /dev/null 2> validate_bad.log
vstatus=$?
set -e
[ "$status" = 2 ] && [ "$vstatus" = 2 ] || { cat bad.log validate_bad.log; fail "bad case: exit $status, validate $vstatus"; }
[ "$(wc -l < bad.log)" = 1 ] || { cat bad.log; fail "bad case: not one line"; }
grep -q "bad.yaml: axes\[0\].cases\[1\] (kraby: robot.urdf=$SRC/robots/kraby.urdf, robot.forward_axis=+x, gait.stroke=0.025, gait.foothold_margin=0.015): .*set robot.forward_axis" bad.log ||
  { cat bad.log; fail "bad case: message"; }
[ ! -e bad.h5 ] && [ ! -e bad.h5.checkpoint ] || fail "bad case: output written"
echo "cases: ok"
