#!/usr/bin/python3
"""Checks a hexdyn-result file against the contract (src/hexdyn/io/schema.hpp,
docs/user/output.md).

    /usr/bin/python3 analysis/check_result.py FILE.h5 [--expect-mass 6.7] [--dynamics]

Checks: schema and /meta attributes; every model and kinematic dataset present with
its shape, element type and `units`; finite values; URDF total mass = /model/total_mass
(and = --expect-mass within 1e-9); URDF forward kinematics from /base/position,
/base/orientation and /joints/position reproduces /feet/position within 1e-9 m at
every sample; for a robot with sphere feet (a file with /feet/center), it reproduces
/feet/center instead, and /feet/center - /feet/position is r n on every support sample,
r the radius of the sphere <collision> of L{i}_foot in /model/urdf and n the terrain
normal, with |/feet/center - /feet/position| = r on every sample
(docs/theory/model.md#sphere-feet). With --dynamics, the dynamics datasets as well, and on every sample with
/solver/status 0 (optimal) the constraints the allocation must meet, evaluated from the
file's data alone, against the fixed threshold VIOLATION_THRESHOLD * max(1, |bound|) of
allocation/qp.hpp kViolationThreshold (1e-6 N or N m):
  - sum of the foot forces = sum over the URDF's links of m (a_com - g), with each link's
    COM acceleration from a forward recursion over the URDF from /base/* and /joints/*
    (the three force rows of the trunk equations; independent of hexdyn's RNEA);
  - |tau_k| <= allocation.torque_limit for every joint; with actuators (a file with
    /joints/drive_torque), instead |tau_drive_k| <= min(peak_torque, G k_t eta (V - G k_t
    |omega_k|) / R) (clipped at 0; the allocation's limit for a joint with neither), from
    each joint's values under actuators.joints in /meta config_yaml, and tau_drive_k =
    tau_k + J_a omega_dot_k + tau_c sgn(omega_k) + b omega_k
    (docs/theory/drive-train.md);
  - feet in support: F_n >= allocation.min_normal_force and |F_t| <= mu F_n (the exact
    cone, which contains every inscribed pyramid); feet in swing: F = 0;
with the limits, mu and the terrain normal read from /meta config_yaml.
Prints one line per failure and a summary "check_result: P passed, F failed"; exits 1 on
any failure.
"""

import argparse
import re
import sys
import xml.etree.ElementTree as ET


import numpy as np  # noqa: E402
import yaml  # noqa: E402

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from hexdyn import results as hr  # noqa: E402
from urdf_fk import UrdfRobot  # noqa: E402

FK_TOLERANCE_M = 1e-9
MASS_TOLERANCE_KG = 1e-9
VIOLATION_THRESHOLD = 1e-6  # N or N m, times max(1, |bound|): allocation/qp.hpp kViolationThreshold
GRAVITY = np.array([0.0, 0.0, -9.81])


class Checks:
    def __init__(self, verbose=False):
        self.passed = 0
        self.failed = 0
        self.verbose = verbose

    def check(self, ok, what, detail=""):
        if ok:
            self.passed += 1
            if self.verbose:
                print(f"  ok    {what}")
        else:
            self.failed += 1
            print(f"  FAIL  {what}" + (f": {detail}" if detail else ""))
        return ok


def dtype_name(value):
    if isinstance(value, (str, list)):
        return "string"
    return np.asarray(value).dtype.name


def check_datasets(c, res, table, samples, impacts=None, messages=None):
    for path, (shape, units, element) in table.items():
        if not c.check(path in res, f"{path} present"):
            continue
        # L and J: the numbers of the file's leg and joint names.
        names = {k: len(res[p]) for k, p in hr.SIZE_NAMES.items() if p in res}
        want = hr.expected_shape(shape, samples, impacts, messages,
                                 Y=res.shapes.get("/gait/cycle_start", (None,))[0],
                                 K=res.shapes.get("/terrain/y", (None,))[0], **names)
        got = res.shapes[path]
        c.check(got == want, f"{path} shape {want}", f"got {got}")
        c.check(dtype_name(res[path]) == element, f"{path} element {element}",
                f"got {dtype_name(res[path])}")
        c.check(res.units.get(path) == (units or None), f"{path} units {units or 'none'}",
                f"got {res.units.get(path)!r}")
        if path in NON_FINITE_BY_CONTRACT:
            check_grip_values(c, res, path)
        elif element == "float64":
            c.check(bool(np.all(np.isfinite(res[path]))), f"{path} finite",
                    "NaN or infinity present")


