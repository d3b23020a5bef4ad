"""Synthetic robots against DART 6.12 (docs/validation/dynamics.md#synthetic-robots-against-dart).

Five robots are written as URDF with random masses, inertias, link placements and joint axes
(fixed seed): a quadruped of four legs of three joints, a hexapod of legs of four joints, a
robot of six legs of five joints, an octopod of legs of three joints and a biped of legs of six
joints; prismatic joints in the hexapod, the six-by-five robot and the biped. Each link's
inertia is R diag(Sy + Sz, Sx + Sz, Sx + Sy) Rᵀ for random second moments S > 0 and a random
rotation R (positive definite, the triangle inequality strict), at a random centre of mass and
inertial frame; each joint has a random placement (origin and rpy) and a random unit axis; a
fixed sensor link on the trunk and a foot link with its own mass at the end of each chain
(merged by the reader). The chains are written in a shuffled order, and their hips placed so
that leg Li (rank by rank front to rear, left before right,
docs/theory/conventions.md#legs-and-joints) has the foot link Li_foot: the scene names the feet
by robot.foot_links. Each robot's scene is the URDF and the keys of configs/robots/solo12_flat.yaml.

At STATES random states of each robot (pose, twist, joint angles, rates and accelerations,
torques, foot forces), checked against DART (Debian's python3-dartpy, the URDF on a free
trunk, tests/python/test_drive_dart.py load_skeleton; its FreeJoint coordinates converted to a
result file's, as tests/python/test_robots_dart.py does):
  1. hexdyn.mass_matrix equals DART's mass matrix Sᵀ M_DART S (S: the root link's
     coordinates [v; ω; q̇] to DART's [Rᵀω; Rᵀv; q̇]) to TOLERANCE relative to its largest entry;
  2. hexdyn.inverse_dynamics (trunk force, moment about the root link's origin, joint torques)
     equals Sᵀ τ_DART of DART's inverse dynamics with the foot forces at the feet, to TOLERANCE
     relative to its largest value;
  3. hexdyn.forward_dynamics equals DART's forward dynamics under the joint torques and the
     foot forces, to TOLERANCE relative to the largest acceleration;
  4. the legs are the ones predicted (joint names in leg order), the joints' count, and the
     prismatic joints are there;
  5. the check can fail: against DART given the same URDF with one foot link's mass and
     inertia 50 % larger, each of 1-3 differs by more than 1e6 TOLERANCE;
  6. a joint_position one joint short is refused by each function with one line.

    /usr/bin/python3 tests/python/test_synthetic_robots_dart.py HEXDYN SOURCE_DIR
"""
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import args  # noqa: E402
from test_drive_dart import dart, load_skeleton, rotation  # noqa: E402

import hexdyn  # noqa: E402

TOLERANCE = 1e-10
STATES = 20
SEED = 20261129
# name, legs, joints per leg, prismatic joints as (leg index, joint index)
ROBOTS = (("quadruped_4x3", 4, 3, ()),
          ("hexapod_6x4", 6, 4, ((0, 3), (3, 1))),
          ("robot_6x5", 6, 5, ((1, 2), (4, 4))),
          ("octopod_8x3", 8, 3, ()),
          ("biped_2x6", 2, 6, ((0, 3), (1, 2))))
PERTURBED = 1.5  # the falsification: one foot link's mass and inertia times this


def random_rotation(rng):
    q = rng.normal(size=4)
    return rotation(q / np.linalg.norm(q))


def rpy_of(R):
    """URDF rpy (fixed axes x, y, z: R = Rz(y) Ry(p) Rx(r)) of a rotation matrix."""
    pitch = np.arcsin(-np.clip(R[2, 0], -1.0, 1.0))
    return np.array([np.arctan2(R[2, 1], R[2, 2]), pitch, np.arctan2(R[1, 0], R[0, 0])])


def numbers(v):
    return " ".join(repr(float(x)) for x in v)


def inertial(rng, mass, size, scale=1.0):
    """An <inertial>: mass [kg], a random COM within `size` [m], random frame and moments."""
    S = mass * (size * rng.uniform(0.2, 1.0, 3)) ** 2  # second moments, positive
    R = random_rotation(rng)
    I = scale * R @ np.diag([S[1] + S[2], S[0] + S[2], S[0] + S[1]]) @ R.T
    return (f'<inertial><origin xyz="{numbers(rng.uniform(-size, size, 3) / 3)}" '
            f'rpy="{numbers(rpy_of(random_rotation(rng)))}"/><mass value="{scale * mass!r}"/>'
            f'<inertia ixx="{I[0, 0]!r}" ixy="{I[0, 1]!r}" ixz="{I[0, 2]!r}" iyy="{I[1, 1]!r}" '
            f'iyz="{I[1, 2]!r}" izz="{I[2, 2]!r}"/></inertial>')


