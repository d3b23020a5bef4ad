#!/usr/bin/python3
"""replay.early_contact: hold, its rule recomputed from the replay file
(docs/theory/replay.md#early-contact).

    test_early_contact.py HEXDYN SOURCE_DIR

Plans the paper scene, moves every riser of a copy of the result 3 cm further along y (a
staircase the plan does not know: its swing feet strike risers as well as treads) and replays
that copy with `replay.early_contact: hold`. Every stored sample's joint torque is
tau = feedforward + kp (q_plan - q) + kd (qd_ref - qd); the damping reference is recovered from
the stored torque, feedforward, tracking error and rates and the resolved gains in /meta, and
set beside the rule, with each foot's face found in numpy from the stored foot points and the
terrain polyline (the nearest segment, a second computation of the replay's contact geometry):

  - a foot the plan swings (/contacts/phase 0) that touches a tread (a horizontal face): its
    leg's reference is not the planned rates (the foot is held);
  - a foot the plan swings that touches a riser (a vertical face, steeper than atan mu_s): its
    leg's reference is the planned rates, to 1e-8 rad/s (a stubbed toe is not a touchdown);
  - every other leg: the planned rates.

It also checks that both kinds of contact occur, so that the test can fail.
"""
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

HEXDYN, SRC = sys.argv[1], sys.argv[2]
failures = []


def check(ok, what, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail else ''}")
    if not ok:
        failures.append(what)


def on_riser(ty, tz, y, z):
    """Whether the terrain segment nearest to (y, z) is vertical; None within 0.1 mm of a tie."""
    best = []
    for i in range(len(ty) - 1):
        a, b = np.array([ty[i], tz[i]]), np.array([ty[i + 1], tz[i + 1]])
        d = b - a
        if d @ d == 0.0:
            continue
        u = np.clip((np.array([y, z]) - a) @ d / (d @ d), 0.0, 1.0)
        best.append((np.hypot(*(np.array([y, z]) - (a + u * d))), abs(d[0]) < 1e-12))
    best.sort()
    if len(best) > 1 and best[1][0] - best[0][0] < 1e-4 and best[1][1] != best[0][1]:
        return None
    return best[0][1]


def main():
    with tempfile.TemporaryDirectory() as d:
        plan, moved, rep = (os.path.join(d, n) for n in ("plan.h5", "moved.h5", "replay.h5"))
        subprocess.run([HEXDYN, "run", os.path.join(SRC, "configs", "paper.yaml"), "-o", plan],
                       check=True, capture_output=True)
        shutil.copyfile(plan, moved)
        with h5py.File(moved, "r+") as f:
            y = f["terrain/y"][()]
            y[2:] += 0.03  # every riser 3 cm further: the first at 0.03 m
            f["terrain/y"][...] = y
        subprocess.run([HEXDYN, "replay", moved, "-o", rep, "--set", "replay.early_contact=hold"],
                       check=True, capture_output=True)
        with h5py.File(plan, "r") as p, h5py.File(rep, "r") as r:
            T = len(r["time"])
            phase = p["contacts/phase"][:T]
            qd_plan = p["joints/velocity"][:T]
            tau, ff = r["joints/torque"][()], r["joints/feedforward_torque"][()]
            err, qd = r["joints/tracking_error"][()], r["joints/velocity"][()]
            pen, foot = r["contacts/penetration"][()], r["feet/position"][()]
            ty, tz = r["terrain/y"][()], r["terrain/z"][()]
            scene = r["meta"].attrs["config_yaml"]
        kp, kd = gains(scene.decode() if isinstance(scene, bytes) else scene)
        qd_ref = (tau - ff + kp * err) / kd + qd
        joints = qd.shape[1] // phase.shape[1]
        held = stubbed = not_held = 0
        worst_stub = worst_other = 0.0
        for k in range(T):
            for leg in range(phase.shape[1]):
                cols = slice(joints * leg, joints * (leg + 1))
                gap = np.abs(qd_ref[k, cols] - qd_plan[k, cols]).max()
                swing, touching = phase[k, leg] == 0, pen[k, leg] > 0.0
                if swing and touching:
                    riser = on_riser(ty, tz, foot[k, leg, 1], foot[k, leg, 2])
                    if riser is None:
                        continue
                    if riser:
                        stubbed += 1
                        worst_stub = max(worst_stub, gap)
                    else:
                        held += 1
                        not_held += gap <= 1e-6
                else:
                    worst_other = max(worst_other, gap)
        check(held > 0 and stubbed > 0, "swing feet on treads and on risers",
              f"{held} samples on treads, {stubbed} on risers")
        check(not_held == 0, "a swing foot on a tread is held",
              f"{not_held} of {held} samples with the plan's rates")
        check(worst_stub < 1e-8, "a toe stubbed on a riser follows the plan's rates",
              f"largest difference {worst_stub:.3g} rad/s")
        check(worst_other < 1e-8, "every other leg follows the plan's rates",
              f"largest difference {worst_other:.3g} rad/s")
    if failures:
        print(f"{len(failures)} check(s) failed: {'; '.join(failures)}")
        return 1
    return 0


def gains(config_yaml):
    """replay.kp and replay.kd of the resolved scene (its replay: section, as hexdyn writes it)."""
    section = config_yaml[config_yaml.index("\nreplay:") + 1:]
    values = {}
    for line in section.splitlines()[1:]:
        if not line.startswith("  "):
            break
        key, _, value = line.strip().partition(":")
        values[key] = value.strip()
    return float(values["kp"]), float(values["kd"])


if __name__ == "__main__":
    sys.exit(main())
