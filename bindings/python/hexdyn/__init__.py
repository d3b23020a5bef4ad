"""hexdyn in Python: run scenes in process, read and write hexdyn's files.

    import hexdyn
    r = hexdyn.run("configs/paper.yaml", set={"gait.duty_factor": "3/4"})
    r["/energy/total"]            # numpy float64 (0-d array) [J]
    r["/joints/torque"]           # (T, J) numpy array [N m], bit for bit the file's dataset
    r.units["/joints/torque"]     # "N m"
    r.meta["git_commit"]          # the /meta attributes (r.attrs: also "/terrain/type")
    r.config["gait"]              # the resolved configuration, as a dict
    r.to_xarray("joints")         # labelled (xarray)
    r.write("out.h5")             # the file `hexdyn run` would write
    res = hexdyn.open_result("out.h5")   # the same Result type, read from the file
    res.write("copy.h5")          # a copy of the file's objects
    hexdyn.validate("configs/sweeps/smoke.yaml")
    p = hexdyn.sample_problem("configs/paper.yaml", 2.0)   # one instant's allocation rows
    a = hexdyn.forward_dynamics("configs/paper.yaml", r["/base/position"],
                                r["/base/orientation"], r["/joints/position"],
                                r["/base/linear_velocity"], r["/base/angular_velocity"],
                                r["/joints/velocity"], r["/joints/torque"],
                                foot_forces=r["/contacts/force"])
    a["joint_acceleration"]       # (T, J) [rad/s²]: what those torques and forces do
    hexdyn.inverse_dynamics(...)  # the torques (and trunk wrench) of given accelerations
    hexdyn.mass_matrix("configs/paper.yaml", r["/base/orientation"], r["/joints/position"])
    sw = hexdyn.open_sweep("smoke.h5")          # hexdyn-sweep/5: Sweep
    env = hexdyn.open_envelope("envelope.h5")   # hexdyn-envelope/2: Envelope
    rep = hexdyn.open_replay("replay.h5")       # hexdyn-replay/3 (hexdyn replay): Replay
    rob = hexdyn.open_robustness("rob.h5")      # hexdyn-robustness/1: Robustness
    st = hexdyn.open_study("study.h5")          # hexdyn-study/1 (analysis/study.py): Study
    hexdyn.open_file("any.h5")                  # whichever of them the file is
    hexdyn.check_layout("any.h5")               # any of them against its schema
    hexdyn.leg_names(r), hexdyn.joint_names(r)  # the file's names: L legs, J joints
    hexdyn.leg_joints(r)          # each leg's joints: [[0, 1, 2], [3, 4, 5], ...]

One type, Result, holds a result whether computed (run) or read (open_result, Sweep.run):
the same mapping from dataset path to values, .meta, .units, .config, .to_xarray() and
.write(). The readers (open_*, check_layout, decode_text) need h5py, numpy and PyYAML and
the schema module hexdyn._schema (generated at build time from src/hexdyn/io/schema.hpp),
not the compiled part nor xarray: xarray is imported by to_xarray only.

Errors are hexdyn.Error and its family (ConfigError, a ValueError; IoError, an OSError;
ReachError, PlanningError, SolverError; InternalError), each with the one-line message
`hexdyn` prints after "hexdyn: error: ". A path with a NUL character raises ValueError (the
C++ side would stop at the NUL) in every function that takes a path; the readers raise
hexdyn.IoError for a file whose datasets are off the schema (an OSError when the compiled
part is absent). run() releases the GIL while the scene computes: threads run scenes in
parallel.
"""

import json
import math
import os
from collections.abc import Mapping

import numpy as np

from ._version import __git_commit__, __version__
from .results import (Envelope, Replay, Result, Robustness, Study, Sweep, UnknownGroupError,
                      check_layout, decode_text, joint_names, leg_joints, leg_names,
                      open_envelope, open_file, open_replay, open_result, open_robustness,
                      open_study, open_sweep)
from .results import checked_path as _path

_compiled = None


def _lib():
    """The compiled part (_hexdyn*.so), imported on first use: reading files needs only h5py."""
    global _compiled
    if _compiled is None:
        from . import _hexdyn as compiled
        _compiled = compiled
    return _compiled


_SET_ALLOWED = ("a number, a bool, None, a string (YAML text, as after --set KEY=), or a list or "
                "a map of these (a numpy array as its list)")


