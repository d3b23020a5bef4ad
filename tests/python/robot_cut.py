"""Files of a robot of another shape made from a hexdyn file with h5py, for tests of the
layout code and of the figures (tests/python/test_layout_sizes.py,
tests/analysis/test_leg_counts.py).

cut_copy(src, dst, legs) copies the file at `src` keeping only the legs of index `legs`
(0-based, in their order) and their joints: every axis along the dimension `leg` is cut to
those legs, every axis along `joint` to their joints (found by name: hexdyn.leg_joints, or a
sweep's /joint_names by the leg's name and "_"), /impacts/* to the kept legs' touchdowns,
/contacts/required_friction_leg renumbered (-1 where a removed leg bound), /model/urdf cut to
the kept legs' links and joints and /model/total_mass to the cut URDF's mass. Dimension
scales and their attachments are rebuilt. The result has the layout of a robot with those
legs; its kinematics are the original's for the kept legs, its dynamics are not a robot's (the
forces of the removed legs are gone), which is what a test of the layout needs.
"""

import xml.etree.ElementTree as ET

import h5py
import numpy as np

from hexdyn import decode_text
from hexdyn import results as hr

# Attributes of the dimension-scale machinery: the copy makes its own (make_scale, attach).
SCALE_ATTRIBUTES = {"CLASS", "NAME", "REFERENCE_LIST", "DIMENSION_LIST"}


def dims_of(path, ds):
    """The dimension names of a dataset: its declaration's, or its own name for a scale (a
    sweep axis's datasets, declared by templates, have neither leg nor joint: ())."""
    if path in hr.DECLARED:
        return hr.DECLARED[path][0].dims
    if h5py.h5ds.is_scale(ds.id):
        return (path.rsplit("/", 1)[1],)
    return ()


def _names(f, path):
    return [str(decode_text(n)) for n in f[path][()]]


def kept_joints(src, legs):
    """The joint indices of the legs `legs` of an open file (a result: hexdyn.leg_joints; a
    sweep: the joints of /joint_names whose names start with L<i>_, its legs' labels)."""
    if "model" in src:
        per_leg = hr.leg_joints(src)
    else:
        joints = _names(src, "joint_names")
        names = sorted({j.split("_", 1)[0] for j in joints}, key=lambda n: int(n[1:]))
        per_leg = hr.joints_by_leg(names, joints)
    return [k for leg in legs for k in per_leg[leg]]


def cut_urdf(text, removed):
    """The URDF `text` without the links and joints of the legs named `removed`: every link
    on the chain from the root to the leg's foot link <leg>_foot but the root, and the joints
    into them. Returns (text, total mass of the links kept [kg])."""
    root = ET.fromstring(text)
    parent = {j.find("child").get("link"): j for j in root.findall("joint")}
    gone = set()
    for leg in removed:
        link = f"{leg}_foot"
        while link in parent:
            gone.add(link)
            link = parent[link].find("parent").get("link")
    for element in list(root):
        if (element.tag == "link" and element.get("name") in gone) or \
                (element.tag == "joint" and element.find("child").get("link") in gone):
            root.remove(element)
    mass = sum(float(m.get("value")) for m in root.findall("link/inertial/mass"))
    return ET.tostring(root, encoding="unicode"), mass


def _impact_rows(src, legs):
    """The rows of /impacts/* of the kept legs (None: the file has no impacts)."""
    if "impacts/leg" not in src:
        return None
    return np.flatnonzero(np.isin(src["impacts/leg"][()], legs))


def _value(src, path, obj, legs, cut, impacts):
    """The dataset at `path` cut to the kept legs and joints."""
    value = obj[()]
    renumber = {old: new for new, old in enumerate(legs)}
    if path in ("/impacts/leg", "/contacts/required_friction_leg"):
        value = np.array([renumber.get(int(v), -1) for v in np.ravel(value)],
                         dtype=obj.dtype).reshape(np.shape(value))
    if path == "/model/urdf":
        removed = [n for i, n in enumerate(_names(src, "model/leg_names")) if i not in legs]
        text, _ = cut_urdf(str(decode_text(value)), removed)
        return np.array(text.encode(), dtype=obj.dtype)
    if path == "/model/total_mass" and "model/urdf" in src:
        removed = [n for i, n in enumerate(_names(src, "model/leg_names")) if i not in legs]
        return np.array(cut_urdf(str(decode_text(src["model/urdf"][()])), removed)[1])
    for axis, dim in enumerate(dims_of(path, obj)):
        if dim in cut:
            value = np.take(value, cut[dim], axis=axis)
        elif dim == "impact" and impacts is not None:
            value = np.take(value, impacts, axis=axis)
    return value


def cut_copy(src_path, dst_path, legs, keep=()):
    """A copy of the file at `src_path` with the legs of index `legs` and their joints only
    (the module's docstring), but the datasets of `keep`, copied whole."""
    with h5py.File(src_path, "r") as src, h5py.File(dst_path, "w") as dst:
        cut = {"leg": list(legs), "joint": kept_joints(src, legs)}
        impacts = _impact_rows(src, legs)
        datasets = {}

        def visit(name, obj):
            path = "/" + name
            target = dst.require_group(path) if isinstance(obj, h5py.Group) else None
            if isinstance(obj, h5py.Dataset):
                value = obj[()] if path in keep else _value(src, path, obj, legs, cut, impacts)
                target = dst.create_dataset(path, data=value, dtype=obj.dtype)
                datasets[path] = obj
            for key, v in obj.attrs.items():
                if key not in SCALE_ATTRIBUTES:
                    target.attrs[key] = v
        src.visititems(visit)
        for path, obj in datasets.items():
            if h5py.h5ds.is_scale(obj.id):
                dst[path].make_scale(path.rsplit("/", 1)[1])
        for path, obj in datasets.items():
            for axis, dim in enumerate(obj.dims):
                for scale in dim.values():
                    dst[path].dims[axis].attach_scale(dst[scale.name])
