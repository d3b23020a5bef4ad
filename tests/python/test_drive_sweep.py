"""The drive train's metrics of a sweep (docs/theory/drive-train.md, io/schema.hpp /scenarios),
checked against each kept run (--keep-runs):

  1. A cases axis over three servos of the table on the paper scene (MX-64, MX-106 and
     AX-12A, the one of them with a continuous rating; a thermal window shorter than the
     run; regenerating femurs): each kept run's drive-train datasets recompute
     (tests/python/drive_check.py, 1e-9); /scenarios/energy_electrical,
     energy_copper_loss, energy_friction_loss, energy_regenerated and
     cost_of_transport_electrical are the run's /energy values; peak_electrical_power the
     largest /power/electrical_total; peak_drive_torque_gait and _transient the largest
     |/joints/drive_torque| over the samples where no leg is in its touchdown transient
     (/contacts/phase 1) and over those where one is, computed here; peak_torque_gait and
     _transient the same of /joints/torque; drive_torque_window_rms the run's
     /joints/drive_torque_window_rms; thermal_load the largest windowed RMS over the
     continuous_torque of /meta actuators.joints, NaN where no joint has one.
  2. A sweep without actuators (two riser heights): every drive-train metric is NaN, the
     kept runs hold no drive-train dataset, and peak_torque_gait and _transient split
     /joints/torque as above.

    test_drive_sweep.py HEXDYN_BINARY SOURCE_DIR      (PYTHONPATH: the build tree's python/)
"""

import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import args, text  # noqa: E402
import drive_check  # noqa: E402

HEXDYN, SRC = args()
PAPER = os.path.join(SRC, "configs", "paper.yaml")
IMPACT = 1  # /contacts/phase of a leg in its touchdown transient (docs/user/output.md)
DRIVE_METRICS = ("energy_electrical", "energy_copper_loss", "energy_friction_loss",
                 "energy_regenerated", "cost_of_transport_electrical", "peak_electrical_power",
                 "peak_drive_torque_gait", "peak_drive_torque_transient",
                 "drive_torque_window_rms", "thermal_load")
SAME_AS_RUN = {"energy_electrical": "/energy/electrical",
               "energy_copper_loss": "/energy/copper_loss",
               "energy_friction_loss": "/energy/friction_loss",
               "energy_regenerated": "/energy/regenerated",
               "cost_of_transport_electrical": "/energy/cost_of_transport_electrical",
               "drive_torque_window_rms": "/joints/drive_torque_window_rms"}
SERVOS = ("dynamixel_mx64", "dynamixel_mx106", "dynamixel_ax12a")


def write_yaml(path, body):
    with open(path, "w") as f:
        yaml.safe_dump(body, f, sort_keys=False)
    return path


def sweep(d, name, body):
    """`hexdyn sweep` (one rank) of the sweep file `body` with --keep-runs: the file's
    /scenarios columns and kept runs {id: result as drive_check.read_result}."""
    spec = write_yaml(os.path.join(d, f"{name}.yaml"), body)
    out = os.path.join(d, f"{name}.h5")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run([HEXDYN, "sweep", spec, "-o", out, "--keep-runs"], capture_output=True,
                       text=True, env=env)
    assert p.returncode == 0, f"{name}: exit {p.returncode}: {p.stderr}"
    with h5py.File(out, "r") as f:
        table = {k: v[()] for k, v in f["scenarios"].items() if isinstance(v, h5py.Dataset)}
        ids = [text(i) for i in table["id"]]
        runs = {i: drive_check.read_result(f["runs"][i]) for i in ids}
    assert np.all(table["status"] == 0), (table["status"], [text(m) for m in table["message"]])
    return table, ids, runs


def split_peaks(x, phase):
    """(max |x| over the samples with no leg in its transient, max over those with one),
    per joint; NaN where there is no such sample."""
    transient = np.any(phase == IMPACT, axis=1)
    peaks = []
    for rows in (~transient, transient):
        peaks.append(np.max(np.abs(x[rows]), axis=0) if np.any(rows)
                     else np.full(x.shape[1], np.nan))
    return peaks, int(np.sum(transient))


def same(name, got, want):
    assert np.array_equal(np.asarray(got), np.asarray(want), equal_nan=True), \
        f"{name}: sweep {got!r}, run {want!r}"


def check_torque_split(table, i, r, label):
    (gait, transient), n = split_peaks(r["/joints/torque"], r["/contacts/phase"])
    assert n > 0, f"{label}: no sample in a touchdown transient: the split is not tested"
    same(f"{label} peak_torque_gait", table["peak_torque_gait"][i], gait)
    same(f"{label} peak_torque_transient", table["peak_torque_transient"][i], transient)
    assert not np.array_equal(gait, transient)
    return n


