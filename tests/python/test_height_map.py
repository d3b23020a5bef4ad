"""Height maps (terrain.type height_map, docs/theory/stages.md#height-maps), each checked
against something computed here with numpy, not by hexdyn:
  1. the paper's stairs (configs/paper.yaml: 12 risers of 0.05 m on 0.25 m treads from y = 0)
     sampled at 1 mm (x in [-0.6, 0.6], y from -0.4995: the half millimetre keeps nodes off the
     risers; slope atan(0.05/0.25)) give the analytic stairs' footholds -- per leg, the stances'
     positions (/feet/position where /contacts/phase is support), to 1 mm -- and /energy/total
     to 1e-3 relative, with the scene's margin and with gait.foothold_margin 0.1 (footholds
     moved by the margin rule);
  2. one grid (risers of 1/16 m, exact in float32, at 5 mm) as a C-order float64 .npy, a
     Fortran-order .npy, a float32 .npy, an HDF5 file's "elevation" and an .hdf5 file's
     "/maps/z" (terrain.height_map.dataset) give the same /joints/torque and /feet/position,
     bit for bit;
  3. the stored /terrain/map_z is the grid written, /terrain/map_x and map_y are origin + index
     resolution (1e-12), /terrain's type is "height_map" and /terrain/z the bilinear height at
     x = 0 of /terrain/y;
  4. bad input -- NaN and infinite holes (the count and the first hole's row and column in the
     message), 1-D, 3-D and 1 x 5 arrays, a text file named .npy, an HDF5 file without the
     dataset, a .txt file, a missing file, resolution 0, an origin of one number -- exits non-zero
     with one stderr line "hexdyn: error: ..." naming terrain.height_map, writing nothing;
  5. on analysis/make_rough_map.py's map with configs/terrain/rough_map.yaml -- as it is, with
     max_slope 0.1 (steep patches of the noise become no-foothold nodes) and with
     foothold_margin 0.06 -- from the result file alone (and check 3): (a) every contact foot
     lies on the bilinear surface of /terrain/map_* (1e-9 m); (b) every support foot keeps
     foothold_margin - (sqrt 2 / 2) resolution from every no-foothold node (a 4-neighbour more
     than edge_height above or below, or a central-difference slope steeper than
     tan(max_slope); brute-force distances); (c) in a swing's transfer the foot stands
     swing_clearance above the bilinear surface under it. More than 100 contact and 50
     transfer foot-samples. Negative controls on the first run: a contact foot raised 1 um
     (fails a), a support foot moved onto a slab's edge (fails b), a transfer foot at half the
     clearance (fails c).
    test_height_map.py HEXDYN_BINARY SOURCE_DIR      (PYTHONPATH: the build tree's python/)
"""

import math
import os
import re
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import yaml
from common import args, cli_run, transfers

HEXDYN, SRC = args()
TOL = 1e-9
EXACT = 1e-12
FOOTHOLD_TOL = 1e-3  # m, check 1
ENERGY_TOL = 1e-3    # relative, check 1
SUPPORT = 2          # /contacts/phase: 0 swing, 1 impact, 2 support
PAPER = os.path.join(SRC, "configs/paper.yaml")
# Check 5's runs of configs/terrain/rough_map.yaml (the first doctored for the controls): as it
# is; with a max_slope that makes the noise's steeper patches no-foothold nodes; with a margin
# that moves footholds away from the slabs' sides.
ROUGH_RUNS = [("rough map", []),
              ("rough map, max_slope 0.1", ["terrain.height_map.max_slope=0.1"]),
              ("rough map, foothold_margin 0.06", ["gait.foothold_margin=0.06"])]
NO_STAIRS = {k: None for k in ("riser_height", "tread_depth", "steps", "first_riser_y",
                               "ground_height")}
failures = []
quiet = False  # the negative controls' findings are expected: collected, not printed


def check(cond, what):
    if not cond:
        failures.append(what)
        if not quiet:
            print("FAIL:", what)


