#!/usr/bin/env python3
"""Inverse dynamics of a floating-base robot straight from a URDF file (xml.etree + numpy),
independent of hexdyn's model and RNEA: a second computation of a result's joint torques.

    urdf_dynamics.py RESULT.h5 URDF [--tolerance 1e-6] [--trunk-tolerance 1e-6]
    urdf_dynamics.py RESULT.h5 --model-urdf   (the result's own /model/urdf, feet L{i}_foot)

reads the result's states (/base/*: the URDF root link's frame; /joints/position, velocity,
acceleration by /model/joint_names) and foot forces (/contacts/force at the feet that
/model/leg_mapping names; for sphere feet, a file with /feet/center, at the contact point:
the foot point as this script's own forward kinematics places it, moved by /feet/position -
/feet/center, docs/theory/model.md#sphere-feet), computes with a recursive Newton-Euler pass over the URDF's own
links and joints (fixed joints kept as rigid joints, nothing merged, every <inertial> with
its rotated frame) the joint torques and the wrench the base would need, and checks
  - |tau_urdf - /joints/torque| <= tolerance [N m] on every sample, and
  - the trunk equations: the base wrench is zero (<= trunk tolerance, N and N m) on every
    sample whose /solver/status is optimal.
Exit 0 when both hold, 1 otherwise; one summary line either way.

Newton-Euler in world coordinates: per link the origin's linear acceleration a, angular
velocity w and acceleration alpha; child origins move with the parent (the URDF joint
frame is the child link frame), a revolute joint adds its axis z: w_c = w_p + z qd,
alpha_c = alpha_p + (w_p x z) qd + z qdd. Backward, the force f and moment n (about the
link origin) the parent exerts on the link:
  f = m (a_com - g) + sum f_child - sum F_ext,
  n = I alpha + w x I w + (c - p) x m (a_com - g) + sum [n_child + (p_child - p) x f_child]
      - sum (x_ext - p) x F_ext,
and tau = z . n. The root's (f, n) is the residual of the trunk equations.
"""

import argparse
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from hexdyn import decode_text
import numpy as np
from urdf_fk import axis_rotation, quaternion_to_matrix, rpy_to_matrix

GRAVITY_W = np.array([0.0, 0.0, -9.81])


def _vec(text, default=(0.0, 0.0, 0.0)):
    if text is None:
        return np.array(default, dtype=float)
    return np.array([float(v) for v in text.split()], dtype=float)


