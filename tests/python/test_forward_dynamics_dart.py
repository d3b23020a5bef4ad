"""Forward dynamics against DART 6.12 (docs/validation/dynamics.md#forward-dynamics-against-dart).

hexdyn.forward_dynamics (C++ forward_dynamics_joints: CRBA and a Cholesky solve over RNEA's
bias, docs/theory/replay.md#forward-dynamics) gives the accelerations of a scene's robot at a
state under joint torques and foot forces, in a result file's coordinates: the URDF root
link's frame for the trunk (/base/*), /model/joint_names order for the joints. DART (Debian's
python3-dartpy, its articulated-body algorithm) is given the scene's /model/urdf on a free
trunk, the same state, the torques as joint forces and each foot force at its foot link
L{i}_foot (tests/python/test_drive_dart.py DartRobot, whose coordinate conversion that test
checks). At STATES random states (pose, twist, joint angles and rates, torques, foot forces,
fixed seed) of each robot of SCENES -- the paper's, and the PhantomX, whose root link frame is
turned from hexdyn's trunk frame (forward_axis +x) -- checked:
  1. DART's accelerations are hexdyn's to TOLERANCE, relative to the largest acceleration of
     the state;
  2. hexdyn without the foot forces differs from DART with them by more than 100 TOLERANCE
     (the check can fail);
  3. one state alone gives the same accelerations, bit for bit, as within the batch;
  4. on the scene's own result, at every optimal sample, hexdyn's forward dynamics under
     /joints/torque and /contacts/force gives back the stored accelerations (the plan's,
     which the inverse dynamics answered) to TOLERANCE, relative to max(1, |a|) (as
     tests/python/test_drive_dart.py);
  5. a wrong shape raises ValueError, massless legs (robot.leg_inertia) hexdyn.SolverError;
  6. the replay of the paper scene (`hexdyn replay`, docs/theory/replay.md#the-replay): at
     every fifth stored sample, DART's forward dynamics of the stored state under the stored
     /joints/torque and /contacts/force gives the stored accelerations to TOLERANCE relative
     to max(1, |a|): each sample is the forward dynamics of its own state, not an
     integrator's stage.

    /usr/bin/python3 tests/python/test_forward_dynamics_dart.py HEXDYN SOURCE_DIR
"""
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import args, cli_run, text  # noqa: E402
from test_drive_dart import DartRobot, dart, difference  # noqa: E402

import hexdyn  # noqa: E402
from hexdyn import results as hr  # noqa: E402

SCENES = (os.path.join("configs", "paper.yaml"),
          os.path.join("configs", "robots", "phantomx_mark4_stairs.yaml"))
STATES = 20
# The trunk's coordinates of an acceleration, before the joints' (forward_dynamics' order).
TRUNK_DOFS = ("ax", "ay", "az", "alpha_x", "alpha_y", "alpha_z")
TOLERANCE = 1e-10  # max |a_DART - a_hexdyn| over max |a_hexdyn|, per state


def robot_of(r, scene):
    """The scene's robot as its result r describes it: /model/urdf, joint and leg names, mass."""
    return {"urdf": text(r["/model/urdf"]), "joints": [text(n) for n in r["/model/joint_names"]],
            "legs": [text(n) for n in r["/model/leg_names"]],
            "mass": float(r["/model/total_mass"]), "file": os.path.basename(scene)}


def check_result(scene, r):
    """Check 4: the result's optimal samples, forward again."""
    optimal = np.flatnonzero(r["/solver/status"] == 0)
    assert optimal.size > 50, f"only {optimal.size} optimal samples"
    states = {k: r[k][optimal] for k in (
        "/base/position", "/base/orientation", "/base/linear_velocity", "/base/angular_velocity",
        "/joints/position", "/joints/velocity", "/joints/torque", "/contacts/force")}
    a = hexdyn_accelerations(scene, states)
    stored = np.concatenate([r["/base/linear_acceleration"], r["/base/angular_acceleration"],
                             r["/joints/acceleration"]], axis=1)[optimal]
    worst = max(difference(a[i], stored[i]) for i in range(optimal.size))
    print(f"{os.path.basename(scene)}: {optimal.size} optimal samples of its result, forward "
          f"again: largest relative difference {worst:.2g} (tolerance {TOLERANCE:g})")
    assert worst <= TOLERANCE, f"the result's accelerations differ by {worst:.3g}"


def random_states(rng, n, sizes):
    """n random states in a result file's names and shapes (orientation w >= 0) of a robot of
    sizes["L"] legs and sizes["J"] joints (hexdyn.results.shape_sizes of its result)."""
    L, J = sizes["L"], sizes["J"]
    quat = rng.normal(size=(n, 4))
    quat /= np.linalg.norm(quat, axis=1)[:, None]
    quat *= np.sign(quat[:, :1])
    return {"/base/position": rng.uniform(-1, 1, (n, 3)), "/base/orientation": quat,
            "/base/linear_velocity": rng.uniform(-1, 1, (n, 3)),
            "/base/angular_velocity": rng.uniform(-2, 2, (n, 3)),
            "/joints/position": rng.uniform(-1, 1, (n, J)),
            "/joints/velocity": rng.uniform(-2, 2, (n, J)),
            "/joints/torque": rng.uniform(-2, 2, (n, J)),
            "/contacts/force": rng.uniform(-20, 20, (n, L, 3))}