def write_scene(d, name, height_map, inherit=PAPER):
    """A scene in d inheriting `inherit` with terrain.type height_map; returns its path."""
    path = os.path.join(d, name + ".yaml")
    terrain = dict(NO_STAIRS, type="height_map", height_map=height_map)
    with open(path, "w") as f:
        yaml.safe_dump({"inherit": inherit, "name": name, "terrain": terrain}, f)
    return path


def stairs_grid(res, nx, ny, x0, y0, riser, tread=0.25, steps=12):
    """Heights of the stairs riser * clip(floor(y / tread) + 1, 0, steps), row i at y0 + i res."""
    y = y0 + res * np.arange(ny)
    z = riser * np.clip(np.floor(y / tread) + 1, 0, steps)
    return np.repeat(z[:, None], nx, axis=1), (x0, y0)


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def read(path):
    with h5py.File(path, "r") as f:
        out = {"feet": f["/feet/position"][()], "phase": f["/contacts/phase"][()],
               "torque": f["/joints/torque"][()], "energy": float(f["/energy/total"][()]),
               "config": yaml.safe_load(f["/meta"].attrs["config_yaml"]),
               "type": text(f["/terrain"].attrs.get("type", "")),
               "y": f["/terrain/y"][()], "z": f["/terrain/z"][()]}
        for k in ("map_x", "map_y", "map_z"):
            out[k] = f["/terrain/" + k][()] if k in f["/terrain"] else None
    return out


def run(name, scene, out, sets=()):
    """hexdyn run; the result read, or None (a failure recorded) when it fails."""
    rc, err = cli_run(HEXDYN, scene, out, sets)
    check(rc == 0, f"{name}: hexdyn run exited {rc}: {err.strip()[-500:]}")
    if rc != 0:
        return None
    r = read(out)
    os.remove(out)
    return r


def stances(feet, phase):
    """Per leg, the position of each stance (run of support samples), in order."""
    out = []
    for leg in range(feet.shape[1]):
        idx = np.flatnonzero(phase[:, leg] == SUPPORT)
        runs = np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1) if idx.size else []
        out.append(np.array([feet[r[0], leg] for r in runs]).reshape(-1, 3))
    return out


def bilinear(mx, my, mz, x, y):
    """Bilinear height of the grid (mx, my, mz) at (x, y), the border continued outside."""
    res_x, res_y = mx[1] - mx[0], my[1] - my[0]
    s = np.clip((np.asarray(x) - mx[0]) / res_x, 0.0, len(mx) - 1)
    t = np.clip((np.asarray(y) - my[0]) / res_y, 0.0, len(my) - 1)
    j = np.minimum(np.floor(s).astype(int), len(mx) - 2)
    i = np.minimum(np.floor(t).astype(int), len(my) - 2)
    u, w = s - j, t - i
    lo = mz[i, j] + u * (mz[i, j + 1] - mz[i, j])
    hi = mz[i + 1, j] + u * (mz[i + 1, j + 1] - mz[i + 1, j])
    return lo + w * (hi - lo)


def no_foothold(mz, res, edge_height, max_slope):
    """(edge, steep) masks: a 4-neighbour more than edge_height above or below; the central
    (one-sided at the border) difference slope steeper than tan(max_slope)."""
    edge = np.zeros(mz.shape, bool)
    dy, dx = np.abs(np.diff(mz, axis=0)) > edge_height, np.abs(np.diff(mz, axis=1)) > edge_height
    edge[:-1] |= dy
    edge[1:] |= dy
    edge[:, :-1] |= dx
    edge[:, 1:] |= dx
    gy, gx = np.gradient(mz, res)
    return edge, np.hypot(gx, gy) > math.tan(max_slope)