# Datasets whose contract has NaN in places (docs/theory/grip.md): the utilised friction is NaN
# on swing legs and where a relaxed sample's force does not press the foot, the required
# friction NaN where no friction coefficient suffices. Neither holds an infinity.
NON_FINITE_BY_CONTRACT = {"/contacts/utilized_friction", "/contacts/required_friction"}


def check_grip_values(c, res, path):
    values = np.asarray(res[path], dtype=float)
    c.check(bool(np.all(np.isnan(values) | (values >= 0))), f"{path} non-negative or NaN",
            "negative values present")
    c.check(not bool(np.any(np.isinf(values))), f"{path} never infinite",
            f"{int(np.sum(np.isinf(values)))} infinite entries")
    if path == "/contacts/utilized_friction" and "/contacts/phase" in res:
        swing = np.asarray(res["/contacts/phase"]) == 0
        c.check(bool(np.all(np.isnan(values[swing]))), f"{path} NaN on every swing leg",
                f"{int(np.sum(~np.isnan(values[swing])))} swing entries are numbers")
        if "/solver/status" in res:
            optimal = np.asarray(res["/solver/status"]) == 0
            odd = np.isnan(values) & ~swing & optimal[:, None]
            c.check(not bool(np.any(odd)), f"{path} a number on the contact legs of optimal "
                    "samples", f"{int(np.sum(odd))} entries are NaN")


def check_meta(c, res):
    for key in hr.META_ATTRIBUTES:
        c.check(key in res.meta, f"/meta attribute {key}")
    created = str(res.meta.get("created_utc", ""))
    c.check(re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", created) is not None,
            "/meta created_utc is ISO 8601 UTC", repr(created))
    try:
        config = yaml.safe_load(res.meta.get("config_yaml", ""))
        c.check(isinstance(config, dict), "/meta config_yaml is a YAML mapping",
                f"got {type(config).__name__}")
    except yaml.YAMLError as e:
        c.check(False, "/meta config_yaml parses", str(e).splitlines()[0])


def check_leg_joint_counts(c, res):
    """/model/leg_joint_counts: each leg's joints, which /model/joint_names lists leg by leg
    (hexdyn.leg_joints groups them), summing to the joint count."""
    path = "/model/leg_joint_counts"
    if path not in res or "/model/joint_names" not in res or "/model/leg_names" not in res:
        return
    counts = [int(n) for n in res[path]]
    J = len(res["/model/joint_names"])
    c.check(sum(counts) == J, f"{path} sums to the {J} joints", f"got {counts}")
    try:
        grouped = [len(leg) for leg in hr.leg_joints(res)]
    except ValueError as e:
        c.check(False, "the joints group by leg", str(e))
        return
    c.check(grouped == counts, f"{path} {counts}: the joints of each leg",
            f"/model/joint_names groups as {grouped}")


