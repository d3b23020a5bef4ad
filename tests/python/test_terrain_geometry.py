"""Feet on and over the terrain (docs/theory/stages.md#terrain): ascending and descending
stairs, nosings, step lists with landings, a quadruped's stairs, flat ground and a slope. For
every run, from the stored result only -- /terrain/y, /terrain/z (the profile z(y), an edge two
vertices of equal y), /feet/position, /contacts/phase, and gait.foothold_margin,
gait.swing_clearance and terrain from /meta's config_yaml -- numpy checks that
  1. every contact foot (phase impact or support) lies on the polyline: point-segment
     distance <= 1e-9 m, and the tread's height at its y equals its z to 1e-9 m;
  2. (stairs) every contact foot keeps foothold_margin horizontally, |y - edge y|, from every
     edge, rising or falling;
  3. in a swing's transfer (samples whose horizontal position differs from both the lift-off
     and the touchdown foothold) the foot stands swing_clearance above the highest terrain
     under it (both sides of an edge it is over) and min(swing_clearance, margin) cos a from
     the polyline, a the inclination of the profile's steepest non-vertical segment (the
     clearance is vertical: on treads and flat ground cos a = 1, on the slope a is its angle);
  4. the polyline's y never decreases and (stairs) its treads are level, its edges' y and
     heights those computed here from the scene's count or step list: riser k at
     first_riser_y plus the goings before it, the edge moved by the riser's nosing towards the
     lower tread, a landing (or zero riser) no edge but its going, heights summed from
     ground_height.
Each run has more than 100 contact and 50 transfer foot-samples. Negative controls: one run's
feet with a support foot moved onto an edge (fails 2), its terrain shifted by 2 margin along y
(fails 1 and 4), a transfer sample lowered to half the clearance (fails 3).
The step list has a 0.3 m going, a 0.02 m nosing, a 0.5 m landing and a 0.06 m riser among
0.05 m ones (motion.cycles 5), up and with its risers negated; flat ground is solo12_flat.yaml
sampled every 0.01 s (its 0.05 s leaves too few transfer samples), the slope the hexapod's
stairs scene on 0.2 rad.
    test_terrain_geometry.py HEXDYN_BINARY SOURCE_DIR      (PYTHONPATH: the build tree's python/)
"""

import os
import sys
import tempfile

import h5py
import numpy as np
import yaml
from common import args, cli_run, segment_distance, transfers

HEXDYN, SRC = args()
TOL = 1e-9
EXACT = 1e-12  # the edges against the scene's arithmetic; a transfer sample's displacement
failures = []
quiet = False  # the negative controls' findings are expected: collected, not printed

STEP_LIST = ("[{riser: 0.05}, {riser: 0.04, tread: 0.3}, {riser: 0.05, nosing: 0.02}, "
             "{landing: 0.5}, {riser: 0.06}, {riser: 0.05}, {riser: 0.05}, {riser: 0.05}, "
             "{riser: 0.05}, {riser: 0.05}]")
STEP_LIST_DOWN = STEP_LIST.replace("riser: 0.", "riser: -0.")


def check(cond, what):
    if not cond:
        failures.append(what)
        if not quiet:
            print("FAIL:", what)


def highest_under(ty, tz, lo, hi):
    """Highest terrain of the polyline over y in [lo, hi]: the vertices inside (both of an
    edge's) and the polyline at both ends."""
    inside = tz[(ty >= lo) & (ty <= hi)]
    ends = np.interp([lo, hi], ty, tz)  # an edge at lo or hi: np.interp takes one side
    return max(inside.max() if inside.size else -np.inf, ends.max())


def edges(ty, tz):
    """(y, z before, z after) of every edge: two vertices of equal y and different z."""
    k = np.flatnonzero((np.diff(ty) == 0.0) & (np.diff(tz) != 0.0))
    return ty[k], tz[k], tz[k + 1]


def scene_edges(terrain):
    """(y, z before, z after) of the edges of the scene's stairs, from its count or list."""
    assert terrain.get("riser_scale", 1) == 1 and terrain["step_offset"]["step"] == 0, terrain
    y, z = float(terrain["first_riser_y"]), float(terrain.get("ground_height", 0.0))
    steps = terrain["steps"]
    entries = [{}] * steps if isinstance(steps, int) else steps
    out = []
    for s in entries:
        if "landing" in s:
            y += s["landing"]
            continue
        h = s.get("riser", terrain["riser_height"])
        if h != 0:
            out.append((y - np.sign(h) * s.get("nosing", terrain.get("nosing", 0.0)), z, z + h))
            z += h
        y += s.get("tread", terrain["tread_depth"])
    return np.array(out).reshape(-1, 3).T