def servo_sweep(d):
    base = write_yaml(os.path.join(d, "drive_base.yaml"), {
        "inherit": PAPER,
        "actuators": {"default": {"model": SERVOS[0], "thermal_window": 1.0},
                      "femur": {"regeneration": 0.5}}})
    table, ids, runs = sweep(d, "servos", {
        "name": "servos", "base": base,
        "axes": [{"name": "servo",
                  "cases": [{"label": s.split("_")[1], "actuators.default.model": s}
                            for s in SERVOS]}]})
    assert len(ids) == len(SERVOS)
    rated = []
    for i, sid in enumerate(ids):
        r = runs[sid]
        label = f"scenario {sid} ({SERVOS[i]})"
        assert r["config"]["actuators"]["joints"]["L1_coxa"]["model"] == SERVOS[i]
        drive_check.check(r, label)
        for metric, dataset in SAME_AS_RUN.items():
            same(f"{label} {metric}", table[metric][i], r[dataset])
        same(f"{label} peak_electrical_power", table["peak_electrical_power"][i],
             np.max(r["/power/electrical_total"]))
        (gait, transient), _ = split_peaks(r["/joints/drive_torque"], r["/contacts/phase"])
        same(f"{label} peak_drive_torque_gait", table["peak_drive_torque_gait"][i], gait)
        same(f"{label} peak_drive_torque_transient", table["peak_drive_torque_transient"][i],
             transient)
        check_torque_split(table, i, r, label)
        continuous = drive_check.parameters(r)["continuous_torque"]
        has = np.isfinite(continuous)
        load = (np.max(r["/joints/drive_torque_window_rms"][has] / continuous[has])
                if np.any(has) else np.nan)
        same(f"{label} thermal_load", table["thermal_load"][i], load)
        rated.append(bool(np.any(has)))
        print(f"{label}: E_el {float(r['/energy/electrical']):.4g} J, thermal_load {load:.4g}")
    assert any(rated) and not all(rated), f"rated servos {rated}: both cases wanted"
    # Different servos, different results: the cases axis took effect.
    assert len(set(float(e) for e in table["energy_electrical"])) == len(SERVOS)
    # The energy breakdown's columns are told apart: different in every scenario, copper
    # loss and regeneration positive, friction positive for the servos with friction in the
    # table (MX-64, MX-106; the AX-12A has none).
    losses = np.array([table[m] for m in ("energy_copper_loss", "energy_friction_loss",
                                          "energy_regenerated")])
    assert np.all(losses[[0, 2]] > 0) and np.all(losses[1, :2] > 0), losses
    assert all(len(set(col)) == 3 for col in losses.T), losses


def plain_sweep(d):
    table, ids, runs = sweep(d, "plain", {
        "name": "plain", "base": PAPER,
        "axes": [{"key": "terrain.riser_height", "values": [0.04, 0.05]}]})
    for metric in DRIVE_METRICS + THERMAL_METRICS:
        assert np.all(np.isnan(table[metric])), f"without actuators: {metric} {table[metric]}"
    for i, sid in enumerate(ids):
        r = runs[sid]
        present = [k for k in drive_check.DRIVE_DATASETS if k in r]
        assert not present, f"scenario {sid} without actuators: {present}"
        n = check_torque_split(table, i, r, f"plain scenario {sid}")
        print(f"plain scenario {sid}: drive metrics NaN, {n} transient samples")


THERMAL_METRICS = ("peak_winding_temperature", "time_to_winding_limit",
                   "peak_winding_temperature_max", "time_to_winding_limit_min")


def thermal_sweep(d):
    """Brushless modules with the thermal model: the sweep's thermal columns are the kept
    runs' /thermal/* (per joint, and the largest peak and the earliest time over them); a
    limit just above the ambient is reached (a finite time), the table's is not (+inf)."""
    base = write_yaml(os.path.join(d, "thermal_base.yaml"), {
        "inherit": PAPER, "actuators": {"default": {"model": "mini_cheetah_hip"}}})
    table, ids, runs = sweep(d, "thermal", {
        "name": "thermal", "base": base,
        "axes": [{"name": "limit", "cases": [
            {"label": "table", "actuators.default.winding_temperature_limit": 120},
            {"label": "low", "actuators.default.winding_temperature_limit": 25.001}]}]})
    for i, sid in enumerate(ids):
        r = runs[sid]
        label = f"thermal scenario {sid}"
        drive_check.check(r, label)
        drive_check.check_thermal(r, label)
        same(f"{label} peak_winding_temperature", table["peak_winding_temperature"][i],
             r["/thermal/peak_winding_temperature"])
        same(f"{label} time_to_winding_limit", table["time_to_winding_limit"][i],
             r["/thermal/time_to_limit"])
        same(f"{label} peak_winding_temperature_max", table["peak_winding_temperature_max"][i],
             r["/thermal/peak"])
        same(f"{label} time_to_winding_limit_min", table["time_to_winding_limit_min"][i],
             r["/thermal/first_time_to_limit"])
        print(f"{label}: peak {float(r['/thermal/peak']):.4g} degC, first time to the limit "
              f"{float(r['/thermal/first_time_to_limit']):.4g} s")
    assert table["time_to_winding_limit_min"][0] == np.inf
    assert np.isfinite(table["time_to_winding_limit_min"][1])


with tempfile.TemporaryDirectory() as tmp:
    for part in (servo_sweep, plain_sweep, thermal_sweep):
        work = os.path.join(tmp, part.__name__)
        os.mkdir(work)
        part(work)
print("drive train in sweeps: ok")