def hexdyn_accelerations(scene, s, t=slice(None), forces=True):
    """hexdyn.forward_dynamics at the states s[t]: (..., 6 + J), trunk then joints."""
    a = hexdyn.forward_dynamics(
        scene, s["/base/position"][t], s["/base/orientation"][t], s["/joints/position"][t],
        s["/base/linear_velocity"][t], s["/base/angular_velocity"][t], s["/joints/velocity"][t],
        s["/joints/torque"][t], foot_forces=s["/contacts/force"][t] if forces else None)
    return np.concatenate([a["base_linear_acceleration"], a["base_angular_acceleration"],
                           a["joint_acceleration"]], axis=-1)


def relative(a_dart, a_hexdyn):
    return float(np.abs(a_dart - a_hexdyn).max() / np.abs(a_hexdyn).max())


def check_scene(scene, rng):
    r = hexdyn.run(scene)
    check_result(scene, r)
    robot = robot_of(r, scene)
    sizes = hr.shape_sizes(r)
    dofs = len(TRUNK_DOFS) + sizes["J"]  # the trunk's, then one per joint
    states = random_states(rng, STATES, sizes)
    dart_robot = DartRobot(robot)
    a = hexdyn_accelerations(scene, states)
    no_forces = hexdyn_accelerations(scene, states, forces=False)
    assert a.shape == (STATES, dofs), a.shape
    worst, least = 0.0, np.inf
    for t in range(STATES):
        a_dart = dart_robot.rigid(states, t, states["/joints/torque"][t])
        worst = max(worst, relative(a_dart, a[t]))
        least = min(least, relative(a_dart, no_forces[t]))
    one = hexdyn_accelerations(scene, states, t=STATES // 2)
    assert one.shape == (dofs,) and (one == a[STATES // 2]).all(), "one state differs from the batch"
    print(f"{robot['file']}: {STATES} random states, largest relative difference to DART "
          f"{worst:.2g} (tolerance {TOLERANCE:g}); without the foot forces, the smallest "
          f"{least:.2g}; largest acceleration {np.abs(a).max():.3g}")
    assert worst <= TOLERANCE, f"{robot['file']}: DART and hexdyn differ by {worst:.3g} relative"
    assert least > 100 * TOLERANCE, f"{robot['file']}: without foot forces still agrees ({least:.3g})"


def check_refusals(scene, rng):
    """Check 5."""
    sizes = hr.shape_sizes(hexdyn.run(scene))
    J = sizes["J"]
    s = random_states(rng, 1, sizes)
    one = {k: v[0] for k, v in s.items()}
    bad = dict(one, **{"/joints/position": np.zeros(J - 1)})
    try:
        hexdyn_accelerations(scene, bad)
        raise AssertionError(f"{J - 1} joint angles accepted")
    except ValueError as e:
        assert f"joint_position has shape ({J - 1}), expected ({J}) or (T, {J})" in str(e), e
    try:
        hexdyn.forward_dynamics(scene, *(one[k] for k in (
            "/base/position", "/base/orientation", "/joints/position", "/base/linear_velocity",
            "/base/angular_velocity", "/joints/velocity", "/joints/torque")),
            set={"robot.leg_inertia": "massless"})
        raise AssertionError("a robot with massless legs simulated")
    except hexdyn.SolverError:
        pass


def check_replay(hexdyn_binary, scene):
    """Check 6."""
    import h5py
    with tempfile.TemporaryDirectory() as tmp:
        result, replay = os.path.join(tmp, "r.h5"), os.path.join(tmp, "p.h5")
        status, err = cli_run(hexdyn_binary, scene, result)
        assert status == 0, err
        p = subprocess.run([hexdyn_binary, "replay", result, "-o", replay],
                           capture_output=True, text=True)
        assert p.returncode == 0, p.stderr
        with h5py.File(replay, "r") as f:
            r = {k: f[k][()] for k in (
                "/base/position", "/base/orientation", "/base/linear_velocity",
                "/base/angular_velocity", "/base/linear_acceleration",
                "/base/angular_acceleration", "/joints/position", "/joints/velocity",
                "/joints/acceleration", "/joints/torque", "/contacts/force")}
        with h5py.File(result, "r") as f:  # the robot as the result describes it
            robot = robot_of({k: f[k][()] for k in (
                "/model/urdf", "/model/joint_names", "/model/leg_names", "/model/total_mass")},
                scene)
    dart_robot = DartRobot(robot)
    stored = np.concatenate([r["/base/linear_acceleration"], r["/base/angular_acceleration"],
                             r["/joints/acceleration"]], axis=1)
    samples = range(0, len(stored), 5)
    worst = max(difference(dart_robot.rigid(r, t, r["/joints/torque"][t]), stored[t])
                for t in samples)
    loaded = int((np.abs(r["/contacts/force"]).sum(axis=2) > 0).any(axis=1).sum())
    print(f"replay of {os.path.basename(scene)}: {len(samples)} stored samples ({loaded} of "
          f"{len(stored)} with a loaded foot), largest relative difference to DART "
          f"{worst:.2g} (tolerance {TOLERANCE:g})")
    assert loaded > len(stored) // 2, "the replay's feet carry no load"
    assert worst <= TOLERANCE, f"the replay's accelerations differ from DART's by {worst:.3g}"


def main():
    binary, src = args()
    if dart is None:
        print("skipped: python3-dartpy is not installed (pipelines/setup.sh installs it)")
        return 77
    rng = np.random.default_rng(20261127)
    for scene in SCENES:
        check_scene(os.path.join(src, scene), rng)
    check_refusals(os.path.join(src, SCENES[0]), rng)
    check_replay(binary, os.path.join(src, SCENES[0]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