def _value_text(value, inner=False):
    """An override value as `--set` text: strings as given (YAML-parsed, "p/q" a fraction, as
    on the command line; quoted inside a list or a map), numbers exactly (repr; NaN and
    infinities as YAML's .nan, .inf, -.inf, which the scene's reader refuses naming the key),
    None as null, lists, tuples, numpy arrays and maps as YAML flow collections. TypeError
    for anything else."""
    if hasattr(value, "tolist") and hasattr(value, "ndim"):  # numpy arrays and scalars
        value = value.tolist()
    if isinstance(value, str):
        return json.dumps(value) if inner else value
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(int(value))
    if isinstance(value, float):
        return repr(float(value)) if math.isfinite(value) else (
            ".nan" if math.isnan(value) else ".inf" if value > 0 else "-.inf")
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_value_text(v, True) for v in value) + "]"
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{json.dumps(str(k))}: {_value_text(v, True)}"
                               for k, v in value.items()) + "}"
    raise TypeError(f"value {value!r} of type {type(value).__name__}, expected {_SET_ALLOWED}")


def _overrides(set):
    if set is None:
        return []
    if not isinstance(set, Mapping):
        raise TypeError(f"set: expected a dict from dotted key to value, got {type(set).__name__}")
    out = []
    for key, value in set.items():
        if not isinstance(key, str):
            raise TypeError(f"set: key {key!r} is not a string")
        try:
            out.append(f"{key}={_value_text(value)}")
        except TypeError as e:
            raise TypeError(f"set: {key}: {e}") from None
        except RecursionError:
            raise TypeError(f"set: {key}: a value that holds itself, expected {_SET_ALLOWED}"
                            ) from None
    return out


def run(scene, set=None, *, allow_large=False):
    """Runs the scene file `scene` (a path) with the overrides `set` (a dict from dotted key to
    value, as `--set key=value`: a number, a bool, None, a string read as YAML text, or a list
    or a map of these, a numpy array as its list; the scene's reader checks the value as the
    key allows, and anything else is a TypeError naming the key) and returns its Result (the
    one type open_result returns too). allow_large: as `--allow-large`. The scene's warnings
    (those `hexdyn run` prints, such as a URDF robot's stance fallback) are issued as
    UserWarning."""
    scene = _path(scene)
    handle, datasets, attrs, units = _lib().run(scene, _overrides(set), bool(allow_large))
    meta = {k: v for k, v in attrs.items() if not k.startswith("/")}
    others = {k: v for k, v in attrs.items() if k.startswith("/")}
    shapes = {p: tuple(getattr(v, "shape", ())) for p, v in datasets.items()}
    return Result(f"hexdyn.run({os.fsdecode(scene)!r})", datasets, units, shapes, meta, others,
                  handle=handle)


def robustness(scene, set=None, *, threads=None):
    """Runs the robustness study of the scene file `scene` with the overrides `set` (as for
    run; its `robustness:` section, docs/user/robustness.md) on `threads` threads (default: one
    per core) and returns a Robustness: the datasets of the hexdyn-robustness/1 file
    `hexdyn robustness` writes, in memory (rob.p_success, rob.interval, rob["/replays/failure"]).
    The result does not depend on `threads`."""
    scene = _path(scene)
    n = threads if threads is not None else (os.cpu_count() or 1)
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise ValueError(f"threads: got {threads!r}, expected a whole number of threads >= 1")
    datasets, attrs, units = _lib().robustness(scene, _overrides(set), n)
    meta = {k: v for k, v in attrs.items() if not k.startswith("/")}
    shapes = {p: tuple(getattr(v, "shape", ())) for p, v in datasets.items()}
    return Robustness(f"hexdyn.robustness({os.fsdecode(scene)!r})", datasets, units, shapes, meta,
                      {})


def validate(scene, set=None):
    """Checks a scene file or a sweep file as `hexdyn validate` does; raises on the first error.
    Returns {"kind": "scene", "name": ..., "messages": [...], "warnings": [...]} ("messages":
    the lines `hexdyn validate` prints; "warnings": the ones it prints on stderr, such as a
    URDF robot's stance fallback, also issued as UserWarning), or for a sweep file also
    "scenarios", "out_of_range" (scenarios that would be rows with status config) and
    "first_out_of_range" (the first one's message)."""
    return _lib().validate(_path(scene), _overrides(set))


