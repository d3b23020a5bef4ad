"""What analysis/animate.py draws, computed without drawing (h5py + numpy).

    from animate_data import load_motion, frames_of
    motion = load_motion("results/paper/paper.h5")           # or run="000003" on a sweep file
    frames = frames_of(motion, fps=25)
    replay = load_motion("replay.h5")                        # a hexdyn-replay/3 file
    replay_frames = frames_of(replay, times=frames.times)    # at the plan's frame times
    frames.times        # (F,) s, F = ceil(duration * fps), frame i at t0 + i / fps
    frames.feet         # (F,L,3) m, /feet/position interpolated linearly in /time
    frames.legs         # L (F,P,3) arrays: hip ... foot link origins by forward kinematics
    frames.phase        # (F,L) the phase codes (Motion.phases) of the last sample at or before
                        # each frame
    frames.force        # (F,L,3) N, /contacts/force interpolated linearly (None without dynamics)
    frames.relaxed      # (F,) relaxed samples (/solver/status 1) since the previous frame
    motion.fk_error()   # max |FK(/base, /joints/position) - /feet/position| over the samples [m]
    replay_mismatch(motion, replay)   # None, or why the replay is not of this plan

The robot is the result's own /model/urdf (hexdyn's generated URDF for a robot given by
parameters, the description itself for a URDF robot), joints in /model/joint_names order,
its L legs those of /model/leg_names, each with its foot link <leg>_foot; the forward
kinematics is analysis/urdf_fk.py. The terrain is the height profile /terrain/y, /terrain/z
(a polyline z(y), constant along x); a file without /terrain (hexdyn-result/1) has none.

A replay (hexdyn-replay/3, `hexdyn replay`) carries the result's robot and terrain and its
motion in the result's dataset names, so it is drawn the same way; it has no planned phases:
its feet are in support where the compliant law's normal force /contacts/normal_force is
positive, in swing elsewhere (Motion.phases).
"""

import math
import os

import h5py
import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from hexdyn import decode_text
import numpy as np
from urdf_fk import UrdfRobot

REQUIRED = ("/time", "/base/position", "/base/orientation", "/joints/position",
            "/feet/position", "/model/urdf", "/model/joint_names", "/model/leg_names")
OPTIONAL = ("/contacts/phase", "/contacts/force", "/solver/status", "/contacts/normal_force",
            "/replay/message")
REPLAY_SCHEMA = "hexdyn-replay/"
PHASE_SWING, PHASE_SUPPORT = 0, 2  # /contacts/phase codes (schema.hpp kContactPhaseFlags)


class InputError(Exception):
    """Bad input: the message is the one line the command prints."""



def _schema(group):
    if "meta" not in group or "schema" not in group["meta"].attrs:
        return ""
    return decode_text(group["meta"].attrs["schema"])


def _run_ids(f):
    return sorted(f["runs"].keys()) if "runs" in f else []


def select_group(f, path, run=None):
    """The h5py group holding the result to draw: the file root of a result file, or
    /runs/<run> of a sweep file kept with --keep-runs. InputError names what is wrong."""
    schema = _schema(f)
    if schema.startswith("hexdyn-sweep/"):
        ids = _run_ids(f)
        if not ids:
            raise InputError(f"{path} is a sweep file without kept runs (swept without "
                             "--keep-runs): nothing to animate")
        if run is None:
            raise InputError(f"{path} is a sweep file: choose a kept run with --run ID "
                             f"(available: {' '.join(ids)})")
        match = [i for i in ids if i == run]
        if not match and str(run).isdigit():
            match = [i for i in ids if i.isdigit() and int(i) == int(run)]
        if not match:
            raise InputError(f"{path}: no kept run {run!r} (available: {' '.join(ids)})")
        return f["runs"][match[0]], f"{path}:/runs/{match[0]}"
    if not schema.startswith(("hexdyn-result/", REPLAY_SCHEMA)):
        raise InputError(f"{path} is not a hexdyn result, replay or sweep file "
                         f"(/meta schema {schema or 'missing'})")
    if run is not None:
        kind = "replay" if schema.startswith(REPLAY_SCHEMA) else "result"
        raise InputError(f"{path} is a {kind} file, not a sweep file: --run does not apply")
    return f, str(path)


def sign_continuous(quat):
    """Quaternions (T,4) with signs flipped so that neighbours have a positive dot product
    (q and -q are the same rotation; linear interpolation needs the near one)."""
    q = np.array(quat, dtype=float)
    for i in range(1, len(q)):
        if np.dot(q[i], q[i - 1]) < 0:
            q[i] = -q[i]
    return q


