"""Drive train against DART 6.12 (docs/validation/dynamics.md#drive-train-against-dart).

hexdyn's drive torque of joint k is

    τ_drive = τ_link + J_a q̈ + τ_c sgn(q̇) + b q̇        (sgn(0) = 0)

with τ_link its floating-base inverse dynamics (/joints/torque) under the foot forces
/contacts/force, J_a the armature, τ_c the Coulomb and b the viscous friction. DART (Debian's
python3-dartpy) is given the robot of /model/urdf on a free-floating trunk, each joint's J_a,
τ_c and b, the state, τ_drive as joint forces and the foot forces at the feet; its
accelerations must be hexdyn's prescribed ones (/joints/acceleration and the trunk's
/base/linear_acceleration, /base/angular_acceleration) to a relative TOLERANCE.

    /usr/bin/python3 tests/python/test_drive_dart.py HEXDYN SOURCE_DIR [--synthetic]

1. Rigid robot: DART's forward dynamics under /joints/torque on every optimal sample of
   configs/paper.yaml reproduces the accelerations (the coordinate conversion); on the
   drive-train result too (its /joints/torque is τ_link).
2. Drive train, on a result of configs/paper.yaml with a section
   `actuators: {default: SCENE_DRIVE, femur: SCENE_FEMUR, joints: {L2_tibia: …}}`
   (scene_with_actuators), each joint's resolved values checked against the scene's. What the file must hold:
     /joints/drive_torque   (T, J) [N m], τ_drive above, in /model/joint_names order;
     /meta config_yaml      YAML with actuators: joints: <joint name>: {armature [kg m²],
                            coulomb_friction [N m], viscous_friction [N m s/rad], ...}
                            for every name of /model/joint_names.
   The samples checked are the optimal ones on which every joint turns at ≥ MIN_SPEED (the
   Coulomb term is then ±τ_c, and DART's friction slides), each leg in swing and in support
   among them. Each is checked with the three terms, then with each term left out of DART:
   the accelerations must then differ by more than 100 TOLERANCE (the check can fail).
3. The replay driven through the same actuators (`hexdyn replay` of that result,
   docs/theory/replay.md#driven-by-the-actuators): the replay file's /joints/drive_torque,
   state and accelerations, and /contacts/force, checked as in 2 on the samples where every
   joint turns at ≥ REPLAY_MIN_SPEED (its regularised Coulomb friction τ_c tanh(q̇ / 1e-3)
   is then τ_c sgn(q̇) to 1e-21), each leg in swing (no normal force) and in support among
   them; each term left out must again be seen.
   --synthetic checks instead a synthetic file (the rigid result plus τ_drive computed here
   from made-up per-joint J_a, τ_c, b, and its actuators section): the check of the check.

DART 6.12 has Coulomb friction and joint damping but no armature (no Joint or
DegreeOfFreedom setArmature; the word is nowhere in its headers or libraries). The one
per-joint inertia its articulated-body forward dynamics takes is that of its implicit
spring and damper: it adds h b + h² k to the joint's projected articulated inertia SᵀI^A S
(GenericJoint::updateInvProjArtInertiaImplicitDynamic, h the skeleton's time step) -- where
Pinocchio's articulated-body algorithm adds its armature (algorithm/aba.hxx) -- and applies
the forces −b q̇ and −k (q − q_rest + h q̇) (updateTotalForceDynamic). With
k = (J_a − h b)/h² and q_rest = q + h q̇ the added inertia is exactly J_a, the spring force
is zero and the damping force is −b q̇: DART solves (M + diag J_a) q̈ = τ − b q̇ − c + Jᵀf,
for any h.

DART's Coulomb friction is a constraint of its World's step (JointCoulombFrictionConstraint):
an impulse within ±τ_c h that would stop the joint. Its velocity response uses the rigid
inertia only (GenericJoint::updateVelocityChangeDynamic, without the implicit terms above),
so the velocity change of a step would apply friction without the armature. The friction
torque is therefore read from a World step (the impulse DART's solver chose, divided by its
step) and given, with τ_drive, to the forward dynamics above. The step is short
(FRICTION_STEP): the impulse bound moves no joint by more than a small part of MIN_SPEED, so
every joint slides and the torque is −τ_c sgn(q̇); the test asserts that DART found it so.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

import h5py
import numpy as np
import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import cli_run, text  # noqa: E402

try:
    import dartpy as dart
except ImportError:
    dart = None

GRAVITY = 9.81            # m/s², along −z (src/hexdyn/core/common.hpp kGravity)
TOLERANCE = 1e-8          # max |a_DART − a_hexdyn| over max(1, |a_hexdyn|), per sample
MIN_SPEED = 0.01          # rad/s, the slowest joint of a drive-train sample
REPLAY_MIN_SPEED = 0.025  # rad/s, the same for a replay's sample (25 stiction speeds)
FRICTION_STEP = 1e-6      # s, the World step that gives DART's Coulomb friction
IMPLICIT_STEP = 1e-3      # s, the skeleton step h of the implicit terms (any h < J_a/b)
SCENE_DRIVE = {"gear_ratio": 200, "torque_constant": 0.0081, "resistance": 3.95,
               "armature": 0.012, "coulomb_friction": 0.05, "viscous_friction": 0.02}
# Entries by joint type and by joint name on top of the default, so that every joint's
# values are not alike and a mix-up of the joints' order shows.
SCENE_FEMUR = {"armature": 0.02, "coulomb_friction": 0.08}
SCENE_JOINT = ("L2_tibia", {"viscous_friction": 0.05, "armature": 0.005})
DRIVE_KEYS = ("armature", "coulomb_friction", "viscous_friction")


def scene_value(name, key):
    """The value of `key` the scene gives joint `name`: the most specific entry's."""
    if name == SCENE_JOINT[0] and key in SCENE_JOINT[1]:
        return SCENE_JOINT[1][key]
    if name.endswith("_femur") and key in SCENE_FEMUR:
        return SCENE_FEMUR[key]
    return SCENE_DRIVE[key]