def sample_problem(scene, t, set=None):
    """The allocation problem of the instant `t` [s] of the scene file `scene` with the
    overrides `set` (as for run), as the run builds and solves it (C++ sample_problem,
    pipeline/pipeline.hpp; docs/theory/grip.md#one-samples-rows). A dict:

    - "C" (m, n), "lower", "upper" (m): the inequality rows lower <= C x <= upper at the
      scene's friction coefficient; "ineq_names" (m), the first six the trunk rows
      (lower == upper); "H" (n, n), "g" (n): the objective 1/2 x'Hx + g'x;
    - "cones": per second-order cone a dict tangent1, tangent2, normal (indices into x), mu,
      name: ||(x[tangent1], x[tangent2])|| <= mu x[normal];
    - "legs": one dict per leg (allocation/problem.hpp AllocationLayout::Leg): offset, count (3
      support, 2 touchdown transient, 0 swing), friction_row, friction_faces, face_reach,
      cone, known_normal_force_N, W_R_contact (3, 3); "variables" (n);
      "constant_excess_Nm" and "constant_violation" (a swing leg's torque over its limit);
    - "phase" (L) int8 as /contacts/phase; "x" (n) the allocation's forces [N]; "status" as
      /solver/status (0 optimal, 1 relaxed, 2 failed); "required_friction" (NaN where none
      suffices) and "required_friction_leg" (-1 none);
    - "friction_coefficient" (the scene's mu), "friction" ("pyramid4", "pyramid8", "cone"),
      "time".

    `t` must lie in the span the run samples, [t0, t1] (0 to the motion's end, or the end of a
    final touchdown's transient): another t, NaN or an infinity raises ValueError in one line
    giving that span."""
    try:
        t = float(t)
    except (TypeError, ValueError):
        raise TypeError(f"sample_problem: t = {t!r}, expected a number [s]") from None
    return _lib().sample_problem(_path(scene), _overrides(set), t)


def _arrays(function, **arrays):
    """The arguments as float64 numpy arrays (None stays None); ValueError in one line naming
    the argument for one that is not numbers."""
    out = []
    for name, a in arrays.items():
        try:
            out.append(None if a is None else np.asarray(a, dtype=float))
        except (TypeError, ValueError) as e:
            raise ValueError(f"{function}: {name}: {_first_line(e)}, expected numbers") from None
    return out


_ROBOT_TEXT = """The robot is that of the scene file `scene` with the overrides `set` (as for run): the
    robot `hexdyn run` builds, the one its /model/urdf describes, gravity -9.81 m/s² along z."""

_STATE_TEXT = """The arguments are in a result file's coordinates, each one state or T states along a first
    axis (all alike): base_position (3) [m], base_orientation (4) unit quaternion (w, x, y, z),
    base_linear_velocity (3) [m/s] and base_angular_velocity (3) [rad/s] of the URDF root
    link's frame (its origin's velocity), world axes (as /base/*); joint_position (J) [rad],
    joint_velocity (J) [rad/s] in /model/joint_names order (a prismatic joint's in m, m/s);
    foot_forces (L, 3) [N] the terrain's force on each foot at its contact point, world axes
    (as /contacts/force; None: no force); foot_normals (L, 3) the unit surface normal under
    each foot, where a sphere foot touches (None: +z). L and J are the robot's legs and joints,
    the lengths of the returned "leg_names" and "joint_names" (those of its result's
    /model/leg_names and /model/joint_names)."""

_ERRORS_TEXT = """Raises ValueError in one line naming the function and the argument as numpy indexes it
    (the sample first for T states: "joint_torque[4, 7]") for an argument of the wrong shape, a
    NaN or an infinity in any argument, a base_orientation whose norm is off 1 by more than
    1e-6, and a foot normal under a sphere foot of norm below 1e-6 (normals are normalised;
    those under point feet are not used)"""


def forward_dynamics(scene, base_position, base_orientation, joint_position,
                     base_linear_velocity, base_angular_velocity, joint_velocity, joint_torque,
                     foot_forces=None, foot_normals=None, set=None):
    return _lib().forward_dynamics(_path(scene), _overrides(set), *_arrays(
        "forward_dynamics", base_position=base_position, base_orientation=base_orientation,
        joint_position=joint_position, base_linear_velocity=base_linear_velocity,
        base_angular_velocity=base_angular_velocity, joint_velocity=joint_velocity,
        joint_torque=joint_torque, foot_forces=foot_forces, foot_normals=foot_normals))


forward_dynamics.__doc__ = f"""The accelerations of a scene's robot at the given states, under
    the joint torques and the foot forces (C++ forward_dynamics_joints,
    dynamics/forward_dynamics.hpp; docs/theory/replay.md#forward-dynamics). No other force
    acts on the trunk.

    {_ROBOT_TEXT}

    {_STATE_TEXT} joint_torque (J) [N m] (a prismatic joint's force [N]).

    Returns a dict: "base_linear_acceleration" (3) [m/s²], the classical acceleration of the
    root link's origin, "base_angular_acceleration" (3) [rad/s²], both world axes (as
    /base/linear_acceleration and /base/angular_acceleration), and "joint_acceleration" (J)
    [rad/s²] (m/s² for a prismatic joint), numpy arrays, each (T, ...) for T states; and the
    robot's "joint_names" (J) and "leg_names" (L).

    {_ERRORS_TEXT}; hexdyn.SolverError for a robot whose mass matrix is singular
    (robot.leg_inertia: massless)."""


