"""The replay of a robot other than the hexapod (docs/theory/replay.md), against DART 6.12.

Solo-12 (configs/robots/solo12_flat.yaml: four legs of three joints) is run with `hexdyn run`
from a copy of its scene and of its URDF, then replayed with `hexdyn replay`. Checked:
  1. the replay file has the run's sizes: one column per joint and one row per leg of the
     result (/model/joint_names, /model/leg_names), /model/leg_joint_counts as the result's;
  2. each stored sample is the forward dynamics of its own state: at every fifth sample,
     DART's forward dynamics of the stored state (the result's /model/urdf on a free trunk,
     tests/python/test_drive_dart.py DartRobot) under the stored /joints/torque and
     /contacts/force gives the stored accelerations to TOLERANCE relative to max(1, |a|);
     the feet carry load in most samples;
  3. the robot is the result's own: after the copied URDF's masses are multiplied by 4, the
     replay prints one warning line naming that URDF and writes every dataset as before, bit
     for bit; DART given the result's /model/urdf so edited misses the stored accelerations
     by more than 100 TOLERANCE (the check of 2 can fail);
  4. a result whose /model/leg_joint_counts is edited (4, 2, 3, 3) is refused in one line
     naming the dataset, and writes nothing.

    /usr/bin/python3 tests/python/test_replay_robots.py HEXDYN SOURCE_DIR
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import args, cli_run, text  # noqa: E402
from test_drive_dart import DartRobot, dart, difference  # noqa: E402

SCENE = os.path.join("configs", "robots", "solo12_flat.yaml")
TOLERANCE = 1e-10  # max |a_DART - a_hexdyn| over max(1, |a_hexdyn|), per sample
STATE = ("/base/position", "/base/orientation", "/base/linear_velocity", "/base/angular_velocity",
         "/base/linear_acceleration", "/base/angular_acceleration", "/joints/position",
         "/joints/velocity", "/joints/acceleration", "/joints/torque", "/contacts/force")


def copy_scene(src, tmp):
    """The scene and its URDF copied to tmp, the scene naming the copy; returns both paths."""
    with open(os.path.join(src, SCENE), encoding="utf-8") as f:
        scene_text = f.read()
    urdf = re.search(r"^\s*urdf:\s*(\S+)", scene_text, re.M).group(1)
    urdf_copy = os.path.join(tmp, os.path.basename(urdf))
    shutil.copyfile(os.path.normpath(os.path.join(src, os.path.dirname(SCENE), urdf)), urdf_copy)
    scene = os.path.join(tmp, "scene.yaml")
    with open(scene, "w", encoding="utf-8") as f:
        f.write(scene_text.replace(urdf, os.path.basename(urdf), 1))
    return scene, urdf_copy


def heavier(urdf_text):
    """A URDF's text with every <mass value> multiplied by 4."""
    return re.sub(r'mass value="([0-9.eE+-]+)"',
                  lambda m: f'mass value="{4 * float(m.group(1))!r}"', urdf_text)