def check_run(name, run):
    """Checks 1-4 of the file comment on one run; returns the summary line."""
    ty, tz, feet, phase, cfg = run["y"], run["z"], run["feet"], run["phase"], run["config"]
    terrain, margin = cfg["terrain"], cfg["gait"]["foothold_margin"]
    clearance = cfg["gait"]["swing_clearance"]
    stairs = terrain["type"] == "stairs"
    # 4. The polyline.
    check(np.all(np.diff(ty) >= 0.0), f"{name}: check 4: /terrain/y decreases")
    check(ty[0] <= feet[..., 1].min() and feet[..., 1].max() <= ty[-1],
          f"{name}: check 4: feet at y in [{feet[..., 1].min()}, {feet[..., 1].max()}] beyond "
          f"the profile's [{ty[0]}, {ty[-1]}]")
    ey, ez0, ez1 = edges(ty, tz)
    if stairs:
        flat = np.diff(ty) != 0.0
        check(np.abs(np.diff(tz)[flat]).max() <= EXACT, f"{name}: check 4: a tread not level")
        want = scene_edges(terrain)
        got = np.array([ey, ez0, ez1])
        check(got.shape == want.shape and np.abs(got - want).max() <= EXACT,
              f"{name}: check 4: edges (y, z before, z after)\n{got.T}\nexpected\n{want.T}")
        check(abs(tz[0] - terrain.get("ground_height", 0.0)) <= EXACT,
              f"{name}: check 4: ground at {tz[0]}")
    # 1. Contact feet on the surface.
    contact = phase != 0
    cy, cz = feet[..., 1][contact], feet[..., 2][contact]
    dist = segment_distance(cy, cz, ty, tz)
    dz = np.abs(np.interp(cy, ty, tz) - cz)
    check(contact.sum() > 100, f"{name}: {contact.sum()} contact foot-samples")
    check(dist.max() <= TOL, f"{name}: check 1: a contact foot {dist.max():.3g} m off the "
          f"terrain (y {cy[dist.argmax()]:.6f}, z {cz[dist.argmax()]:.6f})")
    check(dz.max() <= TOL, f"{name}: check 1: a contact foot {dz.max():.3g} m off its tread's "
          f"height (y {cy[dz.argmax()]:.6f}, z {cz[dz.argmax()]:.6f})")
    # 2. Contact feet keep the margin from every edge.
    edge_gap = np.inf
    if stairs:
        check(ey.size >= 3, f"{name}: {ey.size} edges in the terrain")
        gap = np.abs(cy[:, None] - ey[None, :]).min(-1)
        edge_gap = gap.min()
        check(edge_gap >= margin - TOL,
              f"{name}: check 2: a contact foot at y {cy[gap.argmin()]:.6f} stands "
              f"{edge_gap:.6f} m from an edge, margin {margin}")
    # 3. Transfers clear the terrain.
    moving = transfers(feet, phase, EXACT)
    rise, going = np.diff(tz), np.diff(ty)
    sloped = going != 0.0
    cos_a = np.cos(np.arctan(np.abs(rise[sloped] / going[sloped]).max())) if sloped.any() else 1.0
    least = min(clearance, margin) * cos_a
    lift, near = np.inf, np.inf
    for k, leg in moving:
        _, y, z = feet[k, leg]
        lift = min(lift, z - highest_under(ty, tz, y - TOL, y + TOL))
        near = min(near, segment_distance(y, z, ty, tz))
    check(len(moving) > 50, f"{name}: {len(moving)} transfer foot-samples")
    check(lift >= clearance - TOL, f"{name}: check 3: in a transfer a foot stands {lift:.6f} m "
          f"above the terrain under it, swing_clearance {clearance}")
    check(near >= least - TOL,
          f"{name}: check 3: in a transfer a foot is {near:.6f} m from the terrain, expected at "
          f"least min(swing_clearance, margin) cos a = {least:.6f}")
    return (f"{name}: {feet.shape[0]} samples, {contact.sum()} contact foot-samples, "
            f"{len(moving)} transfer foot-samples; least edge clearance "
            + (f"{edge_gap:.6f} m (margin {margin})" if stairs else "n/a")
            + f", least swing clearance {lift:.6f} m (swing_clearance {clearance}), least "
            f"transfer distance {near:.6f} m (least allowed {least:.6f} m)")


