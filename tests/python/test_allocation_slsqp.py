"""The allocation against an independent QP optimum: SciPy's SLSQP on DART's dynamics
(docs/validation/allocation.md#against-slsqp-on-every-robot).

For each scene given (default: configs/paper.yaml, every configs/robots/*.yaml, and the
paper scene twice more, with a torque limit that binds and with the exact cone), hexdyn runs
it. At sampled optimal instants (status 0; support switches, the samples nearest the friction
limit and the torque bounds among them) the allocation problem of
docs/theory/allocation.md is posed again from physics alone, without the program's matrices:

  - DART (Debian's python3-dartpy) gets the robot of the result's /model/urdf on a free
    trunk in the sample's state (/base/*, /joints/position, velocity, acceleration): its
    inverse dynamics without foot forces gives Q0, the linear Jacobians of the contact points
    /feet/position give J_i, so that the generalised forces are Q(F) = Q0 − Σ J_iᵀ F_i;
  - the unknowns are the support feet's forces in their contact frames [t1 t2 n] (n = +z on
    flat ground and treads, t1 the world x made orthogonal to n, t2 = n × t1;
    docs/theory/conventions.md#frames); swing feet carry none;
  - the six trunk rows of Q(F) vanish;
  - the drive torque of joint k is τ_k(F) + d_k, d_k = J_a q̈ + τ_c sgn(q̇) + b q̇ from the
    scene's resolved actuators (docs/theory/drive-train.md#drive-torque), 0 without them;
  - the objective is Σ_k w_k (τ_k + d_k)², w_k = 1 for allocation.objective torque_squared,
    R_k / (G_k k_t,k η_k)² over its largest for copper_loss
    (docs/theory/drive-train.md#objective);
  - per support foot f_n ≥ allocation.min_normal_force and its friction: the faces
    cos a f_t1 + sin a f_t2 ≤ μ cos(π/N) f_n, a = 2π f/N, of pyramid4 or pyramid8, or the
    cone μ² f_n² − f_t1² − f_t2² ≥ 0 (with f_n ≥ 0, the cone |f_t| ≤ μ f_n in a form
    SLSQP's gradients can take at the apex; docs/theory/allocation.md#friction-pyramid);
  - per joint of a support leg |τ_k + d_k| ≤ bound_k: allocation.torque_limit, or each
    joint's <limit effort> of the scene's URDF file for `effort`, or with an actuator
    min(peak_torque, G k_t η (V − G k_t |q̇|) / R) (docs/theory/drive-train.md#torque-bound).

Samples with a leg inside its touchdown transient are left out: that leg's normal force is
the transient's, an input from the contact law, not an unknown (docs/theory/contact.md).

scipy.optimize.minimize(method="SLSQP") solves it from zero forces with exact gradients,
then once more from its answer. Its forces must equal /contacts/force, and its joint torques
Q0 − Σ J_iᵀ F_i /joints/torque, to TOLERANCE relative to the sample's largest foot force and
largest |τ|. The objective is strictly convex in the forces (each support leg's 3×3
Jacobian is regular away from singular poses), so the optimum is unique. SLSQP stops when
its objective, scaled to order one, changes by less than FTOL = 1e-14; near a strict
minimum the forces are then within about √FTOL = 1e-7 of the optimum, relative to their
scale, at worst. TOLERANCE = 1e-6 is ten times that; the differences measured are 2e-10 to
6e-8 (docs/validation/allocation.md).

The check can fail: on each scene one sample is solved again with its trunk acceleration
changed by PERTURBATION along x (another instant's dynamics), and its optimum must differ
from the file's by more than 100 TOLERANCE. With actuators, the optimum without the drive
offset d (the link torques' Σ τ², on the sample where d is largest) must differ from the
file's by more than TOLERANCE: the comparison would catch a drive offset left out.

    /usr/bin/python3 tests/python/test_allocation_slsqp.py HEXDYN SOURCE_DIR [SCENE ...]
"""
import argparse
import glob
import os
import sys
import tempfile
import xml.etree.ElementTree as ET

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import cli_run, text  # noqa: E402
from test_drive_dart import DartRobot, dart, read_result, rotation  # noqa: E402

try:
    from scipy.optimize import minimize
