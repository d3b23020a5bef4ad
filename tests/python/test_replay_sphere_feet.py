"""The replay of robots with sphere feet touches where the plan does (docs/theory/replay.md).

The replay builds the robot from the result's own /model/urdf, whose feet are links
"<leg>_foot", a sphere foot's with a sphere <collision> centred on it (model/urdf.cpp). Taken
as point feet, the spheres' centres would be the contact points and the robot would sink by
the radius into the terrain within its first tenth of a second. For ANYmal C on flat ground
(configs/robots/anymal_c_crawl_balanced.yaml, r = 0.03 m, replayed with a PD stiff enough
for its 52 kg) and Pexod on the paper's stairs (configs/robots/pexod_stairs.yaml, r = 0.025 m,
the default PD), each plan shortened to one gait cycle, checked:
  1. every foot of /model/urdf is a sphere: its radius r_l read from the XML with ElementTree;
  2. the plan's contact points (/feet/position) lie r_l from its spheres' centres
     (/feet/center), and at the first sample the replay's contact points are the plan's, to
     1e-9 m (a point foot at the centre would be r_l higher);
  3. the trunk's height stays within r/5 of the plan's over the whole replay (a point foot at
     the centre sinks by r: its replay ends a radius low);
  4. ANYmal C replayed with the paper robot's gains (10 N m/rad, 0.1 N m s/rad) falls, and the
     report adds one note naming replay.kp and docs/user/replay.md#gains, with a weight moment
     m g l between /model/total_mass g times the trunk's height above the spheres' centres at
     the first sample (its hips lie in the trunk's plane) and m g times 1 m; Pexod, which does
     not fall, gets no note;
  5. replayed with replay.kp and replay.kd auto (the defaults), the report states the gains
     and the weight moment, which lies in the bounds of 4: kp is 1.1 times it per rad for a
     robot whose moment exceeds 50 N m (ANYmal C, which then reaches the plan's end), else the
     paper robot's 10 N m/rad (Pexod), and kd is kp times 0.01 s; the replay file's
     config_yaml holds those numbers and the requests beside them (auto: replay: kp: auto).

    /usr/bin/python3 tests/python/test_replay_sphere_feet.py HEXDYN SOURCE_DIR
"""
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ElementTree

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import args, check, cli_run, exit_status, text  # noqa: E402

ONE_CYCLE = ("motion.cycles=1",)
ROBOTS = (("ANYmal C, flat", "anymal_c_crawl_balanced.yaml", ("replay.kp=400", "replay.kd=4")),
          ("Pexod, stairs", "pexod_stairs.yaml", ()))


def foot_radii(urdf_text, legs):
    """The sphere radius of each leg's foot link "<leg>_foot" in the URDF's XML (0: none)."""
    root = ElementTree.fromstring(urdf_text)
    radii = []
    for leg in legs:
        link = root.find(f"link[@name='{leg}_foot']")
        sphere = None if link is None else link.find("collision/geometry/sphere")
        radii.append(0.0 if sphere is None else float(sphere.get("radius")))
    return np.array(radii)


