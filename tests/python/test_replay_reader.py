#!/usr/bin/python3
"""The reader of hexdyn-replay/3 files (hexdyn.open_replay, docs/user/output.md#hexdyn-replay3)
on a real replay, and the replay's stored series against second computations from them:

  test_replay_reader.py HEXDYN SOURCE_DIR

Runs configs/paper.yaml shortened to one gait cycle (3.4 s), sampled at the replay's step,
and replays it with `hexdyn replay`, then checks:

  - open_replay: a Replay holding every dataset as h5py reads it (dtype, shape, values) with
    its declared units; every dataset of kReplaySeriesDatasets, kReplayModelDatasets and
    kReplayReportDatasets there with its declared shape (T = len(/time), Y =
    len(/replay/cycle_end)), every other one declared too; /meta names the replayed file and
    its created_utc; check_layout says hexdyn-replay/3;
  - xarray: every group opened alone by xarray.open_dataset with both engines (h5netcdf,
    netcdf4), by Replay.to_xarray and by hexdyn.xr.open_replay: each variable on its declared dimensions, with the
    values h5py reads, and the time, joint and leg coordinates /time and /model/*;
  - one-line errors: the result given to open_replay, the replay to open_result: ValueError
    naming both schemas; a copy without /energy/slip, or with /joints/tracking_error of the
    wrong shape: hexdyn.IoError naming the dataset; an undeclared dataset: check_layout
    refuses it;
  - second computations from the stored series:
      /time is the result's first T instants and /joints/feedforward_torque the result's
      /joints/torque there; /joints/tracking_error = replay /joints/position - result
      /joints/position at the same /time, bit for bit; the cumulative series start at 0;
      /contacts/slip_velocity the loaded feet's tangential velocity by forward kinematics of
      /model/urdf (analysis/urdf_fk.py) from the stored state; /contacts/slip_distance on
      the intervals where a foot stays loaded against the trapezoid rule of
      |/contacts/slip_velocity|, and /energy/actuator at the end against that of
      sum |tau q'| (/joints/torque, /joints/velocity), each within the first-order terms of
      the integrator's accumulation, computed from the file (check_slip, check_series);
      /replay/slip_distance, slip_energy, touchdown_energy and energy the last rows of
      /contacts/slip_distance, /energy/slip, /energy/contact_damping and /energy/actuator;
      /replay/max_tracking_error the largest |/joints/tracking_error|, at the joint and
      instant /replay/max_tracking_error_joint and _time say.
"""

import os
import shutil
import subprocess
import sys
import tempfile
import warnings

import h5py
import numpy as np
import xarray as xr

import hexdyn
from hexdyn import results as hr
from hexdyn import xr as hx

HEXDYN, SRC = sys.argv[1], sys.argv[2]
ENGINES = ("h5netcdf", "netcdf4")
# The paper scene shortened to one gait cycle of 3.4 s (a ramp up and down, no cruise),
# sampled every replay.step (1 ms, its default), so that the samples are the integrator's
# steps (check_slip); the run and its replay take about a second.
SHORT = ("motion.cycle_durations=null", "motion.cycles=1", "motion.peak_speed=0.098",
         "motion.ramp_duration=0.8", "output.grid=uniform", "output.sample_step=1e-3",
         "output.event_step=1e-3", "replay.step=1e-3")
failures = []


def check(ok, what, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail and not ok else ''}")
    if not ok:
        failures.append(what)


def make_files(d):
    """(result, replay, stick_slip) paths: the short paper run and its replays through the CLI,
    with the regularised friction law (whose slip check_slip integrates) and with the default
    stick-slip law (check_stick_slip)."""
    result, replay = os.path.join(d, "plan.h5"), os.path.join(d, "replay.h5")
    stick_slip = os.path.join(d, "stick_slip.h5")
    cmd = [HEXDYN, "run", os.path.join(SRC, "configs", "paper.yaml"), "-o", result]
    subprocess.run(cmd + [a for s in SHORT for a in ("--set", s)], check=True,
                   capture_output=True)
    subprocess.run([HEXDYN, "replay", result, "-o", replay, "--set",
                    "contact.friction_law=regularised"], check=True, capture_output=True)
    subprocess.run([HEXDYN, "replay", result, "-o", stick_slip], check=True, capture_output=True)
    return result, replay, stick_slip


def declared_specs():
    return [d for name in ("kReplaySeriesDatasets", "kReplayModelDatasets",
                           "kReplayReportDatasets") for d in hr.SCHEMA[name]]