def read_result(path, replay=False):
    """A result file's robot and series, as h5py reads them (docs/user/output.md); or a
    replay file's (replay=True), every sample counted optimal and each leg's phase support
    (2) where its normal force is positive, swing (0) elsewhere."""
    own = ("/contacts/normal_force",) if replay else ("/contacts/phase", "/solver/status")
    with h5py.File(path, "r") as f:
        r = {k: f[k][()] for k in (
            "/time", "/base/position", "/base/orientation", "/base/linear_velocity",
            "/base/angular_velocity", "/base/linear_acceleration", "/base/angular_acceleration",
            "/joints/position", "/joints/velocity", "/joints/acceleration", "/joints/torque",
            "/contacts/force", "/feet/position") + own}
        if "/joints/drive_torque" in f:
            r["/joints/drive_torque"] = f["/joints/drive_torque"][()]
        r["urdf"] = text(f["/model/urdf"][()])
        r["joints"] = [text(n) for n in f["/model/joint_names"][()]]
        r["legs"] = [text(n) for n in f["/model/leg_names"][()]]
        if not replay:
            r["mass"] = float(f["/model/total_mass"][()])
        r["config"] = yaml.safe_load(text(f["/meta"].attrs["config_yaml"]))
    r["file"] = os.path.basename(path)
    if replay:
        r["/solver/status"] = np.zeros(len(r["/time"]), dtype=int)
        r["/contacts/phase"] = np.where(r["/contacts/normal_force"] > 0.0, 2, 0)
    return r


def drive_parameters(r):
    """{key: (J,) array in /model/joint_names order} of /meta config_yaml's actuators."""
    joints = ((r["config"] or {}).get("actuators") or {}).get("joints") or {}
    missing = [n for n in r["joints"] if n not in joints]
    assert not missing, f"config_yaml actuators.joints lacks {missing}"
    return {k: np.array([float(joints[n][k]) for n in r["joints"]]) for k in DRIVE_KEYS}