def hip_position(rng, leg, legs):
    """Leg `leg` (0-based, L1 first) at rank leg // 2 front to rear, left (URDF +y) when even."""
    ranks = (legs + 1) // 2
    rank, left = leg // 2, leg % 2 == 0
    x = 0.0 if ranks == 1 else 0.3 - 0.6 * rank / (ranks - 1)
    return np.array([x + rng.uniform(-0.02, 0.02), (1 if left else -1) * rng.uniform(0.1, 0.2),
                     rng.uniform(-0.05, 0.05)])


def joint_xml(rng, name, parent, child, xyz, prismatic):
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    kind, limit = ("prismatic", 'lower="-0.2" upper="0.2"') if prismatic else (
        "revolute", 'lower="-3" upper="3"')
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'<origin xyz="{numbers(xyz)}" rpy="{numbers(rpy_of(random_rotation(rng)))}"/>'
            f'<axis xyz="{numbers(axis)}"/><limit {limit} effort="100" velocity="10"/></joint>')


def chain_xml(rng, leg, legs, m, prismatic, chain, perturb):
    """Leg `leg`'s chain (joints c{chain}_j0 …, foot link L{leg + 1}_foot) as URDF elements."""
    out, parent = [], "trunk"
    for j in range(m):
        link = f"c{chain}_link{j}"
        xyz = hip_position(rng, leg, legs) if j == 0 else rng.normal(size=3) * 0.08
        out.append(joint_xml(rng, f"c{chain}_j{j}", parent, link, xyz, (leg, j) in prismatic))
        out.append(f'<link name="{link}">{inertial(rng, rng.uniform(0.1, 1.0), 0.1)}</link>')
        parent = link
    foot = f"L{leg + 1}_foot"
    out.append(f'<joint name="c{chain}_foot_fixed" type="fixed"><parent link="{parent}"/>'
               f'<child link="{foot}"/><origin xyz="{numbers(rng.normal(size=3) * 0.08)}"/></joint>')
    out.append(f'<link name="{foot}">'
               f'{inertial(rng, rng.uniform(0.02, 0.1), 0.02, PERTURBED if perturb else 1.0)}</link>')
    return out, [f"c{chain}_j{j}" for j in range(m)]


def robot_urdf(seed, name, legs, m, prismatic, perturb=False):
    """(URDF text, total mass [kg], joint names in leg order L1 … Ln)."""
    rng = np.random.default_rng(seed)
    chains = rng.permutation(legs)  # leg l is written as chain chains[l], in chain order
    parts = {}
    for leg in range(legs):
        parts[chains[leg]] = chain_xml(rng, leg, legs, m, prismatic, chains[leg],
                                       perturb and leg == 0)
    body = [f'<link name="trunk">{inertial(rng, rng.uniform(4.0, 8.0), 0.3)}</link>',
            f'<link name="sensor">{inertial(rng, 0.2, 0.05)}</link>',
            '<joint name="sensor_fixed" type="fixed"><parent link="trunk"/>'
            f'<child link="sensor"/><origin xyz="{numbers(rng.normal(size=3) * 0.05)}"/></joint>']
    for c in range(legs):
        body += parts[c][0]
    text = f'<?xml version="1.0"?>\n<robot name="{name}">\n' + "\n".join(body) + "\n</robot>\n"
    mass = sum(float(x.split('"')[1]) for x in text.split("<mass value=")[1:])
    joints = [n for leg in range(legs) for n in parts[chains[leg]][1]]
    return text, mass, joints


SCENE = """name: {name}
robot:
  urdf: {urdf}
  forward_axis: +x
  foot_links: [{feet}]
terrain: {{type: flat, height: 0.0}}
gait: {{duty_factor: 0.75, stroke: 0.03, foot_lateral: 0.08, foothold_margin: 0.01,
        swing_clearance: 0.03, touchdown_speed: 0.05}}
motion: {{posture: {{height: auto, start_y: 0.0}}, peak_speed: 0.05, cycles: 4,
         ramp_duration: 1.0}}
contact: {{model: compliant, stiffness: 3.9810717055349725e11, exponent: 2.2,
          damping_max: 1.0e4, full_damping_depth: 1.0e-5, friction_coefficient: 0.6}}
allocation: {{friction: pyramid4}}
output: {{sample_step: 0.05, tolerance: 0}}
"""