def check_kinematics(c, res, expect_mass):
    T = res.samples
    # /model/leg_joint_counts is new in layout version 4.
    model = {p: v for p, v in hr.MODEL_DATASETS.items()
             if p != hr.LEG_JOINT_COUNTS or int(res.meta.get("schema_version", 0)) >= 4}
    check_datasets(c, res, model, T)
    check_datasets(c, res, hr.KINEMATIC_DATASETS, T)
    # A URDF robot's joints keep the description's names, in hexdyn's order: the order
    # /model/leg_mapping lists them ("L1: J1 J2 J3 foot ...", L2: ...). hexdyn's own URDF
    # (every other robot): leg by leg, the moving joints from the root to the leg's foot
    # link, hip to foot (urdf_fk.UrdfRobot.chain_joints).
    joint_order = None
    if "/model/leg_mapping" in res:
        joint_order = tuple(w for e in res["/model/leg_mapping"]
                            for w in str(e).split()[1:str(e).split().index("foot")])
    if "/model/leg_names" in res:
        n = len(res["/model/leg_names"])
        c.check(tuple(res["/model/leg_names"]) == tuple(f"L{i}" for i in range(1, n + 1)),
                f"/model/leg_names L1 ... L{n}")
    check_leg_joint_counts(c, res)
    if "/time" in res and T > 1:
        c.check(bool(np.all(np.diff(res["/time"]) > 0)), "/time strictly increasing")
    if "/base/orientation" in res:
        err = np.max(np.abs(np.linalg.norm(res["/base/orientation"], axis=1) - 1.0), initial=0.0)
        c.check(err < 1e-9, "/base/orientation unit quaternions", f"max |norm - 1| = {err:.3g}")
    if "/contacts/phase" in res:
        c.check(bool(np.isin(res["/contacts/phase"], (0, 1, 2)).all()),
                "/contacts/phase values in {0, 1, 2}")

    try:
        robot = UrdfRobot(res.urdf, joint_order=joint_order)
    except Exception as e:  # any parse problem is a failed check, not a crash
        c.check(False, "/model/urdf parses", str(e))
        return
    c.check(True, "/model/urdf parses")
    if "/model/joint_names" in res:
        c.check(tuple(res["/model/joint_names"]) == robot.joint_order, "/model/joint_names order",
                f"{tuple(res['/model/joint_names'])} against {robot.joint_order}")
    legs = tuple(res["/model/leg_names"]) if "/model/leg_names" in res else ()
    c.check(robot.foot_links == tuple(f"{leg}_foot" for leg in legs),
            "URDF has a link <leg>_foot per leg of /model/leg_names", f"got {robot.foot_links}")
    if "/model/total_mass" in res:
        stored = float(res["/model/total_mass"])
        c.check(abs(robot.total_mass - stored) <= MASS_TOLERANCE_KG,
                "URDF total mass = /model/total_mass",
                f"URDF {robot.total_mass!r} kg, dataset {stored!r} kg")
    if expect_mass is not None:
        c.check(abs(robot.total_mass - expect_mass) <= MASS_TOLERANCE_KG,
                f"URDF total mass = {expect_mass} kg", f"got {robot.total_mass!r} kg")
    feet_path = "/feet/center" if "/feet/center" in res else "/feet/position"
    if feet_path == "/feet/center":
        check_sphere_feet(c, res)
    needed = ("/base/position", "/base/orientation", "/joints/position", feet_path)
    if all(p in res for p in needed) and len(robot.foot_links) == len(legs) and T > 0:
        try:
            feet = robot.foot_positions(res["/base/position"], res["/base/orientation"],
                                        res["/joints/position"])
        except ValueError as e:
            c.check(False, "URDF FK runs", str(e))
            return
        err = np.linalg.norm(feet - res[feet_path], axis=2)
        t_worst, leg_worst = np.unravel_index(np.argmax(err), err.shape)
        c.check(err.max() <= FK_TOLERANCE_M,
                f"URDF FK reproduces {feet_path} within {FK_TOLERANCE_M:g} m ({T} samples)",
                f"max error {err.max():.3g} m at sample {t_worst} "
                f"(t = {res['/time'][t_worst]:.6g} s), leg {legs[leg_worst]}")


def foot_radii(urdf_text, legs):
    """The radius of the sphere <collision> of each link <leg>_foot of `legs` (0: none)."""
    links = {link.get("name"): link for link in ET.fromstring(urdf_text).iter("link")}
    radii = []
    for leg in legs:
        sphere = links[f"{leg}_foot"].find("collision/geometry/sphere")
        radii.append(0.0 if sphere is None else float(sphere.get("radius")))
    return np.array(radii)