def check_stairs(d):
    """Check 1; returns the 1 mm map (grid, origin) and its map run for check 3."""
    grid, origin = stairs_grid(0.001, 1201, 4001, -0.6, -0.4995, 0.05)
    np.save(os.path.join(d, "stairs.npy"), grid)
    scene = write_scene(d, "paper_map", {"file": "stairs.npy", "resolution": 0.001,
                                         "origin": list(origin), "slope": math.atan(0.05 / 0.25)})
    out = os.path.join(d, "r.h5")
    kept = None
    for label, sets in (("scene's margin", []), ("margin 0.1", ["gait.foothold_margin=0.1"])):
        a = run(f"check 1: analytic stairs, {label}", PAPER, out, sets)
        m = run(f"check 1: 1 mm map, {label}", scene, out, sets)
        if a is None or m is None:
            continue
        kept = kept or m
        fa, fm = stances(a["feet"], a["phase"]), stances(m["feet"], m["phase"])
        worst, where = 0.0, ""
        for leg, (p, q) in enumerate(zip(fa, fm)):
            check(p.shape == q.shape, f"check 1: {label}: leg {leg + 1}: {len(p)} stances on the "
                  f"analytic stairs, {len(q)} on the map")
            if p.shape == q.shape and p.size:
                diff = np.abs(p - q).max(-1)
                if diff.max() > worst:
                    k = diff.argmax()
                    worst = diff.max()
                    where = f" (leg {leg + 1}, stance {k + 1}: {p[k]} vs {q[k]})"
        rel = abs(m["energy"] - a["energy"]) / abs(a["energy"])
        print(f"check 1: {label}: {len(a['feet'])} / {len(m['feet'])} samples (analytic / map), "
              f"{sum(len(p) for p in fa)} stances; largest foothold difference {worst * 1e3:.4f} "
              f"mm{where}; energy {a['energy']:.9g} / {m['energy']:.9g} J, relative difference "
              f"{rel:.3g}")
        check(worst <= FOOTHOLD_TOL, f"check 1: {label}: footholds differ by {worst * 1e3:.4f} mm "
              f"(> {FOOTHOLD_TOL * 1e3:g} mm){where}")
        check(rel <= ENERGY_TOL, f"check 1: {label}: /energy/total {a['energy']} analytic, "
              f"{m['energy']} on the map: relative difference {rel:.3g} > {ENERGY_TOL}")
    return grid, origin, 0.001, kept


def check_stored(name, r, grid, origin, res):
    """Check 3 on one map run."""
    if r is None:
        return
    check(r["type"] == "height_map", f"check 3: {name}: /terrain type '{r['type']}'")
    if any(r[k] is None for k in ("map_x", "map_y", "map_z")):
        check(False, f"check 3: {name}: /terrain/map_x, map_y or map_z missing")
        return
    mx, my, mz = r["map_x"], r["map_y"], r["map_z"]
    check(mz.dtype == np.float64 and np.array_equal(mz, grid),
          f"check 3: {name}: /terrain/map_z ({mz.dtype}, {mz.shape}) is not the grid written "
          f"({grid.shape})")
    want_x = origin[0] + res * np.arange(grid.shape[1])
    want_y = origin[1] + res * np.arange(grid.shape[0])
    ok_x = mx.shape == want_x.shape and np.abs(mx - want_x).max() <= EXACT
    ok_y = my.shape == want_y.shape and np.abs(my - want_y).max() <= EXACT
    check(ok_x and ok_y, f"check 3: {name}: /terrain/map_x {mx.shape} or map_y {my.shape} are "
          f"not origin + index resolution")
    if ok_x and ok_y:
        prof = np.abs(r["z"] - bilinear(mx, my, mz, 0.0, r["y"])).max()
        check(prof <= EXACT, f"check 3: {name}: /terrain/z is {prof:.3g} m off the map at x = 0")
        print(f"check 3: {name}: /terrain/map_z the {mz.shape[0]} x {mz.shape[1]} grid written, "
              f"map_x, map_y origin + index resolution, /terrain/z off the map at x = 0 by "
              f"{prof:.3g} m")