def random_states(rng, n, legs, joints, prismatic_index):
    quat = rng.normal(size=(n, 4))
    quat /= np.linalg.norm(quat, axis=1)[:, None]
    q = rng.uniform(-1.5, 1.5, (n, joints))
    q[:, prismatic_index] = rng.uniform(-0.15, 0.15, (n, len(prismatic_index)))
    return {"p": rng.uniform(-1, 1, (n, 3)), "quat": quat, "q": q,
            "v": rng.uniform(-1, 1, (n, 3)), "w": rng.uniform(-2, 2, (n, 3)),
            "qd": rng.uniform(-2, 2, (n, joints)), "a": rng.uniform(-3, 3, (n, 3)),
            "dw": rng.uniform(-3, 3, (n, 3)), "qdd": rng.uniform(-3, 3, (n, joints)),
            "tau": rng.uniform(-5, 5, (n, joints)), "forces": rng.uniform(-30, 30, (n, legs, 3))}


class Dart:
    """The URDF in DART on a free trunk, its coordinates converted to a result file's."""

    def __init__(self, urdf, joints, legs):
        self.skel = load_skeleton(urdf)
        assert self.skel.getRootJoint().getType() == "FreeJoint", "the root is not free"
        self.free = self.skel.getRootJoint().getIndexInSkeleton(0)
        self.dof = [self.skel.getJoint(n).getIndexInSkeleton(0) for n in joints]
        self.feet = [self.skel.getBodyNode(f"L{leg + 1}_foot") for leg in range(legs)]
        assert self.skel.getNumDofs() == 6 + len(joints), self.skel.getNumDofs()
        for n in joints:
            self.skel.getJoint(n).setLimitEnforcement(False)

    def set_state(self, s, t):
        """State t of s; returns S, DART's generalised velocity of the root link's [v; ω; q̇]."""
        skel, R = self.skel, rotation(s["quat"][t])
        q, v = np.zeros(skel.getNumDofs()), np.zeros(skel.getNumDofs())
        q[self.free:self.free + 6] = dart.dynamics.FreeJoint.convertToPositions(
            dart.math.Isometry3(R, s["p"][t]))
        v[self.free:self.free + 3] = R.T @ s["w"][t]
        v[self.free + 3:self.free + 6] = R.T @ s["v"][t]
        q[self.dof], v[self.dof] = s["q"][t], s["qd"][t]
        skel.setPositions(q)
        skel.setVelocities(v)
        skel.clearExternalForces()
        for foot, force in zip(self.feet, s["forces"][t]):
            foot.setExtForce(force, np.zeros(3), False, True)
        S = np.zeros((skel.getNumDofs(), skel.getNumDofs()))
        S[self.free:self.free + 3, 3:6] = R.T
        S[self.free + 3:self.free + 6, 0:3] = R.T
        S[self.dof, 6 + np.arange(len(self.dof))] = 1.0
        trunk = skel.getRootBodyNode()
        assert np.allclose(trunk.getLinearVelocity(), s["v"][t], rtol=0, atol=1e-12)
        return S

    def mass_matrix(self, s, t):
        S = self.set_state(s, t)
        return S.T @ self.skel.getMassMatrix() @ S

    def inverse_dynamics(self, s, t):
        """[force, moment about the root link's origin (world axes), joint torques]."""
        S = self.set_state(s, t)
        R = rotation(s["quat"][t])
        w_b, v_b = R.T @ s["w"][t], R.T @ s["v"][t]
        a = np.zeros(self.skel.getNumDofs())
        a[self.free:self.free + 3] = R.T @ s["dw"][t]
        a[self.free + 3:self.free + 6] = R.T @ s["a"][t] - np.cross(w_b, v_b)
        a[self.dof] = s["qdd"][t]
        self.skel.setAccelerations(a)
        assert np.allclose(self.skel.getRootBodyNode().getLinearAcceleration(), s["a"][t],
                           rtol=0, atol=1e-12 * max(1.0, np.abs(a).max())), "acceleration"
        self.skel.computeInverseDynamics(True, False, False)
        return S.T @ self.skel.getForces()

    def forward_dynamics(self, s, t):
        """[root origin's classical acceleration, angular acceleration (world), q̈]."""
        self.set_state(s, t)
        tau = np.zeros(self.skel.getNumDofs())
        tau[self.dof] = s["tau"][t]
        self.skel.setForces(tau)
        self.skel.computeForwardDynamics()
        trunk = self.skel.getRootBodyNode()
        return np.concatenate([trunk.getLinearAcceleration(), trunk.getAngularAcceleration(),
                               self.skel.getAccelerations()[self.dof]])


def hexdyn_values(scene, s):
    """hexdyn's mass matrices, inverse dynamics and forward dynamics at the states s."""
    M = hexdyn.mass_matrix(scene, s["quat"], s["q"])
    tau = hexdyn.inverse_dynamics(scene, s["p"], s["quat"], s["q"], s["v"], s["w"], s["qd"],
                                  s["a"], s["dw"], s["qdd"], foot_forces=s["forces"])
    acc = hexdyn.forward_dynamics(scene, s["p"], s["quat"], s["q"], s["v"], s["w"], s["qd"],
                                  s["tau"], foot_forces=s["forces"])
    return M, tau, acc