def h5_value(ds):
    """A dataset's values as h5py reads them: numbers as arrays, text as str or list of str."""
    if h5py.check_string_dtype(ds.dtype) is not None:
        v = ds.asstr()[()]
        return v if ds.shape == () else [str(x) for x in np.asarray(v).ravel()]
    return ds[()]


def check_reader(result, replay):
    """open_replay against h5py, the declared layout and /meta; check_layout. The Replay."""
    rep = hexdyn.open_replay(replay)
    check(isinstance(rep, hexdyn.Replay), "open_replay returns a Replay")
    check(hexdyn.check_layout(replay) == "hexdyn-replay/3", "check_layout: hexdyn-replay/3")
    with h5py.File(replay, "r") as f, h5py.File(result, "r") as r:
        T, Y = f["time"].shape[0], f["replay/cycle_end"].shape[0]
        sizes = {"T": T, "Y": Y, "K": f["terrain/y"].shape[0], **hr.shape_sizes(f)}
        for spec in declared_specs():
            ds = f.get(spec.path)
            check(isinstance(ds, h5py.Dataset), f"{spec.path} present")
            if ds is None:
                continue
            want = tuple(sizes[s] if isinstance(s, str) else s for s in spec.shape)
            check(ds.shape == want, f"{spec.path} shape {want}", f"got {ds.shape}")
            check(hr.decode_text(ds.attrs.get("units", "")) == spec.units,
                  f"{spec.path} units {spec.units!r}")
            v, mine = h5_value(ds), rep[spec.path]
            if isinstance(v, (str, list)):
                check(mine == v, f"Replay[{spec.path}] is the file's text")
            else:
                check(np.asarray(mine).dtype == ds.dtype and np.array_equal(mine, v),
                      f"Replay[{spec.path}] is the file's dataset, bit for bit")
            check(rep.units.get(spec.path, "") == spec.units, f"Replay.units[{spec.path}]")
        # Every other dataset of the file (the group coordinates, copies of the root's, aside):
        # declared, and what the Replay holds.
        others = []
        f.visititems(lambda n, o: others.append("/" + n) if isinstance(o, h5py.Dataset) and
                     not ("/" in n and h5py.h5ds.is_scale(o.id)) else None)
        for path in sorted(set(others) - {s.path for s in declared_specs()}):
            check(path in hr.DECLARED, f"{path} declared in the schema")
            v = h5_value(f[path])
            check(path in rep and (rep[path] == v if isinstance(v, (str, list)) else
                                   np.array_equal(rep[path], v)), f"Replay[{path}] is the file's")
        check(rep.samples == T, "Replay.samples = len(/time)")
        check(rep.source_result == os.path.abspath(result), "/meta source_result is the result",
              rep.source_result)
        check(rep.meta.get("source_created_utc") == hr.decode_text(r["meta"].attrs["created_utc"]),
              "/meta source_created_utc is the result's created_utc")
        check(rep.reached_top == bool(f["replay/reached_top"][()]), "Replay.reached_top")
    check(set(rep.config) >= {"replay", "contact"}, "Replay.config holds replay: and contact:")
    return rep


def check_xarray(replay, rep):
    """Every group with both engines and through Replay.to_xarray: declared dims, values."""
    with h5py.File(replay, "r") as f:
        groups = sorted({os.path.dirname(s.path) for s in declared_specs()})
        coords = {"time": f["time"][()], "joint": h5_value(f["model/joint_names"]),
                  "leg": h5_value(f["model/leg_names"])}
        values = {s.path: h5_value(f[s.path]) for s in declared_specs()}
    specs = {s.path: s for s in declared_specs()}
    for group in groups:
        views = [("to_xarray", rep.to_xarray(group)),
                 ("hexdyn.xr.open_replay", hx.open_replay(replay, group))]
        for engine in ENGINES:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                views.append((engine, xr.open_dataset(replay, engine=engine, group=group)
                              .load()))
        for how, ds in views:
            where = f"{group} ({how})"
            for path, spec in specs.items():
                if os.path.dirname(path) != group or path == "/time":
                    continue
                var = ds.get(path.rsplit("/", 1)[1])
                check(var is not None, f"{where}: {path} present")
                if var is None:
                    continue
                check(tuple(var.dims) == spec.dims, f"{where}: {path} dims {spec.dims}",
                      f"got {var.dims}")
                want = values[path]
                got = var.values if not isinstance(want, (str, list)) else (
                    str(var.values) if isinstance(want, str) else [str(x) for x in var.values])
                check(np.array_equal(got, want) if not isinstance(want, (str, list))
                      else got == want, f"{where}: {path} values")
            for dim, want in coords.items():
                if dim in ds.dims:
                    got = ds[dim].values
                    ok = (np.array_equal(got, want) if dim == "time"
                          else [str(x) for x in got] == want)
                    check(ok, f"{where}: coordinate {dim} is {'/time' if dim == 'time' else 'model'}")
            phony = [d for d in ds.dims if str(d).startswith("phony_dim")]
            check(not phony, f"{where}: no phony dimensions", str(phony))
            ds.close()