except ImportError:
    minimize = None

TOLERANCE = 1e-6          # relative to the sample's largest foot force and largest |τ|
FTOL = 1e-14              # SLSQP's stopping test on the scaled objective
RESTARTS = 2              # SLSQP runs, each from the last one's answer
SAMPLES = 8               # instants per scene: half support switches, half spread over the run
PERTURBATION = 0.1        # m/s², trunk acceleration added along x in the check of the check
LOW_TORQUE_LIMIT = 1.7    # N m, the paper scene's allocation.torque_limit in the last case
SWING, IMPACT, SUPPORT = 0, 1, 2   # /contacts/phase


def torque_bounds(r):
    """(J,) bound on |τ_drive| per joint in /model/joint_names order and (J,) drive offsets'
    coefficients {armature, coulomb_friction, viscous_friction}, from the resolved scene."""
    config = r["config"]
    limit = config["allocation"]["torque_limit"]
    if limit == "effort":
        urdf = config["robot"]["urdf"]   # absolute in the resolved configuration
        effort = {j.get("name"): float(j.find("limit").get("effort"))
                  for j in ET.parse(urdf).getroot().iter("joint") if j.find("limit") is not None}
        bound = np.array([effort[n] for n in r["joints"]])
    else:
        bound = np.full(len(r["joints"]), float(limit))
    drive = {k: np.zeros(len(r["joints"]))
             for k in ("armature", "coulomb_friction", "viscous_friction")}
    weight = np.ones(len(r["joints"]))
    joints = ((config.get("actuators") or {}).get("joints")) or {}
    for k, name in enumerate(r["joints"]):
        a = joints.get(name)
        if not a:
            continue
        for key in drive:
            drive[key][k] = float(a.get(key, 0.0))
        gain = float(a["gear_ratio"]) * float(a["torque_constant"]) * float(
            a.get("gear_efficiency", 1))
        weight[k] = float(a["resistance"]) / gain**2
    if config["allocation"].get("objective", "torque_squared") == "copper_loss":
        weight /= weight.max()
    else:
        weight[:] = 1.0
    return bound, drive, weight, joints


def sample_bound(r, t, bound, joints):
    """Each joint's bound at sample t: the actuator's torque-speed line, clipped by its peak."""
    b = bound.copy()
    for k, name in enumerate(r["joints"]):
        a = joints.get(name) or {}
        limits = []
        if "peak_torque" in a:
            limits.append(float(a["peak_torque"]))
        if "voltage" in a:
            g, kt = float(a["gear_ratio"]), float(a["torque_constant"])
            eta, res = float(a.get("gear_efficiency", 1)), float(a["resistance"])
            limits.append(max(0.0, g * kt * eta * (float(a["voltage"]) - g * kt *
                                                    abs(r["/joints/velocity"][t][k])) / res))
        if limits:
            b[k] = min(limits)
    return b


def drive_offset(r, t, drive):
    qd, qdd = r["/joints/velocity"][t], r["/joints/acceleration"][t]
    return drive["armature"] * qdd + drive["coulomb_friction"] * np.sign(qd) + \
        drive["viscous_friction"] * qd


def dart_split(robot, r, t, trunk_acceleration=np.zeros(3)):
    """(Q0, {leg: J}) at sample t: DART's generalised forces without foot forces (free-joint
    coordinates first) and each foot's linear Jacobian at its contact point, world axes."""
    skel = robot.skel
    robot.set_state(skel, r, t, np.zeros(len(robot.names)))
    skel.clearExternalForces()
    R = rotation(r["/base/orientation"][t])
    w_B = R.T @ r["/base/angular_velocity"][t]
    v_B = R.T @ r["/base/linear_velocity"][t]
    a = np.zeros(skel.getNumDofs())
    a[robot.free:robot.free + 3] = R.T @ r["/base/angular_acceleration"][t]
    a[robot.free + 3:robot.free + 6] = R.T @ (r["/base/linear_acceleration"][t] +
                                              trunk_acceleration) - np.cross(w_B, v_B)
    a[robot.dof] = r["/joints/acceleration"][t]
    skel.setAccelerations(a)
    skel.computeInverseDynamics(False, False, False)
    q0 = skel.getForces().copy()
    jacobians = {}
    for leg, foot in enumerate(robot.feet):
        body = skel.getBodyNode(foot)
        T = body.getWorldTransform()
        point = r["/feet/position"][t][leg]
        # A sphere foot's contact point lies straight below its centre (n = +z here).
        assert np.abs((point - T.translation())[:2]).max() < 1e-9, \
            f"sample {t}: {r['legs'][leg]}'s contact point is not below its foot body"
        # The skeleton's Jacobian: every dof's column (the body's own has its chain's only).
        jacobians[leg] = skel.getLinearJacobian(body, T.rotation().T @ (point - T.translation()))
    return q0, jacobians


