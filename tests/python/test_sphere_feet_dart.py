"""Sphere feet against DART 6.12 (docs/validation/dynamics.md#sphere-feet-against-dart).

pexod (robots/pexod.urdf) stands on spheres of radius 0.025 m, which hexdyn takes from the
tibias' sphere <collision>s (configs/robots/pexod_stairs.yaml). A sphere foot touches at its
contact point, r below its centre along the surface normal n; the terrain's force acts there
(docs/theory/model.md#sphere-feet). What the file must hold:
  /feet/position   (T, L, 3) [m], the contact points;
  /feet/center     (T, L, 3) [m], the spheres' centres;
  /model/urdf      the robot with each L{i}_foot link at a centre, holding a sphere
                   <collision> of the foot's radius.

DART (Debian's python3-dartpy) is given /model/urdf on a free trunk, the sample's state,
/joints/torque as joint forces and each foot force /contacts/force at the world point
/feet/position on its L{i}_foot body. Checked:
  1. the contact point is on the sphere, at its lowest point: DART's placement of each
     L{i}_foot (the centre) is /feet/center to 1e-9 m, and centre - contact = r z on the
     treads in support (|centre - contact| = r always), r from /model/urdf;
  2. on every optimal sample DART's accelerations are hexdyn's prescribed ones to TOLERANCE
     (relative, as tests/python/test_drive_dart.py);
  3. the same forces at the spheres' centres move DART otherwise, by more than 100 TOLERANCE
     on some sample: the moment arm of the contact point counts, the check can fail.

    /usr/bin/python3 tests/python/test_sphere_feet_dart.py HEXDYN SOURCE_DIR
"""
import os
import sys
import tempfile
import xml.etree.ElementTree as ET

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import args, cli_run  # noqa: E402
from test_drive_dart import (TOLERANCE, DartRobot, dart, difference,  # noqa: E402
                             hexdyn_accelerations, read_result)

POSITION_TOLERANCE = 1e-9  # m, DART's FK of a foot centre against /feet/center
SCENE = os.path.join("configs", "robots", "pexod_stairs.yaml")


class ForcesAt(DartRobot):
    """The robot in DART with each foot force acting at a given world point."""

    def __init__(self, r, points):
        super().__init__(r)
        self.points = points  # (T, L, 3) world points of the foot forces

    def set_state(self, skel, r, t, joint_forces):
        super().set_state(skel, r, t, joint_forces)
        skel.clearExternalForces()
        for leg, foot in enumerate(self.feet):
            skel.getBodyNode(foot).setExtForce(r["/contacts/force"][t][leg], self.points[t][leg],
                                               False, False)  # force and point in world axes

    def centers(self):
        """DART's placement of each foot link's origin, the sphere's centre [m]."""
        return np.array([self.skel.getBodyNode(f).getWorldTransform().translation()
                         for f in self.feet])


def foot_radii(urdf):
    """Radius of the sphere <collision> of each L{i}_foot link of /model/urdf."""
    links = {link.get("name"): link for link in ET.fromstring(urdf).iter("link")}
    return np.array([float(links[f"L{i}_foot"].find("collision/geometry/sphere").get("radius"))
                     for i in range(1, 7)])


def main():
    hexdyn, src = args()
    if dart is None:
        print("skipped: python3-dartpy is not installed (pipelines/setup.sh installs it)")
        return 77
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "pexod.h5")
        rc, err = cli_run(hexdyn, os.path.join(src, SCENE), out)
        assert rc == 0, err
        r = read_result(out)
        with h5py.File(out, "r") as f:
            contact, center = f["/feet/position"][()], f["/feet/center"][()]
    radius = foot_radii(r["urdf"])
    assert (radius == 0.025).all(), f"foot radii {radius}, pexod's are 0.025 m"
    gap = np.linalg.norm(center - contact, axis=2)
    assert np.abs(gap - radius).max() <= POSITION_TOLERANCE, "a contact point is off its sphere"
    support = r["/contacts/phase"] != 0
    lowest = center - contact - radius[None, :, None] * np.array([0.0, 0.0, 1.0])
    assert np.abs(lowest[support]).max() <= POSITION_TOLERANCE, "not the sphere's lowest point"

    optimal = np.flatnonzero(r["/solver/status"] == 0)
    assert optimal.size > 100, f"only {optimal.size} optimal samples"
    at_contact, at_center = ForcesAt(r, contact), ForcesAt(r, center)
    worst = moved = 0.0
    for t in optimal:
        a = hexdyn_accelerations(r, t)
        worst = max(worst, difference(at_contact.rigid(r, t, r["/joints/torque"][t]), a))
        placed = np.abs(at_contact.centers() - center[t]).max()
        assert placed <= POSITION_TOLERANCE, f"sample {t}: DART's foot centres differ by {placed}"
        moved = max(moved, difference(at_center.rigid(r, t, r["/joints/torque"][t]), a))
    print(f"{r['file']}: sphere feet (r = {radius[0]} m): {optimal.size} optimal samples, forces "
          f"at the contact points: largest relative difference {worst:.2g} (tolerance "
          f"{TOLERANCE:g}); at the centres instead: {moved:.2g}")
    assert worst <= TOLERANCE, f"DART and hexdyn differ by {worst:.3g} relative"
    assert moved > 100 * TOLERANCE, f"forces at the centres still agree ({moved:.3g})"
    return 0


if __name__ == "__main__":
    sys.exit(main())