def check_sphere_feet(c, res):
    """/feet/center - /feet/position: r n in support, of length r always."""
    config = yaml.safe_load(res.meta.get("config_yaml", "")) or {}
    r = foot_radii(res.urdf, hr.leg_names(res))
    center, contact = np.asarray(res["/feet/center"]), np.asarray(res["/feet/position"])
    c.check(bool((r > 0).any()), "/model/urdf gives a sphere foot", f"radii {r}")
    length = np.linalg.norm(center - contact, axis=2)
    err = np.abs(length - r).max(initial=0.0)
    c.check(err <= FK_TOLERANCE_M, "|/feet/center - /feet/position| = foot radius",
            f"max error {err:.3g} m")
    support = np.asarray(res["/contacts/phase"]) != hr.PHASE_SWING
    offset = r[None, :, None] * terrain_normal(config, center)
    err = np.linalg.norm(center - contact - offset, axis=2)[support].max(initial=0.0)
    c.check(err <= FK_TOLERANCE_M, "/feet/center = /feet/position + r n in support",
            f"max error {err:.3g} m")


def check_dynamics(c, res):
    T = res.samples
    n = res.shapes.get("/impacts/leg", (None,))[0]
    m = res.shapes.get("/solver/messages", (None,))[0]
    check_datasets(c, res, hr.DYNAMICS_DATASETS, T, n, m)
    if "/impacts/leg" in res:
        legs = np.asarray(res["/impacts/leg"])
        c.check(bool(np.all((legs >= 0) & (legs <= 5))), "/impacts/leg values in 0..5")
    if "/solver/status" in res:
        c.check(bool(np.isin(res["/solver/status"], (0, 1, 2)).all()),
                "/solver/status values in {0, 1, 2}")
    # The file integrates to what it reports (docs/theory/output-grid.md#energy-from-the-samples).
    if all(p in res for p in ("/time", "/power/total", "/energy/total", "/energy/cycle")):
        t, P = np.asarray(res["/time"], float), np.asarray(res["/power/total"], float)
        E = float(res["/energy/total"])
        rule = res.meta.get("energy_rule", hr.ENERGY_RULE_TRAPEZOID)  # version 2: the trapezoid
        if rule == hr.ENERGY_RULE_TRAPEZOID:
            integral = float(np.sum(0.5 * np.diff(t) * (P[1:] + P[:-1])))
        else:
            integral = float(np.sum(hr.energy_by_rule(t, res["/power/per_joint"],
                                                      res.get("/sample_kind"), rule)))
        c.check(abs(integral - E) <= 1e-9 * abs(E), f"{rule} rule over /time = /energy/total",
                f"{integral!r} against {E!r}")
        cycles = float(np.sum(res["/energy/cycle"]))
        c.check(abs(cycles - E) <= 1e-9 * abs(E), "sum of /energy/cycle = /energy/total",
                f"{cycles!r} against {E!r}")


def link_com_accelerations(robot, res):
    """{link: COM acceleration (T,3)} in the world frame, by a forward recursion of angular
    velocity, angular acceleration and origin acceleration over the URDF tree."""
    from urdf_fk import axis_rotation, quaternion_to_matrix
    q = np.asarray(res["/joints/position"], float)
    qd = np.asarray(res["/joints/velocity"], float)
    qdd = np.asarray(res["/joints/acceleration"], float)
    # Joint columns by the file's own names (a URDF robot keeps its description's names).
    names = [str(hr.decode_text(n)) for n in res["/model/joint_names"]]
    index = {name: k for k, name in enumerate(names)}
    R0 = quaternion_to_matrix(np.asarray(res["/base/orientation"], float))
    state = {robot.root: (R0, np.asarray(res["/base/angular_velocity"], float),
                          np.asarray(res["/base/angular_acceleration"], float),
                          np.asarray(res["/base/linear_acceleration"], float))}

    def motion(link):
        if link in state:
            return state[link]
        joint = robot.joint_of_child[link]
        R_p, w_p, al_p, a_p = motion(joint.parent)
        r = np.einsum("tij,j->ti", R_p, joint.xyz)
        a = a_p + np.cross(al_p, r) + np.cross(w_p, np.cross(w_p, r))
        R = R_p @ joint.R_origin
        w, al = w_p, al_p
        if joint.type in ("revolute", "continuous"):
            k = index[joint.name]
            z = np.einsum("tij,j->ti", R, joint.axis)
            w = w_p + z * qd[:, k:k + 1]
            al = al_p + z * qdd[:, k:k + 1] + np.cross(w_p, z * qd[:, k:k + 1])
            R = R @ axis_rotation(joint.axis, q[:, k])
        state[link] = (R, w, al, a)
        return state[link]

    out = {}
    for link in robot.link_mass:
        R, w, al, a = motion(link)
        c = np.einsum("tij,j->ti", R, robot.link_com[link])
        out[link] = a + np.cross(al, c) + np.cross(w, np.cross(w, c))
    return out