def check_formats(d):
    """Check 2 (and check 3 on the .npy runs)."""
    res = 0.005
    grid, origin = stairs_grid(res, 241, 801, -0.6, -0.4975, 1 / 16)
    check(np.array_equal(grid.astype(np.float32).astype(np.float64), grid),
          "check 2: the grid is not exact in float32 (the test's own grid)")
    np.save(os.path.join(d, "c.npy"), grid)
    np.save(os.path.join(d, "f.npy"), np.asfortranarray(grid))
    np.save(os.path.join(d, "f4.npy"), grid.astype(np.float32))
    check(np.load(os.path.join(d, "f.npy")).flags.f_contiguous
          and np.load(os.path.join(d, "f4.npy")).dtype == np.float32,
          "check 2: the Fortran or float32 .npy is not (the test's own files)")
    with h5py.File(os.path.join(d, "e.h5"), "w") as f:
        f["elevation"] = grid
    with h5py.File(os.path.join(d, "m.hdf5"), "w") as f:
        f["maps/z"] = grid
    hm = {"resolution": res, "origin": list(origin), "slope": math.atan(1 / 16 / 0.25)}
    files = [("C-order float64 .npy", "c.npy", {}), ("Fortran-order .npy", "f.npy", {}),
             ("float32 .npy", "f4.npy", {}), ("HDF5 'elevation'", "e.h5", {}),
             ("HDF5 '/maps/z'", "m.hdf5", {"dataset": "/maps/z"})]
    ref = None
    for i, (label, file, extra) in enumerate(files):
        scene = write_scene(d, f"format{i}", dict(hm, file=file, **extra))
        r = run(f"check 2: {label}", scene, os.path.join(d, "r.h5"))
        if file.endswith(".npy"):
            check_stored(label, r, grid, origin, res)
        if i == 0:
            ref = r
        if r is None or ref is None or i == 0:
            continue
        same = [k for k, key in (("/joints/torque", "torque"), ("/feet/position", "feet"))
                if np.array_equal(r[key], ref[key])]
        print(f"check 2: {label}: {', '.join(same) or 'nothing'} bit for bit as the C-order "
              f"float64 .npy")
        check(len(same) == 2, f"check 2: {label}: /joints/torque or /feet/position differ from "
              f"the C-order float64 .npy's")


def bad_input(d):
    """Check 4: (label, height_map, [numbers the message must give]) runs."""
    z = np.zeros((50, 40))
    holes = z.copy()
    holes[9, 3], holes[5, 30], holes[40, 39] = np.nan, np.nan, np.inf  # row-major first: (5, 30)
    np.save(os.path.join(d, "holes.npy"), holes)
    np.save(os.path.join(d, "one.npy"), np.zeros(5))
    np.save(os.path.join(d, "three.npy"), np.zeros((3, 4, 5)))
    np.save(os.path.join(d, "row.npy"), np.zeros((1, 5)))
    np.save(os.path.join(d, "flat.npy"), z)
    with open(os.path.join(d, "text.npy"), "w") as f:
        f.write("0 0 0\n0 0 0\n")
    with open(os.path.join(d, "flat.txt"), "w") as f:
        f.write("0 0 0\n0 0 0\n")
    with h5py.File(os.path.join(d, "other.h5"), "w") as f:
        f["heights"] = z
    base = {"resolution": 0.05, "origin": [-1.0, -1.0]}
    cases = [("NaN holes", dict(base, file="holes.npy"), (3, 5, 30)),
             ("a 1-D array", dict(base, file="one.npy"), ()),
             ("a 3-D array", dict(base, file="three.npy"), ()),
             ("a 1 x 5 array", dict(base, file="row.npy"), ()),
             ("a text file named .npy", dict(base, file="text.npy"), ()),
             ("an HDF5 file without the dataset", dict(base, file="other.h5"), ()),
             ("a .txt file", dict(base, file="flat.txt"), ()),
             ("a missing file", dict(base, file="missing.npy"), ()),
             ("resolution 0", dict(base, file="flat.npy", resolution=0), ()),
             ("an origin of one number", dict(base, file="flat.npy", origin=[-1.0]), ())]
    out = os.path.join(d, "bad.h5")
    for i, (label, hm, numbers) in enumerate(cases):
        scene = write_scene(d, f"bad{i}", hm)
        p = subprocess.run([HEXDYN, "run", scene, "-o", out], capture_output=True, text=True)
        lines = p.stderr.strip().splitlines()
        line = lines[0] if lines else ""
        check(p.returncode != 0, f"check 4: {label}: exit status 0")
        check(len(lines) == 1 and line.startswith("hexdyn: error: ")
              and "terrain.height_map" in line,
              f"check 4: {label}: exit status {p.returncode}, stderr {p.stderr.strip()!r}, "
              "expected one line 'hexdyn: error: ...' naming terrain.height_map")
        check(not os.path.exists(out), f"check 4: {label}: wrote {out}")
        if os.path.exists(out):
            os.remove(out)
        if numbers:
            m = re.search(r"(\d+) holes.*row (\d+), column (\d+)", line)
            got = tuple(int(g) for g in m.groups()) if m else None
            check(got == numbers, f"check 4: {label}: (holes, row, column) {got} in {line!r}, "
                  f"expected {numbers}")
        print(f"check 4: {label}: exit {p.returncode}: {line.replace(d + os.sep, '')}")


