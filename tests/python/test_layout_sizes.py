"""The sizes L (legs) and J (joints) of a file's shapes come from the names it stores, not from
a robot of six legs: check_layout accepts a result of the paper scene whose per-leg and
per-joint datasets, /model/leg_names and /model/joint_names are cut to the first four legs
(and their twelve joints), written with h5py in a temporary folder, and reads its names
(hexdyn.leg_names, joint_names); it refuses, in one line naming the dataset, a copy whose
/contacts/force keeps six legs while /model/leg_names has four, and one whose /joints/torque
keeps 18 joints while /model/joint_names has 12. The same for a sweep (tests/sweep/schema.yaml)
cut to 12 joints, J from its /joint_names, and one whose /scenarios/peak_torque keeps 18. The
values of the cut files are not a robot's (the check is of the layout alone).
    test_layout_sizes.py HEXDYN_BINARY SOURCE_DIR      (PYTHONPATH: the build tree's python/)"""

import os
import subprocess
import tempfile

import h5py
import numpy as np

import hexdyn
from hexdyn import results as hr
from common import args, cli_run

HEXDYN, SRC = args()
PAPER = os.path.join(SRC, "configs", "paper.yaml")
# The paper scene shortened to one gait cycle on a coarse uniform grid: a small result.
SHORT = ("motion.cycle_durations=null", "motion.cycles=1", "motion.peak_speed=0.098",
         "motion.ramp_duration=0.8", "output.grid=uniform", "output.sample_step=0.05")
SWEEP = os.path.join(SRC, "tests", "sweep", "schema.yaml")  # 4 scenarios, 2 of them failed
# Attributes of the dimension-scale machinery: the copy makes its own (make_scale, attach).
SCALE_ATTRIBUTES = {"CLASS", "NAME", "REFERENCE_LIST", "DIMENSION_LIST"}


def dims_of(path, ds):
    """The dimension names of a dataset: its declaration's, or its own name for a scale (a
    sweep axis's datasets, declared by templates, have neither leg nor joint: ())."""
    if path in hr.DECLARED:
        return hr.DECLARED[path][0].dims
    if h5py.h5ds.is_scale(ds.id):
        return (path.rsplit("/", 1)[1],)
    return ()


def cut_copy(src_path, dst_path, legs, keep=()):
    """A copy of the file at `src_path` with every axis along `leg` cut to the indices
    `legs` and every axis along `joint` to those legs' joints (leg-major, three per leg), but
    the datasets of `keep`, copied whole; dimension scales and their attachments rebuilt."""
    joints = [3 * leg + j for leg in legs for j in range(3)]
    cut = {"leg": legs, "joint": joints}
    with h5py.File(src_path, "r") as src, h5py.File(dst_path, "w") as dst:
        datasets = {}

        def visit(name, obj):
            path = "/" + name
            target = dst.require_group(path) if isinstance(obj, h5py.Group) else None
            if isinstance(obj, h5py.Dataset):
                value = obj[()]
                if path not in keep:
                    for axis, dim in enumerate(dims_of(path, obj)):
                        if dim in cut:
                            value = np.take(value, cut[dim], axis=axis)
                target = dst.create_dataset(path, data=value, dtype=obj.dtype)
                datasets[path] = obj
            for key, v in obj.attrs.items():
                if key not in SCALE_ATTRIBUTES:
                    target.attrs[key] = v
        src.visititems(visit)
        for path, obj in datasets.items():
            if h5py.h5ds.is_scale(obj.id):
                dst[path].make_scale(path.rsplit("/", 1)[1])
        for path, obj in datasets.items():
            for axis, dim in enumerate(obj.dims):
                for scale in dim.values():
                    dst[path].dims[axis].attach_scale(dst[scale.name])


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
        assert hr.shape_sizes(result) == {"L": 6, "J": 18}, hr.shape_sizes(result)

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