def raises(cls, f, *args):
    try:
        f(*args)
    except cls as e:
        return str(e)
    except BaseException as e:  # noqa: B036 (what else came through is the failure)
        return f"<{type(e).__name__}: {e}>"
    return "<no exception>"


def check_errors(d, result, replay):
    """One line for a file of the other kind, a missing dataset, a wrong shape, an
    undeclared dataset."""
    msg = raises(ValueError, hexdyn.open_replay, result)
    check("\n" not in msg and "hexdyn-result/5" in msg and "hexdyn-replay/3" in msg
          and result in msg, "open_replay(result): ValueError, one line naming both schemas", msg)
    msg = raises(ValueError, hexdyn.open_result, replay)
    check("\n" not in msg and "hexdyn-replay/3" in msg and "hexdyn-result/5" in msg,
          "open_result(replay): ValueError, one line naming both schemas", msg)
    for edit, path, what in (("delete", "/energy/slip", "missing dataset"),
                             ("reshape", "/joints/tracking_error", "wrong shape"),
                             ("add", "/replay/extra", "undeclared dataset")):
        bad = os.path.join(d, f"bad_{edit}.h5")
        shutil.copy(replay, bad)
        with h5py.File(bad, "a") as f:
            if edit == "delete":
                del f[path]
            elif edit == "reshape":
                v = f[path][()]
                del f[path]
                f[path] = v[:, :17]
            else:
                f[path] = np.zeros(3)
        reader = hexdyn.check_layout if edit == "add" else hexdyn.open_replay
        msg = raises(hexdyn.IoError, reader, bad)
        check("\n" not in msg and path in msg and bad in msg,
              f"{reader.__name__} of a {what}: hexdyn.IoError, one line naming {path}", msg)


def trapezoid(t, y):
    """The trapezoid rule of y (T, ...) over t, per interval (T-1, ...)."""
    h = np.diff(t).reshape((-1,) + (1,) * (np.ndim(y) - 1))
    return 0.5 * h * (y[1:] + y[:-1])


def quat_mul(a, b):
    """Hamilton products of quaternions (..., 4), w first."""
    w1, x1, y1, z1 = np.moveaxis(a, -1, 0)
    w2, x2, y2, z2 = np.moveaxis(b, -1, 0)
    return np.stack([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2],
                    axis=-1)


def turned(quat, omega, dt):
    """The orientation `quat` (w, x, y, z, body to world) turned for dt at the world-axes
    angular velocity omega."""
    a = omega * dt
    angle = np.linalg.norm(a, axis=-1, keepdims=True)
    axis = a / np.where(angle > 0, angle, 1.0)
    return quat_mul(np.concatenate([np.cos(angle / 2), np.sin(angle / 2) * axis], axis=-1), quat)


def feet_velocity(robot, p, quat, q, v, omega, qd, eps=1e-6):
    """The feet's velocities (T, L, 3) by central differences of the forward kinematics of
    /model/urdf (analysis/urdf_fk.py, not hexdyn's): the configuration (p, quat, q) moved
    along the velocity (v, omega, qd) for +-eps seconds (an error of order eps^2)."""
    ahead = robot.foot_positions(p + eps * v, turned(quat, omega, eps), q + eps * qd)
    behind = robot.foot_positions(p - eps * v, turned(quat, omega, -eps), q - eps * qd)
    return (ahead - behind) / (2.0 * eps)