def contact_frame():
    """[t1 t2 n] of a foot on flat ground or a tread (docs/theory/conventions.md#frames)."""
    n = np.array([0.0, 0.0, 1.0])
    t1 = np.array([1.0, 0.0, 0.0]) - n[0] * n
    t1 /= np.linalg.norm(t1)
    return np.column_stack([t1, np.cross(n, t1), n])


class Problem:
    """The allocation of one sample in the contact-frame forces x of its support legs."""

    def __init__(self, robot, r, t, setup, trunk_acceleration=np.zeros(3), with_drive=True):
        bound, drive, weight, joints = setup
        q0, jac = dart_split(robot, r, t, trunk_acceleration)
        self.support = [leg for leg, p in enumerate(r["/contacts/phase"][t]) if p == SUPPORT]
        C = contact_frame()
        # Generalised force per unit contact-frame force: columns of −Σ J_iᵀ C.
        G = np.column_stack([-(jac[leg].T @ C) for leg in self.support])
        trunk = list(range(robot.free, robot.free + 6))
        self.q0, self.G = q0, G
        self.trunk_q0, self.trunk_G = q0[trunk], G[trunk]
        self.joint_q0, self.joint_G = q0[robot.dof], G[robot.dof]
        self.d = drive_offset(r, t, drive) if with_drive else np.zeros(len(robot.dof))
        self.w = weight
        self.bound = sample_bound(r, t, bound, joints)
        alloc = r["config"]["allocation"]
        self.mu = float(r["config"]["contact"]["friction_coefficient"])
        self.fn_min = float(alloc.get("min_normal_force", 0.0))
        self.friction = alloc.get("friction", "pyramid4")
        leg_of_joint = np.repeat(np.arange(len(r["legs"])), np.diff(leg_starts(r)))
        self.rows = [k for k in range(len(robot.dof)) if leg_of_joint[k] in self.support]
        self.C = C
        self.force_scale = r["mass"] * 9.81
        self.torque_scale = max(1.0, float(np.abs(self.joint_q0 + self.d).max()))

    def drive_torques(self, x):
        return self.joint_q0 + self.joint_G @ x + self.d

    def solve(self):
        s, ts = self.force_scale, self.torque_scale
        n = self.G.shape[1]

        def objective(y):
            e = self.drive_torques(s * y) / ts
            return float(self.w @ e**2), 2 * s / ts * (self.joint_G.T @ (self.w * e))

        # On two feet (a trot's diagonal) the trunk rows have rank 5: the moment about the line
        # through the feet is none of theirs. SLSQP gets the rows on trunk_G's range; the row
        # left out holds for the file's state alone, to the allocation's threshold of a
        # violated row (1e-6, allocation/qp.hpp), or the sample would be relaxed.
        U, sv, _ = np.linalg.svd(self.trunk_G)
        rank = int(np.count_nonzero(sv > 1e-9 * sv[0]))
        left_out = U[:, rank:].T @ self.trunk_q0
        assert np.abs(left_out).max(initial=0.0) <= 1e-6 * max(1.0, np.abs(self.trunk_q0).max()), \
            f"the trunk rows outside the feet's reach miss by {np.abs(left_out).max():.3g}"
        P = U[:, :rank].T
        cons = [{"type": "eq", "fun": lambda y: P @ (self.trunk_q0 + self.trunk_G @ (s * y)) / s,
                 "jac": lambda y: P @ self.trunk_G}]
        rows_G = self.joint_G[self.rows]
        cons.append({"type": "ineq",
                     "fun": lambda y: np.concatenate([
                         self.bound[self.rows] - self.drive_torques(s * y)[self.rows],
                         self.bound[self.rows] + self.drive_torques(s * y)[self.rows]]) / ts,
                     "jac": lambda y: np.vstack([-rows_G, rows_G]) * s / ts})
        A, b = self.linear_contact_rows(n)
        cons.append({"type": "ineq", "fun": lambda y: (A @ (s * y) - b) / s,
                     "jac": lambda y: A})
        if self.friction == "cone":
            cons.append({"type": "ineq", "fun": lambda y: self.cone(y),
                         "jac": lambda y: self.cone_jacobian(y)})
        y = np.zeros(n)
        for _ in range(RESTARTS):
            res = minimize(objective, y, jac=True, method="SLSQP", constraints=cons,
                           options={"ftol": FTOL, "maxiter": 2000})
            worst = max(float(np.abs(np.minimum(0, c["fun"](res.x)) if c["type"] == "ineq"
                                     else c["fun"](res.x)).max()) for c in cons)
            # Status 8, "positive directional derivative for linesearch": the line search found
            # no descent at the precision of the scaled objective, which happens at the optimum
            # of a well-scaled problem too. Feasible to 1e-9, the answer is kept: its comparison
            # with the file (below) says whether it is the optimum.
            if not res.success and not (res.status == 8 and worst <= 1e-9):
                raise AssertionError(f"SLSQP: {res.message} (run {_ + 1}, {res.nit} "
                                     f"iterations, largest violation {worst:.3g})")
            y = res.x
        return s * res.x

    def active(self, x):
        """(friction rows, torque rows) that hold with equality at x, to 1e-7 of their scale."""
        A, b = self.linear_contact_rows(len(x))
        friction = int(np.count_nonzero(np.abs(A @ x - b) < 1e-7 * self.force_scale)) - int(
            np.count_nonzero(np.abs(x[2::3] - self.fn_min) < 1e-7 * self.force_scale))
        if self.friction == "cone":
            friction = int(np.count_nonzero(np.abs(self.cone(x)) < 1e-7 * self.force_scale**2))
        tau = self.drive_torques(x)[self.rows]
        torque = int(np.count_nonzero(self.bound[self.rows] - np.abs(tau) <
                                      1e-7 * self.bound[self.rows]))
        return friction, torque

    def linear_contact_rows(self, n):
        """A x ≥ b: each support foot's minimum normal force and friction faces."""
        rows, rhs = [], []
        faces = {"pyramid4": 4, "pyramid8": 8}.get(self.friction, 0)
        for i in range(len(self.support)):
            row = np.zeros(n)
            row[3 * i + 2] = 1.0
            rows.append(row)
            rhs.append(self.fn_min)
            for f in range(faces):
                a = 2 * np.pi * f / faces
                row = np.zeros(n)
                row[3 * i:3 * i + 3] = [-np.cos(a), -np.sin(a), self.mu * np.cos(np.pi / faces)]
                rows.append(row)
                rhs.append(0.0)
        return np.array(rows), np.array(rhs)

    def cone(self, y):
        x = y.reshape(-1, 3)
        return self.mu**2 * x[:, 2]**2 - x[:, 0]**2 - x[:, 1]**2

    def cone_jacobian(self, y):
        x = y.reshape(-1, 3)
        out = np.zeros((len(x), 3 * len(x)))
        for i, (t1, t2, fn) in enumerate(x):
            out[i, 3 * i:3 * i + 3] = [-2 * t1, -2 * t2, 2 * self.mu**2 * fn]
        return out

    def world_forces(self, x, legs):
        """(L, 3) world-frame foot forces of x."""
        F = np.zeros((legs, 3))
        for i, leg in enumerate(self.support):
            F[leg] = self.C @ x[3 * i:3 * i + 3]
        return F