def relative(a, b):
    return float(np.abs(a - b).max() / np.abs(b).max())


def differences(dart_robot, s, M, tau, acc):
    """Largest relative difference of DART's mass matrix, inverse and forward dynamics."""
    worst = np.zeros(3)
    for t in range(len(s["quat"])):
        worst[0] = max(worst[0], relative(dart_robot.mass_matrix(s, t), M["mass_matrix"][t]))
        h_tau = np.concatenate([tau["base_force"][t], tau["base_moment"][t],
                                tau["joint_torque"][t]])
        worst[1] = max(worst[1], relative(dart_robot.inverse_dynamics(s, t), h_tau))
        h_acc = np.concatenate([acc["base_linear_acceleration"][t],
                                acc["base_angular_acceleration"][t], acc["joint_acceleration"][t]])
        worst[2] = max(worst[2], relative(dart_robot.forward_dynamics(s, t), h_acc))
    return worst


def check_refusals(scene, s, joints):
    one = {k: v[0] for k, v in s.items()}
    short = one["q"][:-1]
    calls = {
        "mass_matrix": lambda: hexdyn.mass_matrix(scene, one["quat"], short),
        "inverse_dynamics": lambda: hexdyn.inverse_dynamics(
            scene, one["p"], one["quat"], short, one["v"], one["w"], one["qd"], one["a"],
            one["dw"], one["qdd"]),
        "forward_dynamics": lambda: hexdyn.forward_dynamics(
            scene, one["p"], one["quat"], short, one["v"], one["w"], one["qd"], one["tau"])}
    for name, call in calls.items():
        try:
            call()
            raise AssertionError(f"{name}: {joints - 1} joint angles accepted")
        except ValueError as e:
            want = (f"{name}: joint_position has shape ({joints - 1}), expected ({joints}) or "
                    f"(T, {joints})")
            assert str(e) == want, e


def check_robot(d, seed, name, legs, m, prismatic, rng):
    urdf, mass, joints = robot_urdf(seed, name, legs, m, prismatic)
    path = os.path.join(d, f"{name}.urdf")
    with open(path, "w") as f:
        f.write(urdf)
    scene = os.path.join(d, f"{name}.yaml")
    with open(scene, "w") as f:
        f.write(SCENE.format(name=name, urdf=path,
                             feet=", ".join(f"L{leg + 1}_foot" for leg in range(legs))))
    prismatic_index = [leg * m + j for leg, j in prismatic]
    s = random_states(rng, STATES, legs, legs * m, prismatic_index)
    M, tau, acc = hexdyn_values(scene, s)
    assert list(M["joint_names"]) == joints, f"{name}: legs {M['joint_names']}, expected {joints}"
    assert list(M["leg_names"]) == [f"L{leg + 1}" for leg in range(legs)], M["leg_names"]
    assert M["mass_matrix"].shape == (STATES, 6 + legs * m, 6 + legs * m)
    assert abs(M["mass_matrix"][0][0, 0] - mass) < 1e-12 * mass, "total mass"
    worst = differences(Dart(urdf, joints, legs), s, M, tau, acc)
    perturbed = robot_urdf(seed, name, legs, m, prismatic, perturb=True)[0]
    least = differences(Dart(perturbed, joints, legs), s, M, tau, acc)
    print(f"{name}: {legs} legs of {m} joints ({len(prismatic)} prismatic), {STATES} states; "
          f"largest relative difference to DART: mass matrix {worst[0]:.2g}, inverse dynamics "
          f"{worst[1]:.2g}, forward dynamics {worst[2]:.2g} (tolerance {TOLERANCE:g}); one foot "
          f"link {PERTURBED:g}x: {least[0]:.2g}, {least[1]:.2g}, {least[2]:.2g}")
    assert (worst <= TOLERANCE).all(), f"{name}: DART and hexdyn differ by {worst}"
    assert (least > 1e6 * TOLERANCE).all(), f"{name}: a perturbed foot link still agrees: {least}"
    check_refusals(scene, s, legs * m)


def main():
    args()
    if dart is None:
        print("skipped: python3-dartpy is not installed (pipelines/setup.sh installs it)")
        return 77
    rng = np.random.default_rng(SEED)
    with tempfile.TemporaryDirectory() as d:
        for i, robot in enumerate(ROBOTS):
            check_robot(d, SEED + i, *robot, rng)
    return 0


if __name__ == "__main__":
    sys.exit(main())
