"""The balanced trunk against an independent feasibility LP (docs/theory/balance.md#tests).

For each scene given, hexdyn runs it; on every sample outside touchdowns (no leg in its impact
transient), DART (python3-dartpy) gives the trunk wrench the robot's motion needs, and its
response to a unit force on each support foot (the free-floating robot of the result's own
/model/urdf, the stored state: tests/python/test_robots_dart.py). scipy's HiGHS then looks for
foot forces on the support feet that meet the trunk's six equations inside the friction model
of the scene (allocation.friction: pyramid4 or pyramid8, inscribed in the cone of
contact.friction_coefficient, on horizontal ground: the contact frame's tangents are world x
and y), each equation met to the planner's precision: the balanced trunk puts the ZMP within
1e-9 m of a two-foot support's line (motion.balance tolerance, docs/theory/balance.md), a
moment of 1e-9 m times the weight, and the equations are met within SLACK times that (HiGHS's
own feasibility tolerance, 1e-7 in the wrench's units, is below it for a robot heavier than
10 kg). A balanced scene must have no sample without such forces; its straight twin (the same
scene with motion.trunk: straight) must have some, so that the check can fail.

    /usr/bin/python3 tests/python/test_balance_lp.py HEXDYN SOURCE_DIR SCENE [SCENE ...]

A SCENE may carry overrides after an @, as --set takes them: SCENE@key=value,key=value.
"""
import argparse
import math
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import cli_run  # noqa: E402

try:
    from scipy.optimize import linprog
    from test_drive_dart import DartRobot, read_result
    from test_robots_dart import dart_inverse_dynamics
except ImportError as e:  # dartpy or scipy missing
    print(f"skipped: {e} (pipelines/setup.sh installs python3-dartpy and python3-scipy)")
    sys.exit(77)

SUPPORT, IMPACT = 2, 1
LINE_TOLERANCE_M = 1e-9  # the balanced trunk's ZMP tolerance on a line support
SLACK = 2.0              # the equations' slack, in units of LINE_TOLERANCE_M × weight


def friction_rows(mu, faces):
    """Rows G (faces × 3) with G f ≤ 0 for one foot: the inscribed N-gon of the cone."""
    reach = mu * math.cos(math.pi / faces)
    return np.array([[math.cos(2 * math.pi * k / faces), math.sin(2 * math.pi * k / faces),
                      -reach] for k in range(faces)])


def feasible(robot, r, t, legs, mu, faces):
    """Whether foot forces on `legs` within the friction model cancel the trunk wrench."""
    zero = np.zeros((len(r["legs"]), 3))
    w0, _ = dart_inverse_dynamics(robot, r, t, zero)
    columns = []
    for leg in legs:
        for axis in range(3):
            f = zero.copy()
            f[leg, axis] = 1.0
            w, _ = dart_inverse_dynamics(robot, r, t, f)
            columns.append(w - w0)
    B = np.array(columns).T
    G = friction_rows(mu, faces)
    A_ub = np.zeros((len(legs) * faces, 3 * len(legs)))
    for i in range(len(legs)):
        A_ub[i * faces:(i + 1) * faces, 3 * i:3 * i + 3] = G
    # |B f + w0| ≤ slack on every row of the trunk's wrench.
    slack = SLACK * LINE_TOLERANCE_M * np.linalg.norm(w0[3:6])  # w0: [moment; force]
    A_ub = np.vstack([A_ub, B, -B])
    b_ub = np.concatenate([np.zeros(len(legs) * faces), slack - w0, slack + w0])
    res = linprog(np.zeros(3 * len(legs)), A_ub=A_ub, b_ub=b_ub,
                  bounds=[(None, None)] * (3 * len(legs)), method="highs")
    return res.status == 0


def infeasible_samples(hexdyn, scene, d, sets=()):
    out = os.path.join(d, os.path.basename(scene).replace(".yaml", f"{abs(hash(sets))}.h5"))
    rc, err = cli_run(hexdyn, scene, out, sets)
    assert rc == 0, f"{scene}: {err}"
    r = read_result(out)
    robot = DartRobot(r)
    contact = r["config"]["contact"]
    mu = float(contact["friction_coefficient"])
    faces = {"pyramid4": 4, "pyramid8": 8}[r["config"]["allocation"]["friction"]]
    phase = r["/contacts/phase"]
    bad, checked = [], 0
    for t in range(len(phase)):
        if np.any(phase[t] == IMPACT):
            continue
        legs = [leg for leg in range(len(r["legs"])) if phase[t][leg] == SUPPORT]
        checked += 1
        if not feasible(robot, r, t, legs, mu, faces):
            bad.append(float(r["/time"][t]))
    return bad, checked


def main():
    p = argparse.ArgumentParser()
    p.add_argument("hexdyn")
    p.add_argument("source_dir")
    p.add_argument("scenes", nargs="+")
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as d:
        for scene in a.scenes:
            name, _, given = scene.partition("@")
            path = os.path.join(a.source_dir, name)
            sets = tuple(x for x in given.split(",") if x)
            bad, checked = infeasible_samples(a.hexdyn, path, d, sets)
            print(f"{scene}: balanced, {checked} samples outside touchdowns, "
                  f"{len(bad)} without feasible forces {bad[:5]}")
            assert not bad, f"{scene}: no feasible forces at t = {bad[:10]} s"
            straight, checked = infeasible_samples(a.hexdyn, path, d,
                                                   sets + ("motion.trunk=straight",))
            print(f"{scene}: straight, {checked} samples outside touchdowns, "
                  f"{len(straight)} without feasible forces")
            assert straight, f"{scene}: the straight trunk is feasible everywhere too; " \
                             "the check cannot tell"
    print("test_balance_lp: ok")


if __name__ == "__main__":
    main()
