"""Robots from URDF against DART 6.12's inverse dynamics
(docs/validation/robots.md#torques-against-dart).

For each scene given (default: every configs/robots/*.yaml), hexdyn runs it; DART (Debian's
python3-dartpy) is given the robot of the result's own /model/urdf on a free-floating trunk,
and at every sample the state (/base/*, /joints/position, velocity and acceleration) and the
foot forces /contacts/force at the feet. DART's inverse dynamics must give

  - every joint's torque /joints/torque, to TOLERANCE relative to the run's largest |τ|,
    on every sample (a relaxed sample's trunk rows gave way, its joint rows did not);
  - a zero trunk wrench, to TOLERANCE relative to the robot's weight (and weight times its
    size for the moment), on every optimal sample (status 0).

Relaxed samples are counted and printed per scene. Each force acts at its contact point /feet/position. The joint path must be continuous: no
step between samples moves a joint further than its stored rates allow (joint_jumps; a leg
whose IK changes branch between samples jumps). The check can fail: each scene is also
checked with its largest foot force left out, which must move the joint
torques by more than 1e6 TOLERANCE.

    /usr/bin/python3 tests/python/test_robots_dart.py HEXDYN SOURCE_DIR [SCENE ...]
"""
import argparse
import glob
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import cli_run  # noqa: E402
from test_drive_dart import DartRobot, dart, read_result, rotation  # noqa: E402

TOLERANCE = 1e-10


def dart_inverse_dynamics(robot, r, t, forces):
    """DART's generalised forces at sample t of r under foot forces `forces` (L, 3):
    (trunk wrench in DART's free-joint coordinates, joint torques in flat order)."""
    skel = robot.skel
    robot.set_state(skel, r, t, np.zeros(len(robot.names)))
    skel.clearExternalForces()
    for leg, foot in enumerate(robot.feet):
        # At the contact point /feet/position (a sphere foot's lowest point, not its centre),
        # given to DART in the foot body's own frame.
        body = skel.getBodyNode(foot)
        T = body.getWorldTransform()
        offset = T.rotation().T @ (r["/feet/position"][t][leg] - T.translation())
        body.setExtForce(forces[leg], offset, False, True)
    R = rotation(r["/base/orientation"][t])
    w_B = R.T @ r["/base/angular_velocity"][t]
    v_B = R.T @ r["/base/linear_velocity"][t]
    a = np.zeros(skel.getNumDofs())
    a[robot.free:robot.free + 3] = R.T @ r["/base/angular_acceleration"][t]
    a[robot.free + 3:robot.free + 6] = R.T @ r["/base/linear_acceleration"][t] - np.cross(w_B, v_B)
    a[robot.dof] = r["/joints/acceleration"][t]
    skel.setAccelerations(a)
    trunk = skel.getRootBodyNode()
    assert np.allclose(trunk.getLinearAcceleration(), r["/base/linear_acceleration"][t],
                       rtol=0, atol=1e-9 * max(1.0, np.abs(a).max())), \
        f"sample {t}: the trunk acceleration's conversion differs"
    skel.computeInverseDynamics(True, False, False)
    tau = skel.getForces()
    return tau[robot.free:robot.free + 6], tau[robot.dof]


def joint_jumps(t, q, qd, qdd):
    """Steps i where some joint moves further than its rates allow: |q[i+1] - q[i]| above
    2 (h max|q̇| + h² max|q̈|) + 1e-9 over the step's ends, h the step (Taylor's bound on
    the step with the larger end values, doubled). A leg whose IK changes branch between
    two samples jumps by a large fraction of a turn."""
    h = np.diff(t)[:, None]
    rate = np.maximum(np.abs(qd[1:]), np.abs(qd[:-1]))
    accel = np.maximum(np.abs(qdd[1:]), np.abs(qdd[:-1]))
    bound = 2.0 * (h * rate + h * h * accel) + 1e-9
    return np.nonzero((np.abs(np.diff(q, axis=0)) > bound).any(axis=1))[0]