def check_slip(rep):
    """/contacts/slip_velocity is the feet's tangential velocity, by forward kinematics of the
    stored state; /contacts/slip_distance grows as the trapezoid rule of its norm, within the
    integrator's first-order terms.

    The replay integrates by linearly implicit Euler, first order in its step h
    (src/hexdyn/replay/replay.hpp), and adds h |v_t| to a foot's slip distance at the end of
    each step, v_t the tangential velocity of the step's final rates at the configuration of
    the step's start (replay.cpp, account_step). The scene's samples are the integrator's
    steps (a uniform grid at replay.step). On an interval [i, i+1] where the foot stays
    loaded, the stored increment then differs from the trapezoid rule of the stored slip
    speeds s by two terms of order h, both computed here from the file:
      - the rectangle rule against the trapezoid: h |s_{i+1} - s_i| / 2;
      - the lag of the configuration: h |s_lag - s_{i+1}|, s_lag the tangential speed of
        the rates of i+1 at the configuration of i (forward kinematics again).
    Their sum over the loaded intervals is the tolerance (a step halved by the replay's error
    control, near touchdowns, falls inside it too). The intervals where the foot loads or
    unloads are left out: the replay halves its step there and the samples cannot resolve
    the slip between them."""
    sys.path.insert(0, os.path.join(SRC, "analysis"))
    from urdf_fk import UrdfRobot

    t, h = rep["/time"], np.diff(rep["/time"])
    robot = UrdfRobot(rep.urdf, joint_order=tuple(rep["/model/joint_names"]))
    pose = (rep["/base/position"], rep["/base/orientation"], rep["/joints/position"])
    rates = (rep["/base/linear_velocity"], rep["/base/angular_velocity"],
             rep["/joints/velocity"])
    vs, fn = rep["/contacts/slip_velocity"], rep["/contacts/normal_force"]
    loaded = fn > 0
    # The feet stand on treads (normal +z): the tangential velocity is the horizontal one.
    check(np.all(vs[..., 2] == 0.0), "/contacts/slip_velocity lies in the treads' plane")
    v_feet = feet_velocity(robot, *pose, *rates)
    worst = float(np.max(np.abs(v_feet[..., :2] - vs[..., :2])[loaded]))
    check(worst <= 1e-8, "/contacts/slip_velocity = the loaded feet's velocity by forward "
          "kinematics of /model/urdf", f"worst {worst:.3g} m/s")
    step = float(rep["/replay/step"])
    check(np.max(h) <= step * (1.0 + 1e-9), "no sample interval longer than one step",
          f"{np.max(h):.6g} s, step {step:.6g} s")
    s = np.linalg.norm(vs, axis=-1)
    v_lag = feet_velocity(robot, *(x[:-1] for x in pose), *(x[1:] for x in rates))
    s_lag = np.linalg.norm(v_lag[..., :2], axis=-1)
    both = loaded[1:] & loaded[:-1]
    increments = np.diff(rep["/contacts/slip_distance"], axis=0)
    gap = np.abs(np.sum(np.where(both, increments - trapezoid(t, s), 0.0), axis=0))
    rectangle = np.sum(np.where(both, 0.5 * h[:, None] * np.abs(np.diff(s, axis=0)), 0.0), axis=0)
    lag = np.sum(np.where(both, h[:, None] * np.abs(s_lag - s[1:]), 0.0), axis=0)
    share = np.sum(np.where(both, increments, 0.0), axis=0) / rep["/contacts/slip_distance"][-1]
    check(np.all(gap <= rectangle + lag), "/contacts/slip_distance on loaded intervals = the "
          "trapezoid of |/contacts/slip_velocity| within the integrator's first-order terms",
          f"gap {gap}, rectangle {rectangle}, lag {lag}")
    print(f"     slip distance, loaded intervals ({np.round(100 * share)} % of it): gap "
          f"{np.round(gap * 1e6, 2)} um within {np.round((rectangle + lag) * 1e6, 2)} um")