class Link:
    def __init__(self, el):
        self.name = el.get("name")
        self.mass, self.com, self.inertia = 0.0, np.zeros(3), np.zeros((3, 3))
        inertial = el.find("inertial")
        if inertial is not None:  # a link without <inertial> is massless (URDF specification)
            origin = inertial.find("origin")
            self.com = _vec(origin.get("xyz") if origin is not None else None)
            R = rpy_to_matrix(_vec(origin.get("rpy") if origin is not None else None))
            self.mass = float(inertial.find("mass").get("value"))
            i = inertial.find("inertia")
            g = {k: float(i.get(k, "0")) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
            I = np.array([[g["ixx"], g["ixy"], g["ixz"]], [g["ixy"], g["iyy"], g["iyz"]],
                          [g["ixz"], g["iyz"], g["izz"]]])
            self.inertia = R @ I @ R.T  # about the COM, link axes


class Joint:
    def __init__(self, el):
        self.name, self.type = el.get("name"), el.get("type")
        self.parent, self.child = el.find("parent").get("link"), el.find("child").get("link")
        origin, axis = el.find("origin"), el.find("axis")
        self.xyz = _vec(origin.get("xyz") if origin is not None else None)
        self.R = rpy_to_matrix(_vec(origin.get("rpy") if origin is not None else None))
        a = _vec(axis.get("xyz") if axis is not None else None, (1.0, 0.0, 0.0))
        self.axis = a / np.linalg.norm(a)
        if self.type not in ("fixed", "revolute", "continuous"):
            raise ValueError(f"joint {self.name}: type {self.type} not handled")


class UrdfDynamics:
    def __init__(self, text):
        root = ET.fromstring(text)
        self.links = {el.get("name"): Link(el) for el in root.findall("link")}
        self.joints = [Joint(el) for el in root.findall("joint")]
        self.joint_of_child = {j.child: j for j in self.joints}
        self.children = {}
        for j in self.joints:
            self.children.setdefault(j.parent, []).append(j)
        roots = [n for n in self.links if n not in self.joint_of_child]
        if len(roots) != 1:
            raise ValueError(f"expected one root link, got {roots}")
        self.root = roots[0]
        self.order = []  # links, parents first
        todo = [self.root]
        while todo:
            link = todo.pop()
            self.order.append(link)
            todo.extend(j.child for j in self.children.get(link, []))
        self.total_mass = sum(l.mass for l in self.links.values())

    def inverse_dynamics(self, base, q, qd, qdd, external):
        """base: dict of (T,3)/(T,4) arrays position, orientation (w,x,y,z), linear/angular
        velocity and acceleration of the root link frame, world axes; q, qd, qdd: dicts joint
        name -> (T,); external: list of (link, point in link frame (3,), F_W (T,3), shift
        (T,3)): F_W acts at the point, moved by shift in world axes.
        Returns ({joint: tau (T,)}, root force (T,3), root moment about the root origin (T,3))."""
        T = base["position"].shape[0]
        R = {self.root: quaternion_to_matrix(base["orientation"])}
        p = {self.root: base["position"]}
        w = {self.root: base["angular_velocity"]}
        al = {self.root: base["angular_acceleration"]}
        a = {self.root: base["linear_acceleration"]}
        z = {}
        for link in self.order[1:]:
            j = self.joint_of_child[link]
            Rp, pp, wp, alp, ap = R[j.parent], p[j.parent], w[j.parent], al[j.parent], a[j.parent]
            r = np.einsum("tij,j->ti", Rp, j.xyz)
            p[link] = pp + r
            a[link] = ap + np.cross(alp, r) + np.cross(wp, np.cross(wp, r))
            Rj = Rp @ j.R
            if j.type == "fixed":
                R[link], w[link], al[link] = Rj, wp, alp
                continue
            zw = np.einsum("tij,j->ti", Rj, j.axis)
            z[link] = zw
            R[link] = Rj @ axis_rotation(j.axis, q[j.name])
            w[link] = wp + zw * qd[j.name][:, None]
            al[link] = alp + np.cross(wp, zw) * qd[j.name][:, None] + zw * qdd[j.name][:, None]
        f = {n: np.zeros((T, 3)) for n in self.order}
        n_ = {n: np.zeros((T, 3)) for n in self.order}
        for link, point, F, shift in external:
            x = p[link] + np.einsum("tij,j->ti", R[link], point) + shift
            f[link] -= F
            n_[link] -= np.cross(x - p[link], F)
        tau = {}
        for link in reversed(self.order):
            L = self.links[link]
            if L.mass > 0.0:
                c = np.einsum("tij,j->ti", R[link], L.com)
                a_c = a[link] + np.cross(al[link], c) + np.cross(w[link], np.cross(w[link], c))
                I_w = R[link] @ L.inertia @ np.swapaxes(R[link], 1, 2)
                Iw = np.einsum("tij,tj->ti", I_w, w[link])
                Ia = np.einsum("tij,tj->ti", I_w, al[link])
                F_net = L.mass * (a_c - GRAVITY_W)
                f[link] += F_net
                n_[link] += Ia + np.cross(w[link], Iw) + np.cross(c, F_net)
            if link == self.root:
                break
            j = self.joint_of_child[link]
            if link in z:
                tau[j.name] = np.einsum("ti,ti->t", z[link], n_[link])
            r = p[link] - p[j.parent]
            f[j.parent] += f[link]
            n_[j.parent] += n_[link] + np.cross(r, f[link])
        return tau, f[self.root], n_[self.root]



def feet_from_mapping(entries):
    """/model/leg_mapping entries -> [(link, point in the link frame)] for each leg, in leg order."""
    feet = []
    for e in entries:
        words = decode_text(e).split()
        k = words.index("foot")
        if words[k + 1] == "offset":
            feet.append((words[k + 5], np.array([float(v) for v in words[k + 2:k + 5]])))
        else:
            feet.append((words[k + 1], np.zeros(3)))
    return feet


def check(result_path, urdf_path, tolerance, trunk_tolerance):
    """urdf_path None: the result's /model/urdf with its feet <leg>_foot, one per leg of
    /model/leg_names."""
    import h5py

    with h5py.File(result_path, "r") as h:
        names = [decode_text(n) for n in h["/model/joint_names"][:]]
        if urdf_path is None:
            urdf_text = decode_text(h["/model/urdf"][()])
            feet = [(f"{decode_text(leg)}_foot", np.zeros(3))
                    for leg in h["/model/leg_names"][:]]
        else:
            urdf_text = Path(urdf_path).read_text()
            feet = feet_from_mapping(h["/model/leg_mapping"][:])
        base = {k: h["/base/" + k][:] for k in ("position", "orientation", "linear_velocity",
                                                 "angular_velocity", "linear_acceleration",
                                                 "angular_acceleration")}
        q, qd, qdd = (h["/joints/" + k][:] for k in ("position", "velocity", "acceleration"))
        tau_file = h["/joints/torque"][:]
        force = h["/contacts/force"][:]
        # A sphere foot's force acts at its contact point, r n from the centre (the foot point).
        shift = h["/feet/position"][:] - h["/feet/center"][:] if "/feet/center" in h \
            else np.zeros(force.shape)
        status = h["/solver/status"][:]
    robot = UrdfDynamics(urdf_text)
    urdf_path = urdf_path or "its /model/urdf"
    by_name = lambda m: {n: m[:, k] for k, n in enumerate(names)}  # noqa: E731
    external = [(link, point, force[:, leg, :], shift[:, leg, :])
                for leg, (link, point) in enumerate(feet)]
    tau, f_root, n_root = robot.inverse_dynamics(base, by_name(q), by_name(qd), by_name(qdd), external)
    tau_urdf = np.stack([tau[n] for n in names], axis=1)
    err = np.abs(tau_urdf - tau_file)
    optimal = status == 0
    trunk = np.maximum(np.abs(f_root).max(1), np.abs(n_root).max(1))[optimal]
    worst_trunk = float(trunk.max()) if trunk.size else 0.0
    ok = err.max() <= tolerance and worst_trunk <= trunk_tolerance and optimal.any()
    i, k = np.unravel_index(np.argmax(err), err.shape)
    print(f"urdf_dynamics: {'ok' if ok else 'FAILED'}: {result_path} against {urdf_path}: "
          f"{len(status)} samples, largest |tau - /joints/torque| {err.max():.3g} N m "
          f"({names[k]}, sample {i}; tolerance {tolerance:g}); largest trunk-equation residual "
          f"on the {int(optimal.sum())} optimal samples {worst_trunk:.3g} (tolerance {trunk_tolerance:g}); "
          f"peak |tau| {np.abs(tau_urdf).max():.4g} N m; mass {robot.total_mass:.4f} kg")
    return ok


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("result")
    ap.add_argument("urdf", nargs="?", help="the original URDF file")
    ap.add_argument("--model-urdf", action="store_true", help="use the result's /model/urdf instead")
    ap.add_argument("--tolerance", type=float, default=1e-6, help="joint torques [N m]")
    ap.add_argument("--trunk-tolerance", type=float, default=1e-6,
                    help="trunk equations on optimal samples [N, N m]")
    args = ap.parse_args()
    if (args.urdf is None) == (not args.model_urdf):
        ap.error("give either URDF or --model-urdf")
    sys.exit(0 if check(args.result, args.urdf, args.tolerance, args.trunk_tolerance) else 1)


if __name__ == "__main__":
    main()