def terrain_normal(config, feet):
    """Unit normals (T,L,3) of the terrain under the feet (treads and flat ground: +z)."""
    n = np.zeros(feet.shape)
    n[..., 2] = 1.0
    terrain = config.get("terrain", {}) or {}
    if terrain.get("type") == "slope":
        a = float(terrain["angle"])
        n[...] = (0.0, -np.sin(a), np.cos(a))
    return n


def torque_limits(setting, res):
    """Per-joint torque limits (J) in the file's joint order: the scene's one number, or with
    `effort` (a URDF robot) each joint's <limit effort> of /model/urdf, found by the names in
    /model/joint_names."""
    if not isinstance(setting, str):
        return np.full(len(hr.joint_names(res)), float(setting))
    import xml.etree.ElementTree as ET
    effort = {}
    for j in ET.fromstring(res.urdf).iter("joint"):
        lim = j.find("limit")
        if lim is not None and lim.get("effort") is not None:
            effort[j.get("name")] = float(lim.get("effort"))
    names = [str(hr.decode_text(n)) for n in res["/model/joint_names"]]
    return np.array([effort.get(n, np.inf) for n in names])


def drive_torques_and_bounds(config, res, tau, tmax):
    """With actuators (/joints/drive_torque in the file): the drive torques (T, J) computed
    from the joint torques, velocities, accelerations and each joint's actuator in /meta, and
    their bounds (T, J); None without actuators."""
    if "/joints/drive_torque" not in res:
        return None
    joints = ((config.get("actuators") or {}).get("joints")) or {}
    names = [str(hr.decode_text(n)) for n in res["/model/joint_names"]]
    w = np.asarray(res["/joints/velocity"], float)
    wd = np.asarray(res["/joints/acceleration"], float)
    tau_drive = np.array(tau, copy=True)
    bound = np.empty_like(tau_drive)
    for k, name in enumerate(names):
        a = joints[name]
        tau_drive[:, k] += (a["armature"] * wd[:, k] + a["coulomb_friction"] * np.sign(w[:, k])
                            + a["viscous_friction"] * w[:, k])
        gk = a["gear_ratio"] * a["torque_constant"]
        peak = a.get("peak_torque", np.inf)
        line = (gk * a["gear_efficiency"] * (a["voltage"] - gk * np.abs(w[:, k]))
                / a["resistance"]) if "voltage" in a else np.full(len(w), np.inf)
        b = np.minimum(peak, np.maximum(line, 0.0))
        bound[:, k] = np.where(np.isfinite(b), b, tmax[k])
    return tau_drive, bound


def limit_text(tmax):
    return f"{tmax[0]:g}" if np.all(tmax == tmax[0]) else f"[{tmax.min():g} .. {tmax.max():g}]"