def read(path):
    with h5py.File(path, "r") as f:
        check(np.array_equal(f["/feet/time"][()], f["/contacts/time"][()]),
              f"{path}: /feet/time and /contacts/time differ")
        return {"y": f["/terrain/y"][()], "z": f["/terrain/z"][()],
                "feet": f["/feet/position"][()], "phase": f["/contacts/phase"][()],
                "config": yaml.safe_load(f["/meta"].attrs["config_yaml"])}


def control(name, run, must):
    """The checks on a doctored run must fail, among others, with a check in `must`."""
    global quiet
    before, quiet = len(failures), True
    check_run(name, run)
    caught = failures[before:]
    del failures[before:]
    quiet = False
    hit = sorted({c for c in must if any(f"check {c}:" in m for m in caught)})
    print(f"{name}: {len(caught)} failures, checks {hit} among them, as they must")
    check(hit == sorted(must), f"{name}: checks {sorted(must)} expected to fail, {hit} did: "
          f"{caught}")


hexapod = os.path.join(SRC, "configs/sweeps/stairs_base.yaml")
solo_stairs = os.path.join(SRC, "configs/quadrupeds/solo12_crawl_stairs.yaml")
solo_flat = os.path.join(SRC, "configs/robots/solo12_flat.yaml")
no_stairs = [f"terrain.{k}=null" for k in ("riser_height", "tread_depth", "steps",
                                            "first_riser_y")]
RUNS = [
    ("hexapod up", hexapod, []),
    ("hexapod down", hexapod, ["terrain.riser_height=-0.05"]),
    ("hexapod up, nosing 0.025", hexapod, ["terrain.nosing=0.025"]),
    ("hexapod down, nosing 0.025", hexapod,
     ["terrain.nosing=0.025", "terrain.riser_height=-0.05"]),
    ("hexapod step list up", hexapod, [f"terrain.steps={STEP_LIST}", "motion.cycles=5"]),
    ("hexapod step list down", hexapod, [f"terrain.steps={STEP_LIST_DOWN}", "motion.cycles=5"]),
    ("solo12 up", solo_stairs, []),
    ("solo12 down", solo_stairs, ["terrain.riser_height=-0.04"]),
    ("solo12 flat", solo_flat, ["output.sample_step=0.01"]),
    ("hexapod slope 0.2 rad", hexapod, ["terrain.type=slope", "terrain.angle=0.2"] + no_stairs),
]

with tempfile.TemporaryDirectory() as d:
    kept = None
    for name, scene, sets in RUNS:
        out = os.path.join(d, "r.h5")
        rc, err = cli_run(HEXDYN, scene, out, sets)
        check(rc == 0, f"{name}: hexdyn run exited {rc}: {err}")
        if rc != 0:
            continue
        run = read(out)
        print(check_run(name, run))
        if name == "hexapod step list up":
            kept = run
        os.remove(out)

if kept is None:
    check(False, "control: no step-list run to doctor")
else:
    margin = kept["config"]["gait"]["foothold_margin"]
    clearance = kept["config"]["gait"]["swing_clearance"]
    ey, ez0, ez1 = edges(kept["y"], kept["z"])
    # A support foot moved onto the edge nearest it, on the upper tread's height.
    feet = kept["feet"].copy()
    k, leg = np.argwhere(kept["phase"] == 2)[len(feet) // 2]
    e = np.abs(ey - feet[k, leg, 1]).argmin()
    feet[k, leg, 1:] = ey[e], max(ez0[e], ez1[e])
    control("control: support foot on an edge", dict(kept, feet=feet), [2])
    # The terrain shifted by twice the margin along +y.
    control("control: terrain shifted by 2 margin", dict(kept, y=kept["y"] + 2 * margin), [1, 4])
    # A transfer sample lowered to half the clearance above the terrain under it.
    feet = kept["feet"].copy()
    k, leg = transfers(feet, kept["phase"], EXACT)[10]
    y = feet[k, leg, 1]
    feet[k, leg, 2] = highest_under(kept["y"], kept["z"], y - TOL, y + TOL) + clearance / 2
    control("control: transfer foot at half the clearance", dict(kept, feet=feet), [3])

if failures:
    print(f"{len(failures)} failures:")
    for f in failures:
        print("  " + f)
sys.exit(1 if failures else 0)
