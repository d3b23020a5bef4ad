"""Sphere feet clear the stairs (docs/theory/stages.md#gait-planning): on the pexod stairs scene
and on the paper scene with robot.foot_radius 0.03, the distance of every stored sphere centre
/feet/center to the stored terrain polyline /terrain/y, /terrain/z, computed here with numpy as
point-segment distances, is
  - at least r on every sample (no overlap),
  - r where the foot is in contact (/contacts/phase impact or support: the sphere touches),
  - at least r + min(swing_clearance, foothold_margin) during a swing's transfer,
the sphere's lowest point stands swing_clearance above the highest terrain under its shadow
during the transfer, and a support sphere's horizontal extent [y - r, y + r] keeps
foothold_margin from the riser ahead and the nosing behind. The radius comes from the URDF
(pexod) or from the --set (paper), the margins from the scene files. The checks fail on the
paper's point-foot plan given a sphere (the plan before sphere footholds), and a margin no tread
admits exits with status 3 in one line naming the leg, the step and the margin, writing nothing.
    test_sphere_footholds.py HEXDYN_BINARY SOURCE_DIR      (PYTHONPATH: the build tree's python/)
"""

import os
import sys
import tempfile
import xml.etree.ElementTree as ET

import h5py
import numpy as np
import yaml
from common import args, cli_run, segment_distance, swing_runs

HEXDYN, SRC = args()
TOL = 1e-9
failures = []
quiet = False  # the negative control's findings are expected: collected, not printed


def check(cond, what):
    if not cond:
        failures.append(what)
        if not quiet:
            print("FAIL:", what)


def scene_gait(path):
    with open(path) as f:
        gait = yaml.safe_load(f)["gait"]
    return gait["foothold_margin"], gait["swing_clearance"]


def urdf_sphere_radius(path):
    """The one radius of the URDF's sphere <collision>s (pexod: the six feet)."""
    radii = {float(s.get("radius")) for s in ET.parse(path).iter("sphere")}
    assert len(radii) == 1, radii
    return radii.pop()


def highest_under(ty, tz, lo, hi):
    """Highest terrain of the polyline over y in [lo, hi]."""
    inside = tz[(ty >= lo) & (ty <= hi)]
    ends = np.interp([lo, hi], ty, tz)  # a riser at lo or hi: np.interp takes one side
    return max(inside.max() if inside.size else -np.inf, ends.max())


def risers(ty, tz):
    """y of every riser: two vertices of equal y, the upper one second."""
    same = (np.diff(ty) == 0.0) & (np.diff(tz) > 0.0)
    return ty[:-1][same]



def check_clear(name, ty, tz, centre, phase, r, margin, clearance):
    """The checks of the file comment on one run; returns the worst overlap [m] (>0: overlap)
    and the number of samples that overlap by more than TOL."""
    T, legs, _ = centre.shape
    dist = segment_distance(centre[..., 1], centre[..., 2], ty, tz)
    overlap = r - dist
    bad = int((overlap > TOL).sum())
    check(bad == 0, f"{name}: {bad} leg-samples overlap the terrain, by up to "
          f"{overlap.max() * 1e3:.3f} mm")
    contact = phase != 0
    err = np.abs(dist - r)[contact]
    check(contact.sum() > 100 and err.max() <= TOL,
          f"{name}: a contact sphere is {err.max():.3g} m off touching ({contact.sum()} samples)")
    # Support footholds: the sphere's horizontal extent keeps the margin from risers and nosings.
    ry = risers(ty, tz)
    check(ry.size >= 3, f"{name}: {ry.size} risers in the terrain")
    cy = centre[..., 1][contact]
    behind = np.array([ry[ry <= y].max() if (ry <= y).any() else -np.inf for y in cy])
    ahead = np.array([ry[ry > y].min() if (ry > y).any() else np.inf for y in cy])
    horiz = np.minimum((cy - r) - behind, ahead - (cy + r))
    check(horiz.min() >= margin - TOL,
          f"{name}: a support sphere stands {horiz.min():.6f} m from a riser or nosing, "
          f"margin {margin}")
    near = int((horiz < margin + 1e-6).sum())
    # Swing transfers: the sphere clears the nosings by the swing clearance.
    transfers, worst_dist, worst_lift = 0, np.inf, np.inf
    for leg in range(legs):
        for i, j in swing_runs(phase[:, leg]):
            lo, hi = centre[i - 1, leg, :2], centre[j + 1, leg, :2]
            for k in range(i, j + 1):
                c = centre[k, leg]
                if min(np.abs(c[:2] - lo).max(), np.abs(c[:2] - hi).max()) <= 1e-12:
                    continue  # lifting or lowering over a foothold
                transfers += 1
                worst_dist = min(worst_dist, dist[k, leg] - r)
                worst_lift = min(worst_lift, c[2] - r - highest_under(ty, tz, c[1] - r, c[1] + r))
    check(transfers > 50, f"{name}: {transfers} transfer samples")
    check(worst_dist >= min(clearance, margin) - TOL,
          f"{name}: in a transfer a sphere is {worst_dist:.6f} m from the terrain, expected "
          f"at least min(swing_clearance, margin) = {min(clearance, margin)}")
    check(worst_lift >= clearance - TOL,
          f"{name}: in a transfer a sphere's lowest point is {worst_lift:.6f} m above the "
          f"terrain under it, expected at least {clearance}")
    print(f"{name}: {T} samples, {contact.sum()} contact leg-samples ({near} at the margin), "
          f"{transfers} transfer leg-samples; least distance - r {dist.min() - r:.3g} m, "
          f"support |distance - r| <= {err.max():.2g} m, horizontal clearance "
          f"{horiz.min():.6f} m, transfer clearance {worst_dist:.6f} m (lowest point "
          f"{worst_lift:.6f} m above)")
    return overlap.max(), bad