class Motion:
    """One run's (or replay's) datasets as numpy arrays (the file is closed), its /meta
    attributes, the robot and the terrain."""

    def __init__(self, source, data, terrain, meta=None):
        self.source = source
        self.data = data
        self.terrain = terrain  # (y (K,), z (K,), type) or None
        self.meta = dict(meta or {})
        self.is_replay = str(self.meta.get("schema", "")).startswith(REPLAY_SCHEMA)
        self.time = np.asarray(data["/time"], dtype=float)
        names = [decode_text(n) for n in np.asarray(data["/model/joint_names"]).ravel()]
        self.joint_names = tuple(names)
        self.robot = UrdfRobot(decode_text(data["/model/urdf"]), joint_order=self.joint_names)
        # The legs: /model/leg_names, each with its foot link <leg>_foot in /model/urdf.
        self.leg_names = tuple(decode_text(n) for n in
                               np.asarray(data["/model/leg_names"]).ravel())
        feet = tuple(f"{leg}_foot" for leg in self.leg_names)
        if self.robot.foot_links != feet:
            raise InputError(f"{source}: /model/urdf has the foot links "
                             f"{', '.join(self.robot.foot_links)}, expected {', '.join(feet)} "
                             "(one per leg of /model/leg_names)")
        self.chains = [self._chain(foot) for foot in self.robot.foot_links]
        self.duration = float(self.time[-1] - self.time[0])

    def _chain(self, foot):
        """Links from the first link moved by a joint (the hip) to the foot."""
        links = [foot]
        while links[-1] in self.robot.joint_of_child:
            links.append(self.robot.joint_of_child[links[-1]].parent)
        links.reverse()  # root ... foot
        for k in range(1, len(links)):
            if self.robot.joint_of_child[links[k]].type in ("revolute", "continuous"):
                return links[k:]
        return links[-1:]

    def has(self, path):
        return path in self.data

    def phases(self):
        """(T,L) contact phase codes as /contacts/phase has them (0 swing, 1 impact, 2
        support): a result's /contacts/phase; a replay's 2 where /contacts/normal_force > 0,
        else 0 (a replay has no touchdown transients of its own, only contact or none);
        None when the file has neither."""
        if self.has("/contacts/phase"):
            return np.asarray(self.data["/contacts/phase"])
        if self.is_replay and self.has("/contacts/normal_force"):
            loaded = np.asarray(self.data["/contacts/normal_force"]) > 0
            return np.where(loaded, PHASE_SUPPORT, PHASE_SWING).astype(np.int8)
        return None

    @property
    def end_message(self):
        """Why a replay ended early (/replay/message), "" otherwise."""
        return decode_text(self.data["/replay/message"]) if self.has("/replay/message") else ""

    def skeleton(self, base_position, base_quat, q):
        """One (F,P,3) array per leg of link origins, hip to foot, by forward kinematics."""
        needed = sorted({link for chain in self.chains for link in chain})
        poses = self.robot.link_poses(base_position, base_quat, q, needed)
        return [np.stack([poses[link][1] for link in chain], axis=1) for chain in self.chains]

    def fk_error(self):
        """Largest distance [m] between the feet by forward kinematics from /base/* and
        /joints/position and the stored /feet/position, over every sample."""
        feet = self.robot.foot_positions(self.data["/base/position"],
                                         self.data["/base/orientation"],
                                         self.data["/joints/position"])
        return float(np.max(np.linalg.norm(feet - self.data["/feet/position"], axis=-1)))


def read_terrain(group):
    """(y (K,), z (K,), type) of /terrain in a result group ("" without the attribute
    `type`: a replay file's), or None when absent."""
    if "terrain" not in group:
        return None
    g = group["terrain"]
    if "y" not in g or "z" not in g:
        return None
    y, z = np.asarray(g["y"][()], dtype=float), np.asarray(g["z"][()], dtype=float)
    if y.shape != z.shape or y.ndim != 1 or y.size < 2:
        raise InputError(f"/terrain/y and /terrain/z: shapes {y.shape} and {z.shape}, expected "
                         "two equal (K,) with K >= 2")
    kind = decode_text(g.attrs["type"]) if "type" in g.attrs else ""
    return y, z, kind