def rotation(wxyz):
    """Rotation matrix of a unit quaternion (w, x, y, z), body → world."""
    w, x, y, z = wxyz
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def load_skeleton(urdf):
    """/model/urdf as a DART skeleton: a FreeJoint at its root link (the trunk), links
    without <inertial> massless as URDF says (DART's loader would give them 1 kg). DART warns
    about each massless link; those warnings are expected and dropped, any other is shown."""
    massless = {link.get("name") for link in ET.fromstring(urdf).iter("link")
                if link.find("inertial") is None}
    with tempfile.TemporaryFile("w+") as log:
        saved = os.dup(2)
        os.dup2(log.fileno(), 2)
        try:
            loader = dart.utils.DartLoader()
            loader.setOptions(dart.utils.DartLoaderOptions(
                defaultRootJointType=dart.utils.DartLoaderRootJointType.FLOATING,
                defaultInertia=dart.dynamics.Inertia(0.0, np.zeros(3), np.zeros((3, 3)))))
            skel = loader.parseSkeletonString(urdf, dart.common.Uri())
        finally:
            os.dup2(saved, 2)
            os.close(saved)
        log.seek(0)
        expected = ("Inertia::verifyMoment", "Inertia::setMoment") + tuple(
            f"[{name}]" for name in massless)
        for line in log:
            if not any(e in line for e in expected):
                sys.stderr.write(line)
    assert skel is not None, "DART could not read /model/urdf"
    skel.setGravity(np.array([0.0, 0.0, -GRAVITY]))
    return skel