def read(path):
    with h5py.File(path, "r") as f:
        return (f["/terrain/y"][()], f["/terrain/z"][()], f["/feet/position"][()],
                f["/feet/center"][()] if "/feet/center" in f else None, f["/contacts/phase"][()])


with tempfile.TemporaryDirectory() as d:
    pexod = os.path.join(SRC, "configs/robots/pexod_stairs.yaml")
    paper = os.path.join(SRC, "configs/paper.yaml")
    r_pexod = urdf_sphere_radius(os.path.join(SRC, "robots/pexod.urdf"))
    r_paper = 0.03
    runs = [("pexod stairs", pexod, [], r_pexod),
            ("paper, foot_radius 0.03", paper, [f"robot.foot_radius={r_paper}"], r_paper)]
    for name, scene, sets, r in runs:
        out = os.path.join(d, "r.h5")
        rc, err = cli_run(HEXDYN, scene, out, sets)
        check(rc == 0, f"{name}: hexdyn run exited {rc}: {err}")
        if rc != 0:
            continue
        ty, tz, _, centre, phase = read(out)
        margin, clearance = scene_gait(scene)
        check_clear(name, ty, tz, centre, phase, r, margin, clearance)
        os.remove(out)

    # Negative control: the paper's point-foot plan, a sphere of 0.03 m put on it (centre =
    # contact point + r z, as the plan stood before sphere footholds), fails the checks.
    out = os.path.join(d, "point.h5")
    rc, err = cli_run(HEXDYN, paper, out)
    check(rc == 0, f"paper: hexdyn run exited {rc}: {err}")
    if rc == 0:
        ty, tz, position, _, phase = read(out)
        before, quiet = list(failures), True
        worst, bad = check_clear("control", ty, tz, position + np.array([0.0, 0.0, r_paper]),
                                 phase, r_paper, *scene_gait(paper))
        caught = failures[len(before):]
        del failures[len(before):]
        quiet = False
        print(f"control: {len(caught)} checks fail as they must; {bad} leg-samples overlap, "
              f"by up to {worst * 1e3:.2f} mm")
        check(bad > 0 and worst > 1e-3 and len(caught) >= 2,
              "control: the point-foot plan with a sphere passes the checks")
        os.remove(out)

    # A margin no tread admits: one line, status 3, naming leg, step and margin; nothing written.
    for sets, words in [(["robot.foot_radius=0.03", "gait.foothold_margin=0.11"],
                         ["gait.foothold_margin 0.11 m", "radius 0.03 m", "0.28 m"]),
                        (["gait.foothold_margin=0.13"],
                         ["gait.foothold_margin 0.13 m", "twice the margin"])]:
        rc, stderr = cli_run(HEXDYN, paper, os.path.join(d, "none.h5"), sets)
        lines = stderr.splitlines()
        msg = lines[0].removeprefix("hexdyn: error: ") if lines else ""
        print(f"{' '.join(sets)}: exit {rc}: {stderr.strip()}")
        check(rc == 3, f"{sets}: exit status {rc}, expected 3")
        check(len(lines) == 1 and lines[0].startswith("hexdyn: error: "),
              f"{sets}: {len(lines)} lines on stderr")
        check(msg.startswith("leg L") and " step " in msg and all(w in msg for w in words),
              f"{sets}: message does not name the leg, the step and the margin: {msg}")
        check(os.listdir(d) == [], f"{sets}: files left: {os.listdir(d)}")

sys.exit(1 if failures else 0)
