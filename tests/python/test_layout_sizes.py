"""The sizes L (legs) and J (joints) of a file's shapes come from the names it stores, not from
a robot of six legs: check_layout accepts a result of the paper scene whose per-leg and
per-joint datasets, /model/leg_names and /model/joint_names are cut to the first four legs
(and their twelve joints), written with h5py in a temporary folder (tests/python/robot_cut.py),
and reads its names (hexdyn.leg_names, joint_names; the paper result's counts are those of the
robot its /model/urdf describes); it refuses, in one line naming the dataset, a copy whose
/contacts/force keeps every leg while /model/leg_names has four, and one whose /joints/torque
keeps every joint while /model/joint_names has 12. The same for a sweep (tests/sweep/schema.yaml)
cut to 12 joints, J from its /joint_names, and one whose /scenarios/peak_torque keeps all. The
values of the cut files are not a robot's (the check is of the layout alone).
    test_layout_sizes.py HEXDYN_BINARY SOURCE_DIR      (PYTHONPATH: the build tree's python/)"""

import os
import subprocess
import tempfile
import xml.etree.ElementTree as ET

import h5py

import hexdyn
from hexdyn import results as hr
from common import args, cli_run
from robot_cut import cut_copy

HEXDYN, SRC = args()
PAPER = os.path.join(SRC, "configs", "paper.yaml")
# The paper scene shortened to one gait cycle on a coarse uniform grid: a small result.
SHORT = ("motion.cycle_durations=null", "motion.cycles=1", "motion.peak_speed=0.098",
         "motion.ramp_duration=0.8", "output.grid=uniform", "output.sample_step=0.05")
SWEEP = os.path.join(SRC, "tests", "sweep", "schema.yaml")  # 4 scenarios, 2 of them failed


def urdf_sizes(path):
    """{"L": foot links, "J": moving joints} of the robot /model/urdf describes (xml.etree)."""
    with h5py.File(path, "r") as f:
        root = ET.fromstring(hexdyn.decode_text(f["model/urdf"][()]))
    feet = [link for link in root.iter("link") if link.get("name").endswith("_foot")]
    moving = [j for j in root.iter("joint") if j.get("type") in ("revolute", "continuous",
                                                                  "prismatic")]
    return {"L": len(feet), "J": len(moving)}


def refusal(path):
    """The message check_layout raises for `path` (a hexdyn.IoError, an OSError)."""
    try:
        hexdyn.check_layout(path)
    except OSError as e:
        return str(e)
    raise AssertionError(f"check_layout accepted {path}")


def main():
    with tempfile.TemporaryDirectory() as d:
        result = os.path.join(d, "short.h5")
        status, err = cli_run(HEXDYN, PAPER, result, SHORT)
        assert status == 0, err
        assert hexdyn.check_layout(result) == hr.RESULT_SCHEMA
        assert hr.shape_sizes(result) == urdf_sizes(result), hr.shape_sizes(result)

        # Four legs, twelve joints: the shapes follow the names.
        four = os.path.join(d, "four_legs.h5")
        cut_copy(result, four, [0, 1, 2, 3])
        assert hexdyn.check_layout(four) == hr.RESULT_SCHEMA
        assert hexdyn.leg_names(four) == ("L1", "L2", "L3", "L4"), hexdyn.leg_names(four)
        assert len(hexdyn.joint_names(four)) == 12 and hexdyn.joint_names(four)[-1] == "L4_tibia"
        res = hexdyn.open_result(four)
        T = len(res["/time"])
        assert hr.shape_sizes(res) == {"L": 4, "J": 12}
        assert res.shapes["/contacts/force"] == (T, 4, 3), res.shapes["/contacts/force"]
        assert res.shapes["/joints/torque"] == (T, 12), res.shapes["/joints/torque"]
        for path, spec in hr.RESULT_LAYOUT.items():
            if path in res.shapes:
                want = hr.expected_shape(spec[0].shape, T, res.shapes.get("/impacts/leg",
                                                                          (None,))[0],
                                         res.shapes.get("/solver/messages", (None,))[0],
                                         Y=res.shapes.get("/gait/cycle_start", (None,))[0],
                                         K=res.shapes.get("/terrain/y", (None,))[0],
                                         **hr.shape_sizes(res))
                assert res.shapes[path] == want, (path, res.shapes[path], want)

        # A sweep of a robot of 12 joints: J from /joint_names.
        sweep = os.path.join(d, "sweep.h5")
        status = subprocess.run([HEXDYN, "sweep", SWEEP, "-o", sweep], capture_output=True,
                                text=True)
        assert status.returncode == 0, status.stderr
        cut = os.path.join(d, "sweep_12.h5")
        cut_copy(sweep, cut, [0, 1, 2, 3])
        assert hexdyn.check_layout(cut) == hr.SWEEP_SCHEMA
        sw = hexdyn.open_sweep(cut)
        assert len(hexdyn.joint_names(sw)) == 12 and sw.table["peak_torque"].shape == (4, 12)

        # A per-leg and a per-joint dataset that disagree with the names: one line each,
        # naming the dataset and where L or J came from.
        for source, keep, size in (
                (result, "/contacts/force", "L = 4 from /model/leg_names"),
                (result, "/joints/torque", "J = 12 from /model/joint_names"),
                (sweep, "/scenarios/peak_torque", "J = 12 from /joint_names")):
            bad = os.path.join(d, "bad.h5")
            cut_copy(source, bad, [0, 1, 2, 3], keep=(keep,))
            message = refusal(bad)
            assert "\n" not in message, message
            assert f"dataset {keep} is float64" in message and size in message, message
            os.remove(bad)
    print("layout sizes: OK")


if __name__ == "__main__":
    main()
