"""The Python functions' own arguments refused at the edge (docs/user/api.md#arguments), each
in one line naming the argument (and the sample index, the key) and what is allowed:

- hexdyn.forward_dynamics: a base_orientation that is no unit quaternion ([0, 0, 0, 0],
  [2, 0, 0, 0], [0.5, 0.5, 0, 0]; norm off 1 by more than 1e-6), a NaN or an infinity in any
  argument, a zero foot normal under a sphere foot (those under point feet are unused: the
  accelerations are those with +z normals); every index in the message is where numpy finds
  the bad value;
- hexdyn.sample_problem: t outside the span the run samples (-1, 1e300, inf, NaN), the span
  given being the result's /time from first to last; both ends accepted;
- set= values: a numpy array is its list (a list key takes it as the list, a number key refuses
  it naming the key as the scene's reader does), numpy scalars their value, NaN and
  infinities refused as not finite naming the key, an object a TypeError naming the key.
    test_arguments.py HEXDYN_BINARY SOURCE_DIR"""

import os
import re

import numpy as np

import hexdyn
from common import args

HEXDYN, SRC = args()
PAPER = os.path.join(SRC, "configs", "paper.yaml")
SPHERES = os.path.join(SRC, "configs", "robots", "pexod_stairs.yaml")  # sphere feet
STATE = ("/base/position", "/base/orientation", "/joints/position", "/base/linear_velocity",
         "/base/angular_velocity", "/joints/velocity", "/joints/torque")
NAMES = ("base_position", "base_orientation", "joint_position", "base_linear_velocity",
         "base_angular_velocity", "joint_velocity", "joint_torque", "foot_forces", "foot_normals")


def refused(cls, f, *a, **k):
    """The one-line message of the `cls` that f(*a, **k) raises."""
    try:
        f(*a, **k)
    except cls as e:
        message = str(e)
        assert "\n" not in message and message, repr(message)
        return message
    raise AssertionError(f"{f.__name__}{a[1:2]}: accepted, expected {cls.__name__}")


def index_text(name, index):
    return name + ("[" + ", ".join(str(int(i)) for i in index) + "]" if len(index) else "")


# ---- forward_dynamics
paper = hexdyn.run(PAPER)
T = 6
states = {k: np.array(paper[k][:T]) for k in STATE}
states["foot_forces"] = np.array(paper["/contacts/force"][:T])
L = len(hexdyn.leg_names(paper))  # the robot's legs
states["foot_normals"] = np.tile([0.0, 0.0, 1.0], (T, L, 1))


def fd(scene, s, t=slice(None)):
    return hexdyn.forward_dynamics(scene, *(s[k][t] for k in STATE),
                                   foot_forces=s["foot_forces"][t],
                                   foot_normals=s["foot_normals"][t])


base = fd(PAPER, states)
# Quaternions that are no rotation, in a batch and alone; the norm in the message is numpy's.
for q in ([0, 0, 0, 0], [2, 0, 0, 0], [0.5, 0.5, 0, 0]):
    for t in (slice(None), 3):
        bad = {k: v.copy() for k, v in states.items()}
        bad["/base/orientation"][3] = q
        message = refused(ValueError, fd, PAPER, bad, t)
        where = "base_orientation[3]" if t != 3 else "base_orientation"
        assert message.startswith(f"forward_dynamics: {where} = ("), message
        norm = float(re.search(r"has norm ([^,]+),", message).group(1))
        assert abs(norm - np.linalg.norm(q)) <= 1e-8, (message, np.linalg.norm(q))
        assert "unit quaternion (w, x, y, z): a norm within 1e-06 of 1" in message, message
# The tolerance: 5e-7 off is taken (and normalised), 2e-6 off is not.
near = {k: v.copy() for k, v in states.items()}
near["/base/orientation"][2] *= 1 + 5e-7
fd(PAPER, near)
near["/base/orientation"][2] *= 1 + 1.5e-6
assert "base_orientation[2]" in refused(ValueError, fd, PAPER, near)
print("forward_dynamics: quaternions off the unit norm refused, 1e-6 tolerance")

# A NaN or an infinity in each argument, at a random place: named where numpy finds it.
rng = np.random.default_rng(40)
keys = STATE + ("foot_forces", "foot_normals")
for key, name in zip(keys, NAMES):
    for value in (np.nan, np.inf, -np.inf):
        bad = {k: v.copy() for k, v in states.items()}
        flat = bad[key].reshape(-1)
        flat[rng.integers(flat.size)] = value
        where = np.argwhere(~np.isfinite(bad[key]))[0]
        message = refused(ValueError, fd, PAPER, bad)
        want = f"forward_dynamics: {index_text(name, where)} is {value:g}, expected a finite number"
        assert message == want, (message, want)
        one = {k: v[int(where[0])] for k, v in bad.items()}
        message = refused(ValueError, fd, PAPER, one)
        assert message.startswith(f"forward_dynamics: {index_text(name, where[1:])} is "), message