def replay(binary, result, out):
    """`hexdyn replay result -o out`: its datasets {path: value} and its stderr."""
    import h5py
    p = subprocess.run([binary, "replay", result, "-o", out], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    values = {}
    with h5py.File(out, "r") as f:
        f.visititems(lambda name, obj: values.__setitem__("/" + name, obj[()])
                     if isinstance(obj, h5py.Dataset) else None)
    return values, p.stderr


def robot_of(result):
    """The robot the result describes (its /model/*), as DartRobot takes it."""
    import h5py
    with h5py.File(result, "r") as f:
        return {"urdf": text(f["/model/urdf"][()]),
                "joints": [text(n) for n in f["/model/joint_names"][()]],
                "legs": [text(n) for n in f["/model/leg_names"][()]],
                "counts": f["/model/leg_joint_counts"][()],
                "mass": float(f["/model/total_mass"][()]), "file": os.path.basename(SCENE)}


def worst_difference(robot, r):
    """Largest difference of DART's accelerations from the stored ones, every fifth sample."""
    dart_robot = DartRobot(robot)
    stored = np.concatenate([r["/base/linear_acceleration"], r["/base/angular_acceleration"],
                             r["/joints/acceleration"]], axis=1)
    return max(difference(dart_robot.rigid(r, t, r["/joints/torque"][t]), stored[t])
               for t in range(0, len(stored), 5))


def check_sizes(robot, r):
    """Check 1."""
    T, J, L = len(r["/time"]), len(robot["joints"]), len(robot["legs"])
    assert (J, L) == (12, 4), (J, L)
    for path in ("/joints/position", "/joints/torque", "/joints/tracking_error"):
        assert r[path].shape == (T, J), (path, r[path].shape)
    for path in ("/contacts/force", "/feet/position", "/contacts/slip_velocity"):
        assert r[path].shape == (T, L, 3), (path, r[path].shape)
    assert r["/replay/slip_distance"].shape == (L,), r["/replay/slip_distance"].shape
    assert (r["/model/leg_joint_counts"] == robot["counts"]).all(), r["/model/leg_joint_counts"]
    assert [text(n) for n in r["/model/joint_names"]] == robot["joints"]


def check_edited_counts(binary, result, tmp):
    """Check 4."""
    import h5py
    edited, out = os.path.join(tmp, "counts.h5"), os.path.join(tmp, "counts_replay.h5")
    shutil.copyfile(result, edited)
    with h5py.File(edited, "r+") as f:
        f["/model/leg_joint_counts"][:2] = (4, 2)
    p = subprocess.run([binary, "replay", edited, "-o", out], capture_output=True, text=True)
    lines = p.stderr.strip().splitlines()
    assert p.returncode != 0 and len(lines) == 1 and "/model/leg_joint_counts" in lines[0], \
        p.stderr
    assert not os.path.exists(out), "a replay was written"


def main():
    binary, src = args()
    if dart is None:
        print("skipped: python3-dartpy is not installed (pipelines/setup.sh installs it)")
        return 77
    with tempfile.TemporaryDirectory() as tmp:
        scene, urdf = copy_scene(src, tmp)
        result = os.path.join(tmp, "r.h5")
        status, err = cli_run(binary, scene, result)
        assert status == 0, err
        robot = robot_of(result)
        r, err = replay(binary, result, os.path.join(tmp, "p0.h5"))
        assert "warning" not in err, err
        check_sizes(robot, r)
        check_edited_counts(binary, result, tmp)
        worst = worst_difference(robot, r)
        loaded = int((np.abs(r["/contacts/force"]).sum(axis=2) > 0).any(axis=1).sum())
        T = len(r["/time"])
        print(f"replay of {os.path.basename(SCENE)}: {T} samples ({loaded} with a loaded foot; "
              f"{text(r['/replay/message']) or 'reached the end'}), largest relative "
              f"difference to DART {worst:.2g} (tolerance {TOLERANCE:g})")
        assert loaded > T // 2, "the replay's feet carry no load"
        assert worst <= TOLERANCE, f"the replay's accelerations differ from DART's by {worst:.3g}"

        with open(urdf, encoding="utf-8") as f:
            original = f.read()
        edited = heavier(original)
        assert edited != original, "the URDF edit changed nothing"
        with open(urdf, "w", encoding="utf-8") as f:
            f.write(edited)
        again, err = replay(binary, result, os.path.join(tmp, "p1.h5"))
        warnings = [line for line in err.splitlines() if "warning" in line]
        assert len(warnings) == 1 and urdf in warnings[0] and "has changed" in warnings[0], err
        for path, value in r.items():
            if path not in ("/replay/seconds",):
                assert np.array_equal(value, again[path]), f"{path} differs after the URDF edit"
        wrong = worst_difference(dict(robot, urdf=heavier(robot["urdf"]), mass=4 * robot["mass"]),
                                 r)
        print(f"after the URDF edit: the same replay, one warning ({warnings[0].strip()}); "
              f"DART of the stored URDF so edited differs by {wrong:.2g}")
        assert wrong > 100 * TOLERANCE, f"the edited URDF still agrees ({wrong:.3g})"
    return 0


if __name__ == "__main__":
    sys.exit(main())
