#!/usr/bin/python3
"""What a robot's run needs and climbs, from its hexdyn-result file alone.

    /usr/bin/python3 analysis/robot_summary.py RESULT.h5

Prints one block (docs/validation/robots.md, pipelines/robots.sh): the robot's mass and
effort limits (from /model/urdf, the robot as simulated), the stairs, the trunk posture the
run used (P0 at t = 0 and its height above the tread-centre line; the foothold spread the
automatic posture chose is not in the file), travel
and duration, peak |tau| per joint kind outside the touchdown transients (samples where no
leg is in its impact phase) and inside them, with the fraction of the smallest effort limit,
the solver status counts, energy and cost of transport.
"""

import argparse
import sys
import xml.etree.ElementTree as ET

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from hexdyn import results as hr
import numpy as np


def main(argv=None):
    ap = argparse.ArgumentParser(prog="robot_summary.py", description=__doc__.splitlines()[0])
    ap.add_argument("result", help="a hexdyn-result file with dynamics")
    args = ap.parse_args(argv)
    try:
        res = hr.open_result(args.result)
    except (OSError, ValueError) as e:
        print(f"robot_summary: {e}", file=sys.stderr)
        return 2
    cfg = res.config
    urdf = ET.fromstring(hr.decode_text(res["/model/urdf"]))
    efforts = [float(lim.get("effort")) for j in urdf.iter("joint")
               if j.get("type") == "revolute" and (lim := j.find("limit")) is not None
               and lim.get("effort") is not None]
    mass = float(res["/model/total_mass"])
    t = res["/time"]
    tau = np.abs(res["/joints/torque"])                    # (T, J)
    phase = res["/contacts/phase"]                         # (T, L): 0 swing, 1 impact, 2 support
    # The joints of each row, hip to foot (row j: the j-th joint of every leg that has one),
    # named by position (coxa/femur/tibia for legs of three joints: hr.joint_roles).
    legs = hr.leg_joints(res)
    rows = [[joints[j] for joints in legs if len(joints) > j]
            for j in range(max(len(joints) for joints in legs))]
    roles = "/".join(hr.joint_roles(len(rows)))
    status = res["/solver/status"]
    transient = (phase == 1).any(axis=1)
    terrain = cfg["terrain"]
    p0 = res["/base/position"][0]
    stairs = terrain.get("type") == "stairs"
    # The terrain's reference line under the trunk: the tread-centre line of stairs, the
    # ground of flat terrain (a slope's surface for a slope).
    if stairs:
        line = terrain.get("ground_height", 0.0) + terrain["riser_height"] * (
            (p0[1] - terrain.get("first_riser_y", 0.0)) / terrain["tread_depth"] + 0.5)
        where = "the tread-centre line"
    elif terrain.get("type") == "slope":
        line = terrain.get("height", terrain.get("ground_height", 0.0)) + np.tan(
            terrain["angle"]) * (p0[1] - terrain.get("origin_y", 0.0))  # angle [rad]
        where = "the slope"
    else:
        line = terrain.get("height", 0.0)
        where = "the ground"
    travel = float(np.linalg.norm(res["/base/position"][-1] - p0))
    limit = min(efforts) if efforts else float("nan")

    def peaks(mask):
        if not mask.any():
            return [float("nan")] * len(rows)
        return [float(tau[mask][:, row].max()) for row in rows]

    calm, hard = peaks(~transient), peaks(transient)
    print(f"robot: {cfg.get('name', args.result)}  ({args.result})")
    print(f"  mass {mass:.3f} kg; effort limits {min(efforts):g}–{max(efforts):g} N m" if efforts
          else f"  mass {mass:.3f} kg; no effort limits in the description")
    if stairs:
        print(f"  stairs: riser {terrain['riser_height']:g} m, tread {terrain['tread_depth']:g} m")
    else:
        print(f"  terrain: {terrain.get('type', 'flat')}")
    print(f"  trunk origin at t = 0: ({p0[0]:.4f}, {p0[1]:.4f}, {p0[2]:.4f}) m, "
          f"{p0[2] - line:+.4f} m above {where}")
    print(f"  travel {travel:.3f} m in {t[-1] - t[0]:.2f} s; gait duty factor {cfg['gait']['duty_factor']:g}, "
          f"stroke {cfg['gait']['stroke']:g} m")
    print(f"  peak |tau| {roles} outside touchdown transients: "
          + " / ".join(f"{v:.3f}" for v in calm) + f" N m ({max(calm) / limit:.0%} of the limit)")
    print(f"  peak |tau| {roles} inside touchdown transients:  "
          + " / ".join(f"{v:.3f}" for v in hard) + f" N m ({max(hard) / limit:.0%} of the limit)")
    relaxed_calm = int(((status == 1) & ~transient).sum())
    print(f"  samples {len(t)}: optimal {int((status == 0).sum())}, relaxed {int((status == 1).sum())} "
          f"({relaxed_calm} outside touchdown transients), failed {int((status == 2).sum())}")
    print(f"  energy {float(res['/energy/total']):.3f} J, cost of transport "
          f"{float(res['/energy/cost_of_transport']):.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