print("forward_dynamics: NaN and infinities refused in each argument, named by index")

# Zero normals: refused under a sphere foot, naming the sample and the leg; unused under point
# feet (the paper robot's: the accelerations are those with +z).
spheres = hexdyn.run(SPHERES)
sphere_states = {k: np.array(spheres[k][:T]) for k in STATE}
sphere_states["foot_forces"] = np.array(spheres["/contacts/force"][:T])
L_SPHERES = len(hexdyn.leg_names(spheres))
sphere_states["foot_normals"] = np.tile([0.0, 0.0, 1.0], (T, L_SPHERES, 1))
fd(SPHERES, sphere_states)
for leg in range(L_SPHERES):
    for normal in ([0, 0, 0], [0, 1e-7, 0]):
        bad = {k: v.copy() for k, v in sphere_states.items()}
        bad["foot_normals"][4, leg] = normal
        message = refused(ValueError, fd, SPHERES, bad)
        assert message.startswith(f"forward_dynamics: foot_normals[4, {leg}] = ("), message
        assert f"under leg L{leg + 1}'s sphere foot, has norm {np.linalg.norm(normal):g}," \
            in message, message
        assert "expected a direction: a norm of at least 1e-06" in message, message
zero = {k: v.copy() for k, v in states.items()}
zero["foot_normals"][:] = 0.0
point = fd(PAPER, zero)
for k in base:
    assert np.array_equal(point[k], base[k]), f"{k}: the normals under point feet were used"
print("forward_dynamics: zero normals refused under sphere feet, unused under point feet")

# ---- sample_problem: t within the span the run samples, [/time[0], /time[-1]]
t0, t1 = float(paper["/time"][0]), float(paper["/time"][-1])
for t in (-1.0, 1e300, np.inf, -np.inf, np.nan, t1 + 1e-6, t0 - 1e-9):
    message = refused(ValueError, hexdyn.sample_problem, PAPER, t)
    found = re.fullmatch(r"sample_problem: t = (\S+) s is outside the motion's span "
                         r"\[(\S+), (\S+)\] s", message)
    assert found, message
    assert float(found.group(1)) == float(f"{t:g}") or np.isnan(t), message
    assert abs(float(found.group(2)) - t0) <= 1e-8 and abs(float(found.group(3)) - t1) <= 1e-8 * t1
for t in (t0, t1, 0.5 * (t0 + t1)):
    assert hexdyn.sample_problem(PAPER, t)["time"] == t
assert "t = 'x'" in refused(TypeError, hexdyn.sample_problem, PAPER, "x")
print(f"sample_problem: t outside [{t0}, {t1}] s refused, the ends taken")

# ---- set= values
message = refused(hexdyn.ConfigError, hexdyn.validate, PAPER,
                  set={"gait.duty_factor": np.array([0.5, 0.6])})
assert message.endswith("gait.duty_factor: got [0.5, 0.6], expected a number in [0.5, 1)"), message
for value in (np.nan, np.inf, np.float64(-np.inf), np.array([0.7, np.nan])):
    message = refused(hexdyn.ConfigError, hexdyn.validate, PAPER, set={"gait.duty_factor": value})
    assert ": gait.duty_factor: got " in message and "expected a" in message, message
message = refused(TypeError, hexdyn.validate, PAPER, set={"gait.duty_factor": object()})
assert message.startswith("set: gait.duty_factor: value <object") and "a numpy array" in message
message = refused(TypeError, hexdyn.validate, PAPER,
                  set={"motion.cycle_durations": [3.0, {1, 2}]})
assert message.startswith("set: motion.cycle_durations: value {1, 2}"), message
# What is taken: numpy scalars and 0-d arrays as their value, arrays as their list, inside
# maps too; the same result as the plain values.
same = [({"gait.duty_factor": np.float64(0.75)}, {"gait.duty_factor": 0.75}),
        ({"gait.duty_factor": np.array(0.75)}, {"gait.duty_factor": 0.75}),
        ({"motion.cycle_durations": np.array([3.0, 2.6, 3.0])},
         {"motion.cycle_durations": [3.0, 2.6, 3.0]}),
        ({"motion": {"initial_position": np.array([0, 0.412, 0.235]),
                     "cycle_durations": np.array([3, 2.5, 3])}},
         {"motion": {"initial_position": [0, 0.412, 0.235],
                     "cycle_durations": [3.0, 2.5, 3.0]}})]
for mine, plain in same:
    a, b = hexdyn.run(PAPER, set=mine), hexdyn.run(PAPER, set=plain)
    assert a.config == b.config and np.array_equal(a["/joints/torque"], b["/joints/torque"]), mine
print("set: numpy arrays as lists, refusals naming the key")
print("python arguments: ok")