def check_rough(name, r):
    """Checks 5a-5c on one run (or a doctored copy); returns the summary line."""
    cfg, feet, phase = r["config"], r["feet"], r["phase"]
    hm, gait = cfg["terrain"]["height_map"], cfg["gait"]
    margin, clearance = gait["foothold_margin"], gait["swing_clearance"]
    check(float(cfg["robot"].get("foot_radius", 0) or 0) == 0.0,
          f"{name}: the checks are for point feet, robot.foot_radius {cfg['robot']['foot_radius']}")
    mx, my, mz = r["map_x"], r["map_y"], r["map_z"]
    res = hm["resolution"]
    # (a) Contact feet on the bilinear surface.
    contact = phase != 0
    c = feet[contact]
    off = np.abs(c[:, 2] - bilinear(mx, my, mz, c[:, 0], c[:, 1]))
    check(contact.sum() > 100, f"{name}: {contact.sum()} contact foot-samples")
    check(off.max() <= TOL, f"{name}: check 5a: a contact foot {off.max():.3g} m off the map at "
          f"{c[off.argmax()]}")
    # (b) Support feet keep the margin from every no-foothold node.
    edge, steep = no_foothold(mz, res, hm["edge_height"], hm["max_slope"])
    ii, jj = np.nonzero(edge | steep)
    nodes = np.stack([mx[jj], my[ii]], axis=-1)
    support = np.unique(feet[phase == SUPPORT][:, :2], axis=0)
    gap = np.linalg.norm(support[:, None, :] - nodes[None, :, :], axis=-1).min(-1)
    least = margin - math.sqrt(0.5) * res - TOL
    check(edge.sum() > 0, f"{name}: no edge node in the map")
    check(gap.min() >= least, f"{name}: check 5b: a support foot at {support[gap.argmin()]} "
          f"stands {gap.min():.6f} m from a no-foothold node, least allowed {least:.6f} m "
          f"(margin {margin})")
    # (c) Transfers clear the surface under them.
    moving = transfers(feet, phase, EXACT)
    k, leg = np.array(moving).reshape(-1, 2).T
    p = feet[k, leg]
    lift = p[:, 2] - bilinear(mx, my, mz, p[:, 0], p[:, 1])
    check(len(moving) > 50, f"{name}: {len(moving)} transfer foot-samples")
    if len(moving):
        check(lift.min() >= clearance - TOL, f"{name}: check 5c: a transfer foot at "
              f"{p[lift.argmin()]} stands {lift.min():.6f} m above the map, swing_clearance "
              f"{clearance}")
    return (f"{name}: {feet.shape[0]} samples, {contact.sum()} contact foot-samples (largest "
            f"height error {off.max():.3g} m), {len(support)} support footholds, "
            f"{edge.sum()} edge and {(steep & ~edge).sum()} steep-only nodes, least distance "
            f"{gap.min():.6f} m (least allowed {least:.6f} m), {len(moving)} transfer "
            f"foot-samples, least lift {lift.min() if len(moving) else np.nan:.6f} m "
            f"(swing_clearance {clearance})")


