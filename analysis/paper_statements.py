#!/usr/bin/python3
"""Checks the paper's qualitative statements (§5) on a hexdyn-result file.

usage: /usr/bin/python3 analysis/paper_statements.py RESULT.h5 [--markdown]

Statements, each computed from the datasets of the file:
  S1  the normal foot forces sum to the weight (65.7 N) except at impacts: on every
      sample outside the impact transients the sum of F_iz stays within the band
      m (g + a_com,z) of the whole-robot COM acceleration, and within 3 % of m g;
  S2  an impulsive spike at each touchdown: every touchdown has one impact whose peak
      exceeds the quasi-static share of the weight, m g / (number of feet then in support);
  S3  joint 2 (femur) carries the largest torque and joint 1 (coxa) the smallest: compared
      by the peak and the RMS of |tau| over support samples solved without relaxation;
  S4  the highest peak of the power arises when the swing and support legs change stance:
      the largest P_in of the run lies within 0.1 s of a lift-off or touchdown.
Prints one line per statement (or a Markdown table) and a closing
"paper_statements: N passed, M failed" line; exit status 1 when any fails.
"""
import argparse
import sys

import hexdyn_path  # first: the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from hexdyn.results import leg_joints, open_result
import numpy as np

# The joints of a paper leg, hip to foot, as statement S3 ranks them.
PAPER_JOINTS = ("coxa", "femur", "tibia")

G = 9.81


def impact_mask(t, starts, durations):
    m = np.zeros(t.shape, bool)
    for t0, d in zip(starts, durations):
        m |= (t >= t0) & (t <= t0 + d)
    return m


def com_acceleration_z(t, com_z):
    """Second derivative of the COM height on the (non-uniform) grid."""
    v = np.gradient(com_z, t)
    return np.gradient(v, t)