class DartRobot:
    """One robot in DART: `skel` for the forward dynamics; `world` holds a second copy whose
    only drive term is DART's Coulomb friction (friction_torque)."""

    def __init__(self, r):
        self.skel = load_skeleton(r["urdf"])
        self.world = dart.simulation.World()
        self.world.setGravity(np.array([0.0, 0.0, -GRAVITY]))
        self.world.setTimeStep(FRICTION_STEP)
        self.world.addSkeleton(load_skeleton(r["urdf"]))
        self.friction_skel = self.world.getSkeleton(0)
        self.names = r["joints"]
        self.dof = [self.skel.getJoint(n).getIndexInSkeleton(0) for n in self.names]
        self.free = self.skel.getRootJoint().getIndexInSkeleton(0)
        assert self.skel.getRootJoint().getType() == "FreeJoint", "the root is not free"
        assert abs(self.skel.getMass() - r["mass"]) < 1e-12 * r["mass"], \
            f"DART's mass {self.skel.getMass()} kg, /model/total_mass {r['mass']} kg"
        self.feet = [f"{leg}_foot" for leg in r["legs"]]  # /model/urdf names the feet so
        for skel in (self.skel, self.friction_skel):
            for n in self.names:
                skel.getJoint(n).setLimitEnforcement(False)

    def set_state(self, skel, r, t, joint_forces):
        """Sample t of r on skel: trunk pose and twist in DART's FreeJoint coordinates (the
        pose as FreeJoint.convertToPositions of W_T_B; the twist as the trunk's spatial
        velocity in trunk axes, angular first: [Rᵀω_W; Rᵀv_W]), q, q̇, the joint forces
        (flat joint order) and the foot forces (world axes, at the feet)."""
        R, p = rotation(r["/base/orientation"][t]), r["/base/position"][t]
        q, v, tau = (np.zeros(skel.getNumDofs()) for _ in range(3))
        q[self.free:self.free + 6] = dart.dynamics.FreeJoint.convertToPositions(
            dart.math.Isometry3(R, p))
        v[self.free:self.free + 3] = R.T @ r["/base/angular_velocity"][t]
        v[self.free + 3:self.free + 6] = R.T @ r["/base/linear_velocity"][t]
        q[self.dof], v[self.dof] = r["/joints/position"][t], r["/joints/velocity"][t]
        tau[self.dof] = joint_forces
        skel.setPositions(q)
        skel.setVelocities(v)
        skel.setForces(tau)
        skel.clearExternalForces()
        for leg, foot in enumerate(self.feet):
            skel.getBodyNode(foot).setExtForce(r["/contacts/force"][t][leg], np.zeros(3),
                                               False, True)
        trunk = skel.getRootBodyNode()
        read = np.concatenate([trunk.getWorldTransform().translation(),
                               trunk.getLinearVelocity(), trunk.getAngularVelocity()])
        want = np.concatenate([p, r["/base/linear_velocity"][t], r["/base/angular_velocity"][t]])
        assert np.allclose(read, want, rtol=0, atol=1e-12), f"sample {t}: trunk state differs"

    def accelerations(self):
        """After forward dynamics: [trunk origin's classical acceleration, trunk angular
        acceleration (world axes); q̈ (flat joint order)], as hexdyn stores them."""
        trunk = self.skel.getRootBodyNode()
        return np.concatenate([trunk.getLinearAcceleration(), trunk.getAngularAcceleration(),
                               self.skel.getAccelerations()[self.dof]])

    def rigid(self, r, t, joint_forces):
        """DART's accelerations with no drive terms."""
        zero = np.zeros(len(self.names))
        return self.drive(r, t, joint_forces, zero, zero)

    def drive(self, r, t, joint_forces, armature, viscous):
        """DART's forward dynamics with armature J_a (its implicit spring, see the module
        docstring) and damping b, under joint_forces: the accelerations."""
        h = IMPLICIT_STEP
        assert ((armature == 0) | (armature > h * viscous)).all(), "IMPLICIT_STEP too long"
        self.skel.setTimeStep(h)
        self.set_state(self.skel, r, t, joint_forces)
        for n, q, qd, j_a, b in zip(self.names, r["/joints/position"][t],
                                    r["/joints/velocity"][t], armature, viscous):
            joint = self.skel.getJoint(n)
            joint.setDampingCoefficient(0, b)
            joint.setSpringStiffness(0, (j_a - h * b) / h**2 if j_a > 0 else 0.0)
            joint.setRestPosition(0, q + h * qd)
        self.skel.computeForwardDynamics()
        return self.accelerations()

    def friction_torque(self, r, t, joint_forces, coulomb):
        """The joint torques of DART's Coulomb friction on sample t: one World step of
        FRICTION_STEP from the sample's state; the constraint impulse over the step."""
        for n, tau_c in zip(self.names, coulomb):
            self.friction_skel.getJoint(n).setCoulombFriction(0, tau_c)
        self.set_state(self.friction_skel, r, t, joint_forces)
        self.world.step(False)
        return np.array([self.friction_skel.getJoint(n).getConstraintImpulse(0)
                         for n in self.names]) / FRICTION_STEP


def hexdyn_accelerations(r, t):
    return np.concatenate([r["/base/linear_acceleration"][t], r["/base/angular_acceleration"][t],
                           r["/joints/acceleration"][t]])


def difference(a_dart, a_hexdyn):
    """Largest |a_DART − a_hexdyn| relative to max(1, |a_hexdyn|∞) [1]."""
    return float(np.abs(a_dart - a_hexdyn).max() / max(1.0, np.abs(a_hexdyn).max()))


def check_trunk_conversion(robot):
    """On spun, tilted trunks (the paper's trunk never rotates): DART's classical trunk
    acceleration is R(a_B + ω_B × v_B), its angular one R ω̇_B, for DART's free-joint
    acceleration [ω̇_B; a_B] (bench/bench_dynamics_dart.cpp's conversion, checked there
    against hexdyn's inverse dynamics)."""
    rng = np.random.default_rng(20240611)
    skel, trunk = robot.skel, robot.skel.getRootBodyNode()
    for _ in range(20):
        q, v, a = (rng.uniform(-1, 1, skel.getNumDofs()) for _ in range(3))
        skel.setPositions(q)
        skel.setVelocities(3 * v)
        skel.setAccelerations(30 * a)
        R = trunk.getWorldTransform().rotation()
        angular, linear = slice(robot.free, robot.free + 3), slice(robot.free + 3, robot.free + 6)
        w_B, v_B = skel.getVelocities()[angular], skel.getVelocities()[linear]
        dw_B, a_B = skel.getAccelerations()[angular], skel.getAccelerations()[linear]
        assert np.allclose(trunk.getAngularVelocity(), R @ w_B, rtol=0, atol=1e-12)
        assert np.allclose(trunk.getLinearVelocity(), R @ v_B, rtol=0, atol=1e-12)
        assert np.allclose(trunk.getAngularAcceleration(), R @ dw_B, rtol=0, atol=1e-11)
        assert np.allclose(trunk.getLinearAcceleration(), R @ (a_B + np.cross(w_B, v_B)),
                           rtol=0, atol=1e-11), "DART's trunk acceleration is not classical"