def load_motion(path, run=None):
    """Reads the run to draw from a result file (or a kept run of a sweep file)."""
    if not os.path.isfile(path):
        raise InputError(f"{path}: no such file")
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise InputError(f"{path}: not an HDF5 file ({e})") from None
    with f:
        group, source = select_group(f, path, run)
        data = {}
        for p in REQUIRED + OPTIONAL:
            if p.lstrip("/") in group:
                data[p] = group[p.lstrip("/")][()]
            elif p in REQUIRED:
                raise InputError(f"{source}: no dataset {p}")
        terrain = read_terrain(group)
        meta = {k: decode_text(v) for k, v in group["meta"].attrs.items()}
    t = np.asarray(data["/time"], dtype=float)
    if t.ndim != 1 or t.size < 1 or (t.size > 1 and not np.all(np.diff(t) > 0)):
        raise InputError(f"{source}: /time is not a strictly increasing series")
    return Motion(source, data, terrain, meta)


def replay_mismatch(plan, replay):
    """None when `replay` (a Motion of a replay file) replays `plan` (of a result): its /meta
    source_created_utc is the plan's created_utc (which survives a copy or a move of the
    plan's file); else one line saying what it replays."""
    made = replay.meta.get("source_created_utc", "")
    if made and made == plan.meta.get("created_utc"):
        return None
    return (f"{replay.source} replays {replay.meta.get('source_result', '?')} (created "
            f"{made or '?'}), not {plan.source} (created {plan.meta.get('created_utc', '?')})")


def frame_times(t0, duration, fps):
    """ceil(duration * fps) frame times t0 + i / fps (at least one frame); the product is
    rounded to 1e-9 first, so that a duration of 0.7 s computed as 0.7000000000000001 gives 7
    frames at 10 per second, not 8."""
    if not (fps > 0 and math.isfinite(fps)):
        raise InputError(f"--fps must be a positive number, got {fps}")
    n = max(1, math.ceil(round(duration * fps, 9)))
    return t0 + np.arange(n) / fps


def _bracket(t, tf):
    """Left sample index and weight of linear interpolation at each frame time."""
    if t.size == 1:
        return np.zeros(tf.size, dtype=int), np.zeros(tf.size)
    i = np.clip(np.searchsorted(t, tf, side="right") - 1, 0, t.size - 2)
    w = np.clip((tf - t[i]) / (t[i + 1] - t[i]), 0.0, 1.0)
    return i, w


def interpolate(t, values, tf):
    """Piecewise-linear interpolation of values (T, ...) in t at tf (F,)."""
    values = np.asarray(values, dtype=float)
    i, w = _bracket(t, tf)
    if t.size == 1:
        return np.repeat(values[:1], tf.size, axis=0)
    w = w.reshape((-1,) + (1,) * (values.ndim - 1))
    return values[i] * (1.0 - w) + values[i + 1] * w


class Frames:
    """Per-frame quantities (see the module docstring)."""

    def __init__(self, **fields):
        self.__dict__.update(fields)

    def __len__(self):
        return len(self.times)


def frames_of(motion, fps=25.0, times=None):
    """The frames of `motion` at `fps`, or at the frame times `times` (another motion's: a
    replay drawn at its plan's frames; past the end of `motion` its last sample holds)."""
    t = motion.time
    tf = frame_times(float(t[0]), motion.duration, fps) if times is None else np.asarray(times)
    d = motion.data
    base = interpolate(t, d["/base/position"], tf)
    quat = interpolate(t, sign_continuous(d["/base/orientation"]), tf)
    quat /= np.linalg.norm(quat, axis=1, keepdims=True)
    q = interpolate(t, d["/joints/position"], tf)
    hold = np.clip(np.searchsorted(t, tf, side="right") - 1, 0, t.size - 1)
    phase = motion.phases()
    phase = phase[hold] if phase is not None else None
    force = interpolate(t, d["/contacts/force"], tf) if motion.has("/contacts/force") else None
    relaxed = failed = None
    if motion.has("/solver/status"):
        status = np.asarray(d["/solver/status"])
        # Samples in (previous frame, this frame]; the first frame takes those at or before
        # it, the last those after it too.
        edges = np.searchsorted(t, tf, side="right")
        edges[-1] = t.size
        edges = np.concatenate(([0], edges))
        relaxed = np.diff(np.concatenate(([0], np.cumsum(status == 1)))[edges])
        failed = np.diff(np.concatenate(([0], np.cumsum(status == 2)))[edges])
    return Frames(times=tf, base=base, quat=quat, q=q,
                  feet=interpolate(t, d["/feet/position"], tf),
                  legs=motion.skeleton(base, quat, q), phase=phase, force=force,
                  relaxed=relaxed, failed=failed, fps=float(fps))