def control(name, r, must):
    """The checks on a doctored run must fail, among others, with a check in `must`."""
    global quiet
    before, quiet = len(failures), True
    check_rough(name, r)
    caught = failures[before:]
    del failures[before:]
    quiet = False
    hit = sorted({c for c in must if any(f"check {c}:" in m for m in caught)})
    print(f"{name}: {len(caught)} failures, checks {hit} among them, as they must")
    check(hit == sorted(must), f"{name}: checks {sorted(must)} expected to fail, {hit} did: "
          f"{caught}")


def rough(d):
    """Check 5 and its negative controls."""
    npy = os.path.join(d, "rough.npy")
    p = subprocess.run([sys.executable, os.path.join(SRC, "analysis/make_rough_map.py"), npy],
                       capture_output=True, text=True)
    check(p.returncode == 0, f"check 5: make_rough_map.py exited {p.returncode}: {p.stderr}")
    if p.returncode != 0:
        return
    print("check 5:", p.stdout.strip().replace(npy, "rough.npy"))
    scene = os.path.join(SRC, "configs/terrain/rough_map.yaml")
    kept = None
    for label, sets in ROUGH_RUNS:
        r = run(f"check 5: {label}", scene, os.path.join(d, "r.h5"),
                [f"terrain.height_map.file={npy}"] + sets)
        if r is not None:
            hm = r["config"]["terrain"]["height_map"]
            check_stored(label, r, np.load(npy), hm["origin"], hm["resolution"])
            print(check_rough(f"check 5: {label}", r))
            kept = kept or r
    if kept is None:
        return
    r = kept
    hm = r["config"]["terrain"]["height_map"]
    mx, my, mz = r["map_x"], r["map_y"], r["map_z"]
    # A contact foot raised by 1 um.
    feet = r["feet"].copy()
    k, leg = np.argwhere(r["phase"] != 0)[len(feet) // 2]
    feet[k, leg, 2] += 1e-6
    control("control: contact foot raised 1 um", dict(r, feet=feet), ["5a"])
    # A support foot moved onto the slab edge node nearest it, on the map.
    feet = r["feet"].copy()
    k, leg = np.argwhere(r["phase"] == SUPPORT)[len(feet) // 2]
    edge, _ = no_foothold(mz, hm["resolution"], hm["edge_height"], hm["max_slope"])
    ii, jj = np.nonzero(edge)
    e = np.hypot(mx[jj] - feet[k, leg, 0], my[ii] - feet[k, leg, 1]).argmin()
    x, y = mx[jj[e]], my[ii[e]]
    feet[k, leg] = x, y, bilinear(mx, my, mz, x, y)
    control("control: support foot on a slab edge", dict(r, feet=feet), ["5b"])
    # A transfer sample lowered to half the clearance above the map.
    feet = r["feet"].copy()
    k, leg = transfers(feet, r["phase"], EXACT)[10]
    x, y = feet[k, leg, :2]
    feet[k, leg, 2] = bilinear(mx, my, mz, x, y) + r["config"]["gait"]["swing_clearance"] / 2
    control("control: transfer foot at half the clearance", dict(r, feet=feet), ["5c"])


with tempfile.TemporaryDirectory() as tmp:
    stairs_grid_1mm, stairs_origin, stairs_res, stairs_run = check_stairs(tmp)
    check_stored("1 mm stairs map", stairs_run, stairs_grid_1mm, stairs_origin, stairs_res)
    check_formats(tmp)
    bad_input(tmp)
    rough(tmp)

if failures:
    print(f"{len(failures)} failures:")
    for f in failures:
        print("  " + f)
sys.exit(1 if failures else 0)