def leg_starts(r):
    """First joint of each leg and the joint count at the end, from /model/leg_mapping's
    joint lists (or the paper robot's names L1_coxa …: the joints' leg prefix)."""
    prefix = [n.split("_")[0] for n in r["joints"]]
    mapping = r.get("mapping")
    if mapping:
        counts = [len(line.split(":")[1].split(" foot")[0].split()) for line in mapping]
    else:
        counts = [prefix.count(leg) for leg in r["legs"]]
    return np.concatenate([[0], np.cumsum(counts)])


def pick_samples(r):
    """Optimal samples with no leg inside a touchdown transient: SAMPLES/2 support switches
    (the support set differs from the previous sample's) and SAMPLES/2 others, evenly."""
    status, phase = r["/solver/status"], r["/contacts/phase"]
    ok = [t for t in range(len(status)) if status[t] == 0 and not (phase[t] == IMPACT).any()]
    switch = [t for t in ok
              if t > 0 and ((phase[t] == SUPPORT) != (phase[t - 1] == SUPPORT)).any()]
    rest = [t for t in ok if t not in switch]
    assert len(switch) >= 1 and len(rest) >= SAMPLES // 2, \
        f"{len(switch)} optimal support switches and {len(rest)} other optimal samples"

    def spread(ts, k):
        picks = np.unique(np.linspace(0, len(ts) - 1, min(k, len(ts))).round())
        return [ts[int(i)] for i in picks]
    return sorted(spread(switch, SAMPLES // 2) + spread(rest, SAMPLES - SAMPLES // 2)), switch, ok


def torque_load(r, t, setup):
    bound, drive, _, joints = setup
    return float((np.abs(r["/joints/torque"][t] + drive_offset(r, t, drive)) /
                  sample_bound(r, t, bound, joints)).max())


def difference(problem, x, r, t):
    """(force error, torque error), each relative to the sample's largest."""
    F = problem.world_forces(x, len(r["legs"]))
    F_file = np.nan_to_num(r["/contacts/force"][t])
    tau = problem.joint_q0 + problem.joint_G @ x
    tau_file = r["/joints/torque"][t]
    return (float(np.abs(F - F_file).max() / max(1e-12, np.abs(F_file).max())),
            float(np.abs(tau - tau_file).max() / max(1e-12, np.abs(tau_file).max())))


def check_scene(hexdyn, scene, d, sets=()):
    out = os.path.join(d, "result.h5")
    rc, err = cli_run(hexdyn, scene, out, sets)
    assert rc == 0, f"{scene}: {err}"
    r = read_result(out)
    with h5py.File(out, "r") as f:
        r["/contacts/utilized_friction"] = f["/contacts/utilized_friction"][()]
        if "/model/leg_mapping" in f:
            r["mapping"] = [text(v) for v in f["/model/leg_mapping"][()]]
    terrain = r["config"]["terrain"]["type"]
    assert terrain in ("flat", "stairs"), f"{scene}: terrain {terrain}: normals other than +z"
    robot = DartRobot(r)
    setup = torque_bounds(r)
    samples, switch, ok = pick_samples(r)
    # The samples nearest the friction limits and the torque bounds, where their rows bind.
    grip = np.nan_to_num(r["/contacts/utilized_friction"]).max(axis=1)
    samples = sorted(set(samples) | {max(ok, key=lambda t: grip[t]),
                                     max(ok, key=lambda t: torque_load(r, t, setup))})
    drive = setup[1]
    has_drive = any(np.abs(v).max() > 0 for v in drive.values())
    if has_drive:
        # The sample whose drive offset is largest: there, leaving it out must show.
        t_drive = max(ok, key=lambda t: float(np.abs(drive_offset(r, t, drive)).max()))
        samples = sorted(set(samples) | {t_drive})
    worst_force = worst_torque = 0.0
    active = np.zeros(2, dtype=int)
    for t in samples:
        problem = Problem(robot, r, t, setup)
        # DART's split is linear: Q0 − Σ J_iᵀ F_i at the file's forces is DART's inverse
        # dynamics with them (checked, so that a wrong Jacobian point cannot hide).
        F_file = np.nan_to_num(r["/contacts/force"][t])
        x_file = np.concatenate([problem.C.T @ F_file[leg] for leg in problem.support])
        tau_split = problem.joint_q0 + problem.joint_G @ x_file
        assert np.abs(tau_split - r["/joints/torque"][t]).max() <= \
            1e-9 * max(1.0, np.abs(r["/joints/torque"][t]).max()), f"sample {t}: split differs"
        x = problem.solve()
        active += problem.active(x)
        e_force, e_torque = difference(problem, x, r, t)
        worst_force, worst_torque = max(worst_force, e_force), max(worst_torque, e_torque)
        assert e_force <= TOLERANCE and e_torque <= TOLERANCE, \
            f"{scene} sample {t} (support " \
            f"{[r['legs'][leg] for leg in problem.support]}): SLSQP's forces differ by " \
            f"{e_force:.3g}, torques by {e_torque:.3g} (tolerance {TOLERANCE:g})"
    # The check of the check: another instant's dynamics gives other forces. On the sample
    # farthest from its torque bounds, so that the perturbed problem stays feasible.
    # On three feet or more, so that the perturbed trunk rows stay within the feet's reach.
    wide = [t for t in samples if np.count_nonzero(r["/contacts/phase"][t] == SUPPORT) >= 3]
    t = min(wide or samples, key=lambda t: torque_load(r, t, setup))
    perturbed = Problem(robot, r, t, setup, np.array([PERTURBATION, 0.0, 0.0]))
    moved = max(difference(perturbed, perturbed.solve(), r, t))
    assert moved > 100 * TOLERANCE, f"{scene}: a perturbed sample moved the optimum by {moved:.3g}"
    line = (f"{' '.join([os.path.basename(scene), *sets])}: {len(samples)} samples "
            f"({len([t for t in samples if t in switch])} support switches): forces to "
            f"{worst_force:.2g}, torques to {worst_torque:.2g} (tolerance {TOLERANCE:g}), "
            f"{active[0]} friction and {active[1]} torque rows active; "
            f"perturbed instant differs by {moved:.2g}")
    if has_drive:
        # Leaving the drive offset out must move the optimum where the offset is largest on the
        # joints the foot forces load (a swing leg's offset moves no force), unless active
        # friction faces pin the forces: of the 40 samples of largest offset, the 8 whose
        # offset on those joints is largest, the largest move.
        by_offset = sorted(ok, key=lambda t: -float(np.abs(drive_offset(r, t, drive)).max()))

        def loaded_offset(t):
            loaded = np.abs(Problem(robot, r, t, setup).joint_G).sum(axis=1) > 0
            return float(np.abs(drive_offset(r, t, drive)[loaded]).max(initial=0.0))
        bare = 0.0
        for t_bare in sorted(by_offset[:40], key=loaded_offset)[-8:]:
            bare_problem = Problem(robot, r, t_bare, setup, with_drive=False)
            bare = max(bare, *difference(bare_problem, bare_problem.solve(), r, t_bare))
        line += f", without the drive offset by {bare:.2g}"
    print(line)
    return bare if has_drive else None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("hexdyn")
    ap.add_argument("source")
    ap.add_argument("scenes", nargs="*")
    args = ap.parse_args()
    if dart is None or minimize is None:
        print("skipped: python3-dartpy or python3-scipy is not installed "
              "(pipelines/setup.sh installs both)")
        return 77
    src = os.path.realpath(args.source)
    paper = os.path.join(src, "configs", "paper.yaml")
    cases = [(s, ()) for s in args.scenes] or [(paper, ())] + [
        (s, ()) for s in sorted(glob.glob(os.path.join(src, "configs", "robots", "*.yaml")))]
    if not args.scenes:
        # No shipped scene's optimal samples reach a torque bound: the paper scene with a lower
        # one does (its rows bind on about 40 optimal samples). No shipped scene has the exact
        # cone: the paper scene with it.
        cases += [(paper, (f"allocation.torque_limit={LOW_TORQUE_LIMIT}",)),
                  (paper, ("allocation.friction=cone",))]
    with tempfile.TemporaryDirectory() as d:
        moves = [check_scene(args.hexdyn, scene, d, sets) for scene, sets in cases]
    # The check of the drive offset: leaving it out moves the optimum beyond the tolerance on
    # some scene with a drive train (a gentle scene's may not: its forces hardly feel it).
    moves = [m for m in moves if m is not None]
    assert not moves or max(moves) > 10 * TOLERANCE, \
        f"the drive offset moved no scene's optimum beyond {10 * TOLERANCE:g}: {moves}"
    return 0


if __name__ == "__main__":
    sys.exit(main())