def study(binary, src, tmp, name, scene, replay_sets):
    plan, rep = os.path.join(tmp, "plan.h5"), os.path.join(tmp, "replay.h5")
    for f in (plan, rep):
        if os.path.exists(f):
            os.remove(f)
    status, err = cli_run(binary, os.path.join(src, "configs", "robots", scene), plan,
                          ONE_CYCLE)
    assert status == 0, err
    cmd = [binary, "replay", plan, "-o", rep]
    for s in replay_sets:
        cmd += ["--set", s]
    p = subprocess.run(cmd, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    with h5py.File(plan, "r") as f, h5py.File(rep, "r") as g:
        legs = [text(n) for n in f["/model/leg_names"][()]]
        r = foot_radii(text(f["/model/urdf"][()]), legs)
        check(bool(np.all(r > 0)), f"{name}: every foot of /model/urdf is a sphere",
              str(r.tolist()))
        plan_feet, centres = f["/feet/position"][0], f["/feet/center"][0]
        rep_feet = g["/feet/position"][0]
        z_err = g["/base/position"][:, 2] - f["/base/position"][:len(g["/time"]), 2]
        message = text(g["/replay/message"][()])
    arm = np.linalg.norm(centres - plan_feet, axis=1)
    check(float(np.max(np.abs(arm - r))) <= 1e-9, f"{name}: the plan's feet lie r from the centres",
          str(arm.tolist()))
    worst = float(np.max(np.abs(rep_feet - plan_feet)))
    check(worst <= 1e-9, f"{name}: the replay's first contact points are the plan's",
          f"worst {worst:.3g} m")
    sink = float(np.max(np.abs(z_err)))
    check(sink <= r.min() / 5, f"{name}: the trunk's height within r/5 of the plan's",
          f"worst {sink * 1e3:.2f} mm, r {r.min() * 1e3:.0f} mm; {message or 'reached the end'}")
    return plan


def replay_with(binary, tmp, plan, file_name, sets):
    """`hexdyn replay plan -o tmp/file_name --set ...` into a fresh file: (its path, the run)."""
    rep = os.path.join(tmp, file_name)
    if os.path.exists(rep):
        os.remove(rep)
    cmd = [binary, "replay", plan, "-o", rep]
    for x in sets:
        cmd += ["--set", x]
    p = subprocess.run(cmd, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return rep, p


def check_gain_note(binary, tmp, plan, name, heavy):
    """Check 4: the note after a fall with the paper robot's gains."""
    _, p = replay_with(binary, tmp, plan, "weak.h5", ("replay.kp=10", "replay.kd=0.1"))
    notes = [ln for ln in p.stderr.splitlines() if ln.startswith("hexdyn: replay: note:")]
    fell = "the robot fell" in p.stderr
    if not heavy:
        check(not notes, f"{name}: no note with the paper robot's gains", "; ".join(notes))
        return
    check(fell and len(notes) == 1 and "replay.kp 10 N m/rad" in notes[0] and
          "docs/user/replay.md#gains" in notes[0], f"{name}: falls with the note",
          notes[0] if notes else p.stderr[-400:])
    if len(notes) != 1:
        return
    with h5py.File(plan, "r") as f:
        mass = float(f["/model/total_mass"][()])
        # ANYmal's hips lie in its trunk's plane: standing, each leg reaches at least the trunk's
        # height above its sphere's centre.
        depth = float(f["/base/position"][0, 2] - np.max(f["/feet/center"][0, :, 2]))
    moment = float(re.search(r"weight moment m g l of ([0-9.eE+-]+) N m", notes[0]).group(1))
    check(mass * 9.81 * depth <= moment <= mass * 9.81 * 1.0,
          f"{name}: the note's weight moment is m g times a reach", f"{moment} N m, m {mass} kg, "
          f"standing depth {depth:.3f} m")


def standing_depth(plan):
    """/model/total_mass and the trunk's height above the spheres' centres at the first sample."""
    with h5py.File(plan, "r") as f:
        mass = float(f["/model/total_mass"][()])
        depth = float(f["/base/position"][0, 2] - np.max(f["/feet/center"][0, :, 2]))
    return mass, depth


def check_auto_gains(binary, tmp, plan, name, heavy):
    """Check 5: the gains replay.kp: auto and replay.kd: auto resolve to for the robot."""
    rep, p = replay_with(binary, tmp, plan, "auto.h5", ("replay.kp=auto", "replay.kd=auto"))
    number = r"([0-9.eE+-]+)"
    m = re.search(rf"joint PD kp {number} N m/rad, kd {number} N m s/rad \(replay.kp, replay.kd: "
                  rf"auto, auto; weight moment {number} N m\)", p.stderr)
    check(m is not None, f"{name}: the report states the auto gains", p.stderr[-400:])
    if m is None:
        return
    kp, kd, moment = (float(x) for x in m.groups())  # as printed, to 6 digits
    mass, depth = standing_depth(plan)
    check(mass * 9.81 * depth <= moment <= mass * 9.81 * 1.0,
          f"{name}: the weight moment is m g times a reach", f"{moment} N m, m {mass} kg")
    with h5py.File(rep, "r") as f:
        config = text(f["/meta"].attrs["config_yaml"])
    replay = re.search(rf"\nreplay:\n  kp: {number}\n  kd: {number}\n", config)
    requests = re.search(r"\nauto:\n(?:  .*\n)*  replay:\n    kp: auto\n    kd: auto\n", config)
    check(replay is not None and requests is not None,
          f"{name}: the replay file holds the gains used and the requests", config[-600:])
    if replay is None:
        return
    kp_file, kd_file = float(replay.group(1)), float(replay.group(2))
    expected = 1.1 * moment if moment > 50.0 else 10.0
    check(heavy == (moment > 50.0) and abs(kp_file - expected) <= 1e-5 * expected and
          abs(kp - kp_file) <= 1e-5 * kp_file and abs(kd_file - 0.01 * kp_file) <= 1e-12 * kp_file,
          f"{name}: kp and kd follow the weight moment",
          f"kp {kp_file}, kd {kd_file}, moment {moment}")
    if heavy:
        check("reached the plan's end" in p.stderr, f"{name}: reaches the end with them",
              p.stderr[-400:])


def main():
    binary, src = args()
    with tempfile.TemporaryDirectory() as tmp:
        for name, scene, replay_sets in ROBOTS:
            plan = study(binary, src, tmp, name, scene, replay_sets)
            check_gain_note(binary, tmp, plan, name, heavy=name.startswith("ANYmal"))
            check_auto_gains(binary, tmp, plan, name, heavy=name.startswith("ANYmal"))
    return exit_status()


if __name__ == "__main__":
    sys.exit(main())