def check_allocation(c, res):
    """The constraints of every optimal sample, from the file's data (module docstring)."""
    needed = ("/solver/status", "/contacts/force", "/contacts/phase", "/joints/torque",
              "/base/linear_acceleration", "/joints/acceleration")
    if not all(p in res for p in needed):
        return
    config = yaml.safe_load(res.meta.get("config_yaml", "")) or {}
    alloc = config.get("allocation", {}) or {}
    contact = config.get("contact", {}) or {}
    tmax = torque_limits(alloc.get("torque_limit", np.inf), res)
    fmin = float(alloc.get("min_normal_force", 0.0))
    mu = float(contact.get("friction_coefficient", np.inf))
    status = np.asarray(res["/solver/status"])
    ok = status == 0
    time = np.asarray(res["/time"])
    F = np.asarray(res["/contacts/force"], float)
    phase = np.asarray(res["/contacts/phase"])
    tau = np.asarray(res["/joints/torque"], float)

    def report(bad, excess, what):
        idx = np.flatnonzero(bad & ok)
        worst = idx[np.argmax(excess[idx])] if idx.size else None
        c.check(idx.size == 0, f"optimal samples: {what}",
                "" if worst is None else f"{idx.size} samples violate it, worst by {excess[worst]:.3g} "
                f"at sample {worst} (t = {time[worst]:.6g} s)")

    # Trunk force rows: sum of foot forces = sum of m (a_com - g) over the links.
    try:
        robot = UrdfRobot(res.urdf)
        acc = link_com_accelerations(robot, res)
        rhs = sum(robot.link_mass[l] * (acc[l] - GRAVITY) for l in robot.link_mass)
        excess = np.abs(F.sum(axis=1) - rhs) - VIOLATION_THRESHOLD * np.maximum(1.0, np.abs(rhs))
        report((excess > 0).any(axis=1), excess.max(axis=1) + VIOLATION_THRESHOLD,
               "sum of foot forces = total mass x COM acceleration - weight (trunk force rows) [N]")
    except (ValueError, KeyError) as e:
        c.check(False, "trunk force rows evaluated", str(e))
    # Torque limits: of the joint torques, or with actuators of the drive torques.
    drive = drive_torques_and_bounds(config, res, tau, tmax)
    if drive is None:
        excess = np.abs(tau) - tmax
        report((excess > VIOLATION_THRESHOLD * np.maximum(1.0, tmax)).any(axis=1),
               excess.max(axis=1), f"|torque| <= {limit_text(tmax)} N m")
    else:
        tau_drive, bound = drive
        stored = np.asarray(res["/joints/drive_torque"], float)
        diff = np.abs(stored - tau_drive) - 1e-9 * np.maximum(1.0, np.abs(tau_drive))
        c.check(not (diff > 0).any(), "/joints/drive_torque = torque + armature, friction terms",
                f"largest difference {np.abs(stored - tau_drive).max():.3g} N m")
        excess = np.abs(tau_drive) - bound
        report((excess > VIOLATION_THRESHOLD * np.maximum(1.0, bound)).any(axis=1),
               excess.max(axis=1), "|drive torque| <= min(peak, torque-speed line) [N m]")
    # Contact rows: swing feet carry nothing; support feet push and stay in the cone.
    normal = terrain_normal(config, F)
    fn = np.einsum("tlk,tlk->tl", F, normal)
    ft = np.linalg.norm(F - fn[..., None] * normal, axis=2)
    swing = phase == 0
    fmag = np.where(swing, np.linalg.norm(F, axis=2), 0.0)
    report((fmag > VIOLATION_THRESHOLD).any(axis=1), fmag.max(axis=1), "swing feet carry no force")
    support = phase == 2
    below = np.where(support, fmin - fn, -np.inf)
    report((below > VIOLATION_THRESHOLD * max(1.0, fmin)).any(axis=1), below.max(axis=1),
           f"support feet: normal force >= {fmin:g} N")
    contact_feet = phase != 0
    cone = np.where(contact_feet, ft - mu * fn, -np.inf)
    bound = np.maximum(1.0, np.abs(mu * fn))
    report((cone > VIOLATION_THRESHOLD * bound).any(axis=1), cone.max(axis=1),
           f"feet in contact: |F_t| <= {mu:g} F_n (friction cone)")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file", help="hexdyn-result HDF5 file")
    parser.add_argument("--expect-mass", type=float, default=None, metavar="KG",
                        help="also require the URDF total mass to equal KG (within 1e-9)")
    parser.add_argument("--dynamics", action="store_true",
                        help="also require the dynamics datasets")
    parser.add_argument("-v", "--verbose", action="store_true", help="list passed checks too")
    args = parser.parse_args(argv)

    c = Checks(args.verbose)
    print(f"check_result: {args.file}")
    try:
        res = hr.open_result(args.file)
    except (OSError, ValueError) as e:
        c.check(False, "open as a hexdyn-result file", str(e))
        print(f"check_result: {c.passed} passed, {c.failed} failed")
        return 1
    c.check(True, "open as a hexdyn-result file")
    check_meta(c, res)
    check_kinematics(c, res, args.expect_mass)
    if args.dynamics:
        check_dynamics(c, res)
        check_allocation(c, res)
    print(f"check_result: {c.passed} passed, {c.failed} failed")
    return 0 if c.failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
