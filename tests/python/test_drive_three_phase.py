"""Three-phase actuators and the thermal model through `hexdyn run`
(docs/theory/drive-train.md#three-phase-motors, #voltage-limit, #thermal-model), checked
against a second computation in numpy and scipy (tests/python/drive_check.py):

  a. Solo-12 on flat ground with the ODRI module of the servo table
     (configs/robots/solo12_flat_odri.yaml: amplitude-invariant winding, two gear stages,
     the thermal model) on a 4 V bus, its winding limit set just above the ambient so that some joints
     reach it and a joint given a higher limit does not: every drive-train dataset from
     /joints/torque, velocity, acceleration and /meta actuators.joints to 1e-9 (the copper
     loss 3/2 R I², the voltage bounds on both sides, which differ at speed), and the
     winding and housing temperatures by scipy's matrix exponential of the network
     augmented by the loss (exact for the loss linear between samples) to 1e-9, the peak
     no lower than the samples, the time to the limit where the winding meets it.
  b. The same scene stated power-invariant (k_t / √(3/2), the same R): the same drive
     torques' bounds, copper loss, electrical energy and temperatures to 1e-9.
  c. Solo-12's DC scene (configs/robots/solo12_flat.yaml) writes no /thermal group and no
     winding in /meta, and its lower bound is −its bound.

    test_drive_three_phase.py HEXDYN_BINARY SOURCE_DIR      (PYTHONPATH: the build tree's python/)
"""

import os
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import args, cli_run  # noqa: E402
import drive_check  # noqa: E402

HEXDYN, SRC = args()
ODRI = os.path.join(SRC, "configs", "robots", "solo12_flat_odri.yaml")
DC = os.path.join(SRC, "configs", "robots", "solo12_flat.yaml")
# Short runs (two cycles) on a 4 V bus: the voltage range (stall 1.9 N m, no load 13 rad/s at
# the joint) binds below the 2.5 N m peak, and its two sides differ at the joints' speeds.
SHORT = ["motion.cycles=2", "actuators.default.voltage=4"]


def run(d, scene, name, sets=()):
    out = os.path.join(d, name)
    rc, err = cli_run(HEXDYN, scene, out, list(SHORT) + list(sets))
    assert rc == 0, f"{scene} {sets}: exit {rc}: {err}"
    return out


def part_a(d):
    path = run(d, ODRI, "odri.h5", ["actuators.default.winding_temperature_limit=25.5",
                                    "actuators.joints.FR_KFE.winding_temperature_limit=200"])
    r = drive_check.read_file(path)
    counts = drive_check.check(r, "ODRI three-phase")
    p = drive_check.parameters(r)
    assert set(p["winding"]) == {"three_phase_amplitude"}, set(p["winding"])
    up, lo = r["/joints/drive_torque_limit"], r["/joints/drive_torque_lower_limit"]
    asymmetric = int(np.sum(np.abs(up + lo) > 1e-6 * np.abs(up)))
    print(f"a: {counts}; samples × joints with lower ≠ −upper: {asymmetric}")
    assert asymmetric > 0, "no sample where the voltage range is asymmetric: the check is vacuous"
    joints, reached = drive_check.check_thermal(r, "ODRI thermal")
    print(f"a: thermal model on {joints} joints, {reached} reach their limit")
    assert joints == len(r["joints"]) and 0 < reached < joints, (joints, reached)
    k = r["joints"].index("FR_KFE")
    assert not r["/thermal/limit_reached"][k] and r["/thermal/time_to_limit"][k] == np.inf
    return r


def part_b(d, amp):
    kt = 0.025 / np.sqrt(1.5)
    path = run(d, ODRI, "odri_power.h5", ["actuators.default.winding=three_phase_power",
                                          f"actuators.default.torque_constant={kt!r}"])
    r = drive_check.read_file(path)
    drive_check.check(r, "ODRI power-invariant")
    drive_check.check_thermal(r, "ODRI power-invariant thermal")
    for name in ("/joints/drive_torque_limit", "/joints/drive_torque_lower_limit",
                 "/energy/copper_loss", "/energy/electrical", "/thermal/winding_temperature",
                 "/thermal/peak_winding_temperature"):
        a, b = np.asarray(amp[name], float), np.asarray(r[name], float)
        scale = np.max(np.abs(a))
        assert np.all(np.abs(a - b) <= 1e-9 * scale), f"{name}: amplitude and power differ"
    # The current of the power-invariant statement is √(3/2) times the amplitude's.
    ratio = r["/joints/current"] / np.where(amp["/joints/current"] == 0, 1, amp["/joints/current"])
    nonzero = amp["/joints/current"] != 0
    assert np.allclose(ratio[nonzero], np.sqrt(1.5), rtol=1e-9, atol=0)
    print("b: power-invariant statement gives the same bounds, losses and temperatures")


def part_c(d):
    path = run(d, DC, "dc.h5")
    with h5py.File(path, "r") as f:
        assert "thermal" not in f, "a DC scene without thermal keys wrote /thermal"
        up, lo = f["joints/drive_torque_limit"][()], f["joints/drive_torque_lower_limit"][()]
    assert np.array_equal(lo, -up)
    r = drive_check.read_file(path)
    assert all("winding" not in v for v in r["config"]["actuators"]["joints"].values())
    drive_check.check(r, "Solo-12 DC")
    print("c: the DC scene has no thermal datasets and symmetric bounds")


def main():
    with tempfile.TemporaryDirectory() as d:
        amp = part_a(d)
        part_b(d, amp)
        part_c(d)
    print("ok")


if __name__ == "__main__":
    main()