def inverse_dynamics(scene, base_position, base_orientation, joint_position,
                     base_linear_velocity, base_angular_velocity, joint_velocity,
                     base_linear_acceleration, base_angular_acceleration, joint_acceleration,
                     foot_forces=None, foot_normals=None, set=None):
    return _lib().inverse_dynamics(_path(scene), _overrides(set), *_arrays(
        "inverse_dynamics", base_position=base_position, base_orientation=base_orientation,
        joint_position=joint_position, base_linear_velocity=base_linear_velocity,
        base_angular_velocity=base_angular_velocity, joint_velocity=joint_velocity,
        base_linear_acceleration=base_linear_acceleration,
        base_angular_acceleration=base_angular_acceleration,
        joint_acceleration=joint_acceleration, foot_forces=foot_forces,
        foot_normals=foot_normals))


inverse_dynamics.__doc__ = f"""The generalised forces that give a scene's robot the given
    accelerations at the given states, under the foot forces (recursive Newton-Euler, C++ rnea,
    dynamics/rnea.hpp; docs/theory/stages.md#inverse-dynamics): M(q) ν̇ + h(q, ν) − Σ J_lᵀ F_l,
    the trunk's rows about the root link's origin.

    {_ROBOT_TEXT}

    {_STATE_TEXT} base_linear_acceleration (3) [m/s²], the classical acceleration of the root
    link's origin, and base_angular_acceleration (3) [rad/s²], world axes (as
    /base/linear_acceleration and /base/angular_acceleration); joint_acceleration (J) [rad/s²].

    Returns a dict: "base_force" (3) [N] and "base_moment" (3) [N m], the force and the moment
    about the root link's origin that an actuator on the trunk would apply, world axes (zero for
    a motion the feet carry alone), and "joint_torque" (J) [N m] (a prismatic joint's force
    [N]), numpy arrays, each (T, ...) for T states; and the robot's "joint_names" (J) and
    "leg_names" (L). The power of the trunk's rows is base_force · v + base_moment · ω with
    v the root link origin's velocity.

    {_ERRORS_TEXT}."""


def mass_matrix(scene, base_orientation, joint_position, set=None):
    return _lib().mass_matrix(_path(scene), _overrides(set), *_arrays(
        "mass_matrix", base_orientation=base_orientation, joint_position=joint_position))


mass_matrix.__doc__ = f"""The mass matrix M of a scene's robot at the given poses
    (composite-rigid-body algorithm, C++ crba, dynamics/rnea.hpp), the kinetic energy ½ νᵀ M ν
    of the generalised velocity ν = [v; ω; q̇]: v [m/s] the velocity of the URDF root link's
    origin and ω [rad/s] the trunk's angular velocity, world axes (as /base/linear_velocity and
    /base/angular_velocity), q̇ (J) the joint rates in /model/joint_names order. Rows and
    columns 0-2 [kg], the trunk's linear coordinates; 3-5 its angular ones [kg m²]; then the
    joints. M does not depend on the trunk's position.

    {_ROBOT_TEXT}

    base_orientation (4), a unit quaternion (w, x, y, z) of the root link's frame, and
    joint_position (J) [rad] (a prismatic joint's [m]): one pose or T along a first axis.

    Returns a dict: "mass_matrix" (6 + J, 6 + J), or (T, 6 + J, 6 + J) for T poses, symmetric
    positive definite; and the robot's "joint_names" (J) and "leg_names" (L).

    {_ERRORS_TEXT}."""


def _first_line(error):
    text = str(error).strip()
    return text.splitlines()[0] if text else type(error).__name__


def __getattr__(name):
    # The exception family lives in the compiled part; hexdyn.ConfigError etc. load it.
    if name in ("Error", "ConfigError", "IoError", "ReachError", "PlanningError", "SolverError",
                "InternalError"):
        return getattr(_lib(), name)
    raise AttributeError(f"module 'hexdyn' has no attribute {name!r}")


__all__ = ["run", "robustness", "validate", "sample_problem", "forward_dynamics", "inverse_dynamics",
           "mass_matrix", "Result", "Sweep", "Envelope",
           "Replay", "Robustness", "Study", "open_file", "open_result", "open_sweep",
           "open_envelope", "open_replay", "open_robustness", "open_study", "check_layout",
           "leg_names", "joint_names",
           "leg_joints", "decode_text", "UnknownGroupError",
           "Error", "ConfigError", "IoError", "ReachError", "PlanningError", "SolverError",
           "InternalError", "__version__", "__git_commit__"]