def statements(res):
    t = res["/time"]
    F = res["/contacts/force"]
    phase = res["/contacts/phase"]
    status = res["/solver/status"]
    mass = float(res["/model/total_mass"])
    weight = mass * G
    starts, durations = res["/impacts/t_start"], res["/impacts/duration"]
    in_impact = impact_mask(t, starts, durations)
    out = []

    # S1: balance outside impacts.
    Fz = F[:, :, 2].sum(axis=1)
    quiet = ~in_impact
    dev = np.abs(Fz[quiet] - weight) / weight
    ok1 = bool(dev.max() < 0.03)
    out.append(("S1", "normal forces sum to the weight except at impacts", ok1,
                f"outside impacts sum F_iz in [{Fz[quiet].min():.2f}, {Fz[quiet].max():.2f}] N, "
                f"weight {weight:.2f} N, largest deviation {100 * dev.max():.2f} %; during impacts up to "
                f"{Fz[in_impact].max() if in_impact.any() else float('nan'):.1f} N"))

    # S2: one spike per touchdown, above the quasi-static share.
    touchdowns = []
    for leg in range(phase.shape[1]):  # every leg (/model/leg_names)
        swing = phase[:, leg] == 0
        for i in np.flatnonzero(swing[:-1] & ~swing[1:]):
            touchdowns.append((leg + 1, t[i + 1]))
    legs = res["/impacts/leg"].astype(int) + 1  # 0-based in the file (leg dimension)
    peaks = res["/impacts/peak_force"]
    fails = []
    worst_ratio = np.inf
    for leg, ttd in touchdowns:
        k = np.flatnonzero((legs == leg) & (np.abs(starts - ttd) < 1e-6))
        if k.size != 1:
            fails.append(f"L{leg} at {ttd:.3f} s: {k.size} impacts")
            continue
        i = np.searchsorted(t, ttd + durations[k[0]] + 1e-9)
        feet = int((phase[min(i, len(t) - 1)] != 0).sum())
        share = weight / max(feet, 1)
        worst_ratio = min(worst_ratio, peaks[k[0]] / share)
        if peaks[k[0]] <= share:
            fails.append(f"L{leg} at {ttd:.3f} s: peak {peaks[k[0]]:.1f} <= share {share:.1f} N")
    ok2 = not fails and len(touchdowns) > 0
    out.append(("S2", "an impulsive spike at each touchdown", ok2,
                f"{len(touchdowns)} touchdowns, {len(starts)} impacts, peaks {peaks.min():.1f}-{peaks.max():.1f} N, "
                f"smallest peak / quasi-static share = {worst_ratio:.2f}" + ("; " + "; ".join(fails) if fails else "")))

    # S3: joint ranking over support samples solved without relaxation.
    # tau[j]: (T, L) the torques of joint j of every leg (/model/joint_names, leg by leg)
    tau = [res["/joints/torque"][:, [joints[j] for joints in leg_joints(res)]]
           for j in range(len(PAPER_JOINTS))]
    support = (phase == 2) & (status == 0)[:, None]
    peak = np.array([np.abs(tau[j][support]).max() for j in range(len(PAPER_JOINTS))])
    rms = np.array([np.sqrt(np.mean(tau[j][support] ** 2)) for j in range(len(PAPER_JOINTS))])
    ok3 = bool(np.argmax(peak) == 1 and np.argmin(peak) == 0 and np.argmax(rms) == 1 and np.argmin(rms) == 0)
    out.append(("S3", "joint 2 carries the largest torque, joint 1 the smallest", ok3,
                "support samples: peak abs(τ) coxa/femur/tibia = " + "/".join(f"{x:.2f}" for x in peak) +
                " N m, RMS = " + "/".join(f"{x:.2f}" for x in rms) + " N m"))

    # S4: the highest power peak at a stance change.
    P = res["/power/total"]
    changes = np.unique(np.round(np.concatenate(
        [t[np.flatnonzero(np.diff((phase[:, leg] == 0).astype(int)) != 0) + 1]
         for leg in range(phase.shape[1])]), 9))
    i = int(np.argmax(P))
    dist = float(np.min(np.abs(changes - t[i]))) if changes.size else np.inf
    # Information: how many of the intervals between stance changes peak next to one.
    bounds = np.concatenate(([t[0]], changes[(changes > t[0]) & (changes < t[-1])], [t[-1]]))
    near = total = 0
    for a, b in zip(bounds[:-1], bounds[1:]):
        sel = (t >= a) & (t <= b)
        if sel.sum() < 3:
            continue
        j = np.flatnonzero(sel)[np.argmax(P[sel])]
        total += 1
        near += int(np.min(np.abs(changes - t[j])) <= 0.1)
    ok4 = bool(dist <= 0.1)
    out.append(("S4", "the highest power peak arises when the stance changes", ok4,
                f"max P_in {P[i]:.2f} W at t = {t[i]:.4f} s, {dist:.4f} s from a stance change; "
                f"{near} of {total} intervals between stance changes peak within 0.1 s of one"))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(prog="paper_statements.py", description=__doc__.splitlines()[0])
    ap.add_argument("result", help="a hexdyn-result file with dynamics")
    ap.add_argument("--markdown", action="store_true", help="print a Markdown table")
    args = ap.parse_args(argv)
    try:
        res = open_result(args.result)
    except (OSError, ValueError) as e:
        print(f"paper_statements: {e}", file=sys.stderr)
        return 2
    rows = statements(res)
    if args.markdown:
        print("| | paper's statement | holds | our figures |")
        print("|---|---|---|---|")
        for key, text, ok, detail in rows:
            print(f"| {key} | {text} | {'yes' if ok else 'no'} | {detail} |")
    else:
        for key, text, ok, detail in rows:
            print(f"{key} {'PASS' if ok else 'FAIL'}: {text}: {detail}")
    failed = sum(not r[2] for r in rows)
    print(f"paper_statements: {len(rows) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