def check_rigid(r, robot):
    """Every optimal sample: DART under /joints/torque and the foot forces moves as hexdyn
    prescribes (on relaxed samples a trunk equation gave way, so DART would not)."""
    optimal = np.flatnonzero(r["/solver/status"] == 0)
    assert optimal.size > 100, f"only {optimal.size} optimal samples"
    worst = max(difference(robot.rigid(r, t, r["/joints/torque"][t]), hexdyn_accelerations(r, t))
                for t in optimal)
    print(f"{r['file']}: rigid robot: {optimal.size} optimal samples, largest relative difference "
          f"{worst:.2g} (tolerance {TOLERANCE:g})")
    assert worst <= TOLERANCE, f"DART and hexdyn differ by {worst:.3g} relative"


def drive_samples(r, min_speed=MIN_SPEED):
    """Optimal samples on which every joint turns at ≥ min_speed; each leg must be in swing
    (phase 0) on some of them and in support (2) on others."""
    moving = np.abs(r["/joints/velocity"]).min(axis=1) >= min_speed
    samples = np.flatnonzero((r["/solver/status"] == 0) & moving)
    phases = r["/contacts/phase"][samples]
    assert samples.size >= 20, f"only {samples.size} samples with every joint moving"
    assert ((phases == 0).any(axis=0) & (phases == 2).any(axis=0)).all(), \
        "a leg is never in swing or never in support among the samples"
    return samples


def check_drive(r, robot, min_speed=MIN_SPEED):
    """The drive train on every drive_samples sample; and each term left out of DART."""
    p = drive_parameters(r)
    assert "/joints/drive_torque" in r, "the result has no /joints/drive_torque"
    samples = drive_samples(r, min_speed)
    zero = np.zeros(len(r["joints"]))
    worst, least = 0.0, {"armature": np.inf, "viscous friction": np.inf,
                         "Coulomb friction": np.inf}
    for t in samples:
        tau = r["/joints/drive_torque"][t]
        a = hexdyn_accelerations(r, t)
        friction = robot.friction_torque(r, t, tau, p["coulomb_friction"])
        slides = -p["coulomb_friction"] * np.sign(r["/joints/velocity"][t])
        assert np.allclose(friction, slides, rtol=1e-12, atol=0), \
            f"sample {t}: DART's Coulomb friction {friction}, expected sliding {slides}"
        full = robot.drive(r, t, tau + friction, p["armature"], p["viscous_friction"])
        worst = max(worst, difference(full, a))
        for term, acc in (
                ("armature", robot.drive(r, t, tau + friction, zero, p["viscous_friction"])),
                ("viscous friction", robot.drive(r, t, tau + friction, p["armature"], zero)),
                ("Coulomb friction", robot.drive(r, t, tau, p["armature"],
                                                 p["viscous_friction"]))):
            least[term] = min(least[term], difference(acc, a))
    print(f"{r['file']}: drive train: {samples.size} samples, largest relative difference {worst:.2g} "
          f"(tolerance {TOLERANCE:g}); left out of DART, the smallest difference: " +
          ", ".join(f"{k} {v:.2g}" for k, v in least.items()))
    assert worst <= TOLERANCE, f"DART and hexdyn's drive train differ by {worst:.3g} relative"
    for term, d in least.items():
        assert d > 100 * TOLERANCE, f"without its {term}, DART still agrees ({d:.3g})"


