"""Forward kinematics from a URDF string alone (xml.etree + numpy).

Used to check that /model/urdf of a result file is the robot that was simulated:
composing the joints' <origin xyz rpy> (R = Rz(yaw) Ry(pitch) Rx(roll)) and the
revolute rotations about <axis> from the root link reproduces /feet/position.

    from urdf_fk import load_urdf
    mass, feet_fk = load_urdf(urdf_text)
    feet = feet_fk(base_position, base_quat_wxyz, q)   # (T,3), (T,4), (T,J) -> (T,L,3)

L legs and J joints, the robot's. Joint angle order for hexdyn's own URDF (links L1_foot,
L2_foot, ...): leg by leg, each leg's moving joints on its chain from the root to its foot,
hip to foot (L1_coxa, L1_femur, L1_tibia, L2_coxa, ..., the order of /model/joint_names);
any other URDF (a real robot's) takes its joint names in hexdyn's order, e.g.
/model/joint_names of a result, and its foot links: UrdfRobot(text, joint_order=...,
foot_links=...). Fixed joints are composed like any other; continuous joints rotate like
revolute ones; a link without <inertial> is massless.
"""

import re
import xml.etree.ElementTree as ET

import numpy as np

def _vec(text, default=(0.0, 0.0, 0.0)):
    if text is None:
        return np.array(default, dtype=float)
    values = [float(v) for v in text.split()]
    if len(values) != 3:
        raise ValueError(f"URDF: expected 3 numbers, got {text!r}")
    return np.array(values)