def check_stick_slip(path):
    """With the stick-slip law (docs/theory/replay.md#stick-slip) slip is the anchor's motion:
    on an interval between samples at both of whose ends a foot is loaded (F_n > 1 N) below
    0.9 mu_s F_n, its /contacts/slip_distance does not grow at all; and where it grows on a
    loaded interval the foot ends the interval sliding, at |F_t| = mu_d F_n, for most of the
    distance (a foot that slid within a step and stuck again before the sample is the rest)."""
    with h5py.File(path, "r") as f:
        force, fn = f["contacts/force"][()], f["contacts/normal_force"][()]
        dist = f["contacts/slip_distance"][()]
    mu = 0.3  # configs/paper.yaml's mu = mu_s = mu_d
    ft = np.sqrt(np.maximum(0.0, np.sum(force ** 2, axis=-1) - fn ** 2))
    held = (fn > 1.0) & (ft < 0.9 * mu * fn)
    inc = np.diff(dist, axis=0)
    both_held = held[1:] & held[:-1]
    check(np.all(inc[both_held] == 0.0), "stick-slip: a foot held below 0.9 mu_s F_n at both "
          "ends of an interval does not slip in it", f"{np.max(inc[both_held]):.3g} m")
    loaded = (fn[1:] > 1.0) & (fn[:-1] > 1.0)
    sliding = loaded & (np.abs(ft[1:] - mu * fn[1:]) <= 1e-9 * fn[1:])
    total = np.sum(np.where(loaded, inc, 0.0))
    share = np.sum(np.where(sliding, inc, 0.0)) / total if total > 0 else 1.0
    check(share >= 0.5, "stick-slip: most slip on loaded intervals ends them sliding at mu_d F_n",
          f"{100 * share:.1f} %")
    print(f"     stick-slip: slip {np.round(dist[-1] * 1e6, 2)} um per foot; "
          f"{100 * share:.1f} % of the loaded intervals' slip ends sliding")


def check_series(result, rep):
    with h5py.File(result, "r") as f:
        t_plan, q_plan, tau_plan = (f[p][()] for p in ("time", "joints/position", "joints/torque"))
    t = rep["/time"]
    T = t.size
    check(T <= t_plan.size and np.array_equal(t, t_plan[:T]),
          "/time is the result's first T instants")
    check(np.array_equal(rep["/joints/feedforward_torque"], tau_plan[:T]),
          "/joints/feedforward_torque is the result's /joints/torque at the same /time")
    err = rep["/joints/tracking_error"]
    # Both subtract the same two doubles: equal to the last bit.
    check(np.array_equal(err, rep["/joints/position"] - q_plan[:T]),
          "/joints/tracking_error = replay - result /joints/position, bit for bit")
    for p in ("/contacts/slip_distance", "/contacts/slip_displacement", "/energy/actuator",
              "/energy/slip", "/energy/contact_damping"):
        check(np.all(rep[p][0] == 0.0), f"{p} starts at 0 (cumulative from the start)")
    check_slip(rep)

    # /energy/actuator: the replay adds h sum|tau q'| at each step's end with the torques
    # and rates of that end, the stored sample's (replay.cpp, account_step): against the
    # trapezoid rule, the rectangle's first-order term h |p_{i+1} - p_i| / 2 is the tolerance.
    power = np.sum(np.abs(rep["/joints/torque"] * rep["/joints/velocity"]), axis=1)
    stored, trap = rep["/energy/actuator"][-1], np.sum(trapezoid(t, power))
    bound = np.sum(0.5 * np.diff(t) * np.abs(np.diff(power)))
    check(abs(stored - trap) <= bound, "/energy/actuator at the end = the trapezoid of "
          "sum |tau q'| within the rectangle's first-order term",
          f"stored {stored:.9g} J, trapezoid {trap:.9g} J, bound {bound:.3g} J")
    print(f"     /energy/actuator {stored:.6f} J, trapezoid {trap:.6f} J, within {bound:.3g} J")

    # The report: the last rows of the series, and the largest tracking error.
    for total, series in (("/replay/slip_distance", "/contacts/slip_distance"),
                          ("/replay/slip_energy", "/energy/slip"),
                          ("/replay/touchdown_energy", "/energy/contact_damping"),
                          ("/replay/energy", "/energy/actuator")):
        check(np.array_equal(rep[total], rep[series][-1]), f"{total} = the last row of {series}")
    k = np.unravel_index(np.argmax(np.abs(err)), err.shape)
    check(float(rep["/replay/max_tracking_error"]) == float(np.max(np.abs(err))),
          "/replay/max_tracking_error = max |/joints/tracking_error|")
    check(int(rep["/replay/max_tracking_error_joint"]) == k[1]
          and float(rep["/replay/max_tracking_error_time"]) == t[k[0]],
          "/replay/max_tracking_error_joint and _time: where it occurs")


def main():
    with tempfile.TemporaryDirectory() as d:
        result, replay, stick_slip = make_files(d)
        rep = check_reader(result, replay)
        check_xarray(replay, rep)
        check_errors(d, result, replay)
        check_series(result, rep)
        check_stick_slip(stick_slip)
    if failures:
        print(f"{len(failures)} check(s) failed: {'; '.join(failures)}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