def synthetic_drive_result(base, out):
    """The result `base` with /joints/drive_torque and /meta config_yaml's actuators section
    of made-up per-joint J_a, τ_c, b (each joint's own, so that an order mix-up shows)."""
    r = read_result(base)
    k = np.arange(len(r["joints"]))
    p = {"armature": 0.008 + 0.0005 * k, "coulomb_friction": 0.03 + 0.002 * k,
         "viscous_friction": 0.01 + 0.001 * k}
    qd = r["/joints/velocity"]
    tau = (r["/joints/torque"] + p["armature"] * r["/joints/acceleration"] +
           p["coulomb_friction"] * np.sign(qd) + p["viscous_friction"] * qd)
    config = dict(r["config"])
    config["actuators"] = {"joints": {n: {key: float(p[key][i]) for key in DRIVE_KEYS}
                                      for i, n in enumerate(r["joints"])}}
    with open(base, "rb") as src, open(out, "wb") as dst:
        dst.write(src.read())
    with h5py.File(out, "r+") as f:
        f.create_dataset("/joints/drive_torque", data=tau)
        f["/meta"].attrs["config_yaml"] = yaml.safe_dump(config, sort_keys=False)
    return out


def scene_with_actuators(src, d):
    """configs/paper.yaml with actuators: default SCENE_DRIVE, femur SCENE_FEMUR, and
    SCENE_JOINT by name."""
    path = os.path.join(d, "drive.yaml")
    with open(path, "w") as f:
        yaml.safe_dump({"inherit": os.path.join(src, "configs", "paper.yaml"),
                        "actuators": {"default": SCENE_DRIVE, "femur": SCENE_FEMUR,
                                      "joints": {SCENE_JOINT[0]: SCENE_JOINT[1]}}},
                       f, sort_keys=False)
    return path


def real_drive_result(hexdyn, src, d):
    """hexdyn's result of scene_with_actuators, its resolved values checked against the
    scene's."""
    out = os.path.join(d, "drive.h5")
    rc, err = cli_run(hexdyn, scene_with_actuators(src, d), out)
    assert rc == 0, err
    r = read_result(out)
    p = drive_parameters(r)
    for key in DRIVE_KEYS:
        expected = np.array([scene_value(n, key) for n in r["joints"]])
        assert (p[key] == expected).all(), f"resolved {key} {p[key]}, the scene's {expected}"
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("hexdyn")
    ap.add_argument("source")
    ap.add_argument("--synthetic", action="store_true",
                    help="check the synthetic drive-train file even if hexdyn has actuators")
    args = ap.parse_args()
    if dart is None:
        print("skipped: python3-dartpy is not installed (pipelines/setup.sh installs it)")
        return 77
    src = os.path.realpath(args.source)
    with tempfile.TemporaryDirectory() as d:
        base = os.path.join(d, "paper.h5")
        rc, err = cli_run(args.hexdyn, os.path.join(src, "configs", "paper.yaml"), base)
        assert rc == 0, err
        r = read_result(base)
        robot = DartRobot(r)
        check_trunk_conversion(robot)
        check_rigid(r, robot)
        if args.synthetic:
            check_drive(read_result(synthetic_drive_result(base, os.path.join(d, "synthetic.h5"))),
                        robot)
            return 0
        drive = real_drive_result(args.hexdyn, src, d)
        r = read_result(drive)
        robot = DartRobot(r)  # the robot as this run simulated it
        check_rigid(r, robot)  # /joints/torque is still τ_link
        check_drive(r, robot)
        replay = os.path.join(d, "drive_replay.h5")
        done = subprocess.run([args.hexdyn, "replay", drive, "-o", replay], capture_output=True,
                              text=True)
        assert done.returncode == 0, done.stderr
        check_drive(read_result(replay, replay=True), robot, REPLAY_MIN_SPEED)
    return 0


if __name__ == "__main__":
    sys.exit(main())