def check_continuity(scene, r):
    """The joint path is continuous: no step jumps beyond its rates (joint_jumps); and the
    check can fail: the same path with one joint turned by a quarter turn at one sample."""
    t = r["/time"]
    q, qd, qdd = (r[f"/joints/{k}"] for k in ("position", "velocity", "acceleration"))
    jumps = joint_jumps(t, q, qd, qdd)
    if len(jumps):
        i = int(jumps[0])
        joint = r["joints"][int(np.argmax(np.abs(q[i + 1] - q[i])))]
        raise AssertionError(f"{scene}: joint {joint} jumps between t = {t[i]} and {t[i + 1]} s")
    bent = q.copy()
    bent[len(t) // 2, 0] += np.pi / 2
    assert len(joint_jumps(t, bent, qd, qdd)) > 0, f"{scene}: a quarter-turn jump goes unseen"


def check_scene(hexdyn, scene, d):
    out = os.path.join(d, os.path.basename(scene).replace(".yaml", ".h5"))
    rc, err = cli_run(hexdyn, scene, out)
    assert rc == 0, f"{scene}: {err}"
    r = read_result(out)
    robot = DartRobot(r)
    tau_file = r["/joints/torque"]
    scale = max(1.0, float(np.abs(tau_file).max()))
    weight = r["mass"] * 9.81
    status = r["/solver/status"]
    worst_joint = worst_trunk = 0.0
    for t in range(len(status)):
        wrench, tau = dart_inverse_dynamics(robot, r, t, r["/contacts/force"][t])
        worst_joint = max(worst_joint, float(np.abs(tau - tau_file[t]).max()) / scale)
        if status[t] == 0:
            worst_trunk = max(worst_trunk, float(np.abs(wrench).max()) / weight)
    relaxed = int(np.count_nonzero(status != 0))
    print(f"{os.path.basename(scene)}: {len(r['legs'])} legs, {len(r['joints'])} joints, "
          f"{len(status)} samples ({relaxed} relaxed): joint torques to {worst_joint:.2g} "
          f"of {scale:.3g} N m, trunk wrench on optimal samples to {worst_trunk:.2g} of the "
          f"weight (tolerance {TOLERANCE:g})")
    assert worst_joint <= TOLERANCE, f"{scene}: joint torques differ by {worst_joint:.3g}"
    assert worst_trunk <= TOLERANCE * 10, f"{scene}: trunk wrench {worst_trunk:.3g} of weight"
    check_continuity(scene, r)
    # The check of the check: a foot force left out moves the torques.
    # The largest foot force of the run, so that leaving it out cannot go unseen.
    magnitude = np.nan_to_num(np.linalg.norm(r["/contacts/force"], axis=2))
    t, leg = (int(i) for i in np.unravel_index(np.argmax(magnitude), magnitude.shape))
    forces = r["/contacts/force"][t].copy()
    forces[leg] = 0.0
    _, tau = dart_inverse_dynamics(robot, r, t, forces)
    moved = float(np.abs(tau - tau_file[t]).max()) / scale
    assert moved > 1e6 * TOLERANCE, f"{scene}: leaving out {r['legs'][leg]}'s force moved " \
                                    f"the torques by only {moved:.3g}"
    return relaxed


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("hexdyn")
    ap.add_argument("source")
    ap.add_argument("scenes", nargs="*")
    args = ap.parse_args()
    if dart is None:
        print("skipped: python3-dartpy is not installed (pipelines/setup.sh installs it)")
        return 77
    src = os.path.realpath(args.source)
    scenes = args.scenes or sorted(glob.glob(os.path.join(src, "configs", "robots", "*.yaml")))
    with tempfile.TemporaryDirectory() as d:
        for scene in scenes:
            check_scene(args.hexdyn, scene, d)
    return 0


if __name__ == "__main__":
    sys.exit(main())