def rpy_to_matrix(rpy):
    """R = Rz(yaw) Ry(pitch) Rx(roll) for URDF fixed-axis roll, pitch, yaw [rad]."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return rz @ ry @ rx


def axis_rotation(axis, angles):
    """Rotations by `angles` (T,) about the unit `axis` (Rodrigues) -> (T,3,3)."""
    axis = np.asarray(axis, dtype=float)
    axis = axis / np.linalg.norm(axis)
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    s = np.sin(angles)[:, None, None]
    c = np.cos(angles)[:, None, None]
    return np.eye(3)[None] + s * k[None] + (1.0 - c) * (k @ k)[None]


def quaternion_to_matrix(quat_wxyz):
    """Rotation matrices (T,3,3) of quaternions (T,4) w, x, y, z (normalised here)."""
    q = np.asarray(quat_wxyz, dtype=float)
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    w, x, y, z = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1),
    ], -2)


class UrdfJoint:
    def __init__(self, name, jtype, parent, child, xyz, rpy, axis):
        self.name, self.type, self.parent, self.child = name, jtype, parent, child
        self.xyz, self.rpy, self.axis = xyz, rpy, axis
        self.R_origin = rpy_to_matrix(rpy)


class UrdfRobot:
    """Links (name -> mass [kg], COM [m]) and joints of a URDF, with FK."""

    def __init__(self, text, joint_order=None, foot_links=None):
        root = ET.fromstring(text)
        if root.tag != "robot":
            raise ValueError("URDF: root element is not <robot>")
        self.name = root.get("name", "")
        self.link_mass, self.link_com = {}, {}
        for link in root.findall("link"):
            name = link.get("name")
            inertial = link.find("inertial")
            mass, com = 0.0, np.zeros(3)
            if inertial is not None:
                mass_el = inertial.find("mass")
                mass = float(mass_el.get("value")) if mass_el is not None else 0.0
                origin = inertial.find("origin")
                com = _vec(origin.get("xyz") if origin is not None else None)
            self.link_mass[name], self.link_com[name] = mass, com
        self.joints = {}
        self.joint_of_child = {}
        for j in root.findall("joint"):
            origin = j.find("origin")
            axis = j.find("axis")
            joint = UrdfJoint(
                j.get("name"), j.get("type"), j.find("parent").get("link"),
                j.find("child").get("link"),
                _vec(origin.get("xyz") if origin is not None else None),
                _vec(origin.get("rpy") if origin is not None else None),
                _vec(axis.get("xyz") if axis is not None else None, (1.0, 0.0, 0.0)))
            self.joints[joint.name] = joint
            self.joint_of_child[joint.child] = joint
        roots = [name for name in self.link_mass if name not in self.joint_of_child]
        if len(roots) != 1:
            raise ValueError(f"URDF: expected one root link, found {roots}")
        self.root = roots[0]
        self.total_mass = float(sum(self.link_mass.values()))
        if foot_links is None:
            feet = sorted((n for n in self.link_mass if re.fullmatch(r"L\d+_foot", n)),
                          key=lambda n: int(n[1:-5]))
        else:
            feet = list(foot_links)
            missing = [n for n in feet if n not in self.link_mass]
            if missing:
                raise ValueError(f"URDF: no foot links {missing}")
        self.foot_links = tuple(feet)
        self.joint_order = tuple(self.chain_joints() if joint_order is None else joint_order)

    def chain_joints(self):
        """The moving joints on each foot link's chain from the root, leg by leg, hip to foot:
        hexdyn's joint order for its own URDF."""
        order = []
        for foot in self.foot_links:
            chain, link = [], foot
            while link in self.joint_of_child:
                joint = self.joint_of_child[link]
                if joint.type != "fixed":
                    chain.append(joint.name)
                link = joint.parent
            order += reversed(chain)
        return order

    def link_poses(self, base_position, base_quat_wxyz, q, links=None):
        """World poses of `links` (default: all). Inputs (T,3), (T,4), (T,J) or one
        sample (3,), (4,), (J,). Returns {link: (R (T,3,3), p (T,3))}."""
        p0 = np.atleast_2d(np.asarray(base_position, dtype=float))
        R0 = quaternion_to_matrix(np.atleast_2d(base_quat_wxyz))
        q = np.atleast_2d(np.asarray(q, dtype=float))
        if q.shape[1] != len(self.joint_order):
            raise ValueError(f"expected {len(self.joint_order)} joint angles, got {q.shape[1]}")
        angle = {name: q[:, k] for k, name in enumerate(self.joint_order)}
        cache = {self.root: (R0, p0)}

        def pose(link):
            if link in cache:
                return cache[link]
            joint = self.joint_of_child[link]
            R_parent, p_parent = pose(joint.parent)
            p = p_parent + np.einsum("tij,j->ti", R_parent, joint.xyz)
            R = R_parent @ joint.R_origin
            if joint.type in ("revolute", "continuous"):
                if joint.name not in angle:
                    raise ValueError(f"URDF joint {joint.name} is not in the joint order")
                R = R @ axis_rotation(joint.axis, angle[joint.name])
            elif joint.type != "fixed":
                raise ValueError(f"URDF joint {joint.name}: unsupported type {joint.type}")
            cache[link] = (R, p)
            return cache[link]

        return {link: pose(link) for link in (links or self.link_mass)}

    def foot_positions(self, base_position, base_quat_wxyz, q):
        """World positions of the foot links (L1_foot, L2_foot, ... by default): (T,L,3),
        or (L,3) for one sample."""
        single = np.ndim(q) == 1
        poses = self.link_poses(base_position, base_quat_wxyz, q, self.foot_links)
        out = np.stack([poses[name][1] for name in self.foot_links], axis=1)
        return out[0] if single else out

    def com_position(self, base_position, base_quat_wxyz, q):
        """Whole-robot centre of mass in the world frame: (T,3), or (3,)."""
        single = np.ndim(q) == 1
        poses = self.link_poses(base_position, base_quat_wxyz, q)
        acc = 0.0
        for name, (R, p) in poses.items():
            acc = acc + self.link_mass[name] * (p + np.einsum("tij,j->ti", R, self.link_com[name]))
        out = acc / self.total_mass
        return out[0] if single else out


def parse_urdf(text):
    return UrdfRobot(text)


def load_urdf(text):
    """(total mass [kg], feet FK function) of a URDF string; the function maps
    (base_position, base_quat_wxyz, q) to the foot positions (see foot_positions)."""
    robot = UrdfRobot(text)
    return robot.total_mass, robot.foot_positions
