#!/usr/bin/python3
"""The lines that end `hexdyn run` (docs/user/output.md#the-runs-verdict) against the result
file they describe, recomputed here with numpy from its datasets as h5py reads them:

- the verdict: samples (/time), relaxed samples outside and inside touchdown transients
  (/solver/status 1, /contacts/phase 1), failed samples, the largest finite required friction
  over the samples outside touchdowns with its leg (L1 ... L6) and time, the samples without
  one (NaN), and the samples with a /contacts/slip flag;
- the summary of repeated relaxed episodes: how many episodes (runs of consecutive relaxed
  samples, split where the touchdown flag changes), how many samples, the first and last
  time; a kind that occurs once is one line with its span;
- no line of the log runs to hundreds of characters;
- every integer leg or joint column of every file kind says in its long_name that it is
  0-based (hexdyn.results.SCHEMA, which the writers label every dataset from), and the
  result file's say so as h5py reads them.

On the paper scene, on two low friction coefficients (relaxed samples and slips outside
touchdowns) and without the required friction.

    test_verdict.py HEXDYN_BINARY SOURCE_DIR
"""
import math
import os
import re
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import args, cli_run  # noqa: E402

NUMBER = r"([-+0-9.eE]+)"
VERDICT = re.compile(
    r"^hexdyn: verdict: (\d+) samples, (\d+) relaxed outside touchdowns \((\d+) in them\)"
    r"(?:, (\d+) failed)?"
    r"(?:, (?P<off>required friction not computed)"
    r"|, (?P<none>no required friction outside touchdowns)"
    r"|, largest required friction " + NUMBER + r" \((L\d) at t = " + NUMBER +
    r" s\) outside touchdowns)"
    r"(?:, no friction coefficient admits (\d+) samples)?"
    r"(?: \(output\.required_friction is false\))?"
    r", (\d+) slip samples$")
SUMMARY = re.compile(
    r"^hexdyn: (\d+) episodes of relaxed samples (in touchdown transients|outside touchdowns), "
    r"(\d+) samples from t = " + NUMBER + " to " + NUMBER + " s; worst at t = " + NUMBER + " s: ")
SINGLE = re.compile(r"^hexdyn: t = \[" + NUMBER + ", " + NUMBER + r"\] s: (\d+) sample\(s\) relaxed: ")

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def close(a, b, rel=1e-5):
    return math.isclose(a, b, rel_tol=rel, abs_tol=rel)


def expected(path):
    """What the verdict and the episode lines must say, from the file alone."""
    with h5py.File(path, "r") as f:
        t = f["/time"][()]
        status = f["/solver/status"][()]
        touchdown = (f["/contacts/phase"][()] == 1).any(axis=1)
        slip = f["/contacts/slip"][()].any(axis=1)
        rf = f["/contacts/required_friction"][()] if "/contacts/required_friction" in f else None
        rf_leg = f["/contacts/required_friction_leg"][()] if rf is not None else None
    e = {"T": len(t), "relaxed_out": int(((status == 1) & ~touchdown).sum()),
         "relaxed_in": int(((status == 1) & touchdown).sum()), "failed": int((status == 2).sum()),
         "slip": int(slip.sum()), "rf": rf is not None}
    if rf is not None:
        e["nan"] = int(np.isnan(rf).sum())
        finite = ~touchdown & np.isfinite(rf)
        if finite.any():
            i = int(np.flatnonzero(finite)[np.argmax(rf[finite])])  # the first of the largest
            e["peak"] = (float(rf[i]), f"L{int(rf_leg[i]) + 1}", float(t[i]))
    # Episodes: runs of relaxed samples, split where the touchdown flag changes.
    kinds = {True: [], False: []}
    previous = None
    for i in range(len(t)):
        if status[i] != 1:
            previous = None
            continue
        if previous != bool(touchdown[i]):
            kinds[bool(touchdown[i])].append([t[i], t[i], 0])
        run = kinds[bool(touchdown[i])][-1]
        run[1] = t[i]
        run[2] += 1
        previous = bool(touchdown[i])
    e["episodes"] = kinds
    return e


def check_verdict(name, line, e):
    m = VERDICT.match(line)
    check(m is not None, f"{name}: the last line is the verdict: {line[:160]}")
    if not m:
        return
    g = m.groups()
    check(int(g[0]) == e["T"], f"{name}: samples {g[0]} == {e['T']}")
    check(int(g[1]) == e["relaxed_out"], f"{name}: relaxed outside {g[1]} == {e['relaxed_out']}")
    check(int(g[2]) == e["relaxed_in"], f"{name}: relaxed in touchdowns {g[2]} == {e['relaxed_in']}")
    check(int(g[3] or 0) == e["failed"], f"{name}: failed {g[3]} == {e['failed']}")
    check((m.group("off") is not None) == (not e["rf"]), f"{name}: required friction computed or not")
    if e["rf"]:
        check((m.group("none") is not None) == ("peak" not in e), f"{name}: a required friction")
        if "peak" in e:
            mu, leg, when = e["peak"]
            check(close(float(g[6]), mu), f"{name}: largest required friction {g[6]} ~ {mu}")
            check(g[7] == leg, f"{name}: its leg {g[7]} == {leg}")
            check(close(float(g[8]), when), f"{name}: its time {g[8]} ~ {when}")
        check(int(g[9] or 0) == e["nan"], f"{name}: samples without one {g[9]} == {e['nan']}")
    check(int(g[10]) == e["slip"], f"{name}: slip samples {g[10]} == {e['slip']}")


def check_episodes(name, lines, e):
    for touchdown, runs in e["episodes"].items():
        where = "in touchdown transients" if touchdown else "outside touchdowns"
        summaries = [m for m in map(SUMMARY.match, lines) if m and m.group(2) == where]
        if len(runs) > 1:
            check(len(summaries) == 1, f"{name}: one summary of the {len(runs)} episodes {where}")
            if summaries:
                g = summaries[0].groups()
                check(int(g[0]) == len(runs), f"{name}: {where}: episodes {g[0]} == {len(runs)}")
                samples = sum(r[2] for r in runs)
                check(int(g[2]) == samples, f"{name}: {where}: samples {g[2]} == {samples}")
                check(close(float(g[3]), runs[0][0]) and close(float(g[4]), runs[-1][1]),
                      f"{name}: {where}: from {g[3]} to {g[4]} s ~ {runs[0][0]} to {runs[-1][1]}")
                worst = float(g[5])
                check(any(r[0] - 1e-5 <= worst <= r[1] + 1e-5 for r in runs),
                      f"{name}: {where}: the worst sample at {worst} s is in an episode")
        else:
            check(not summaries, f"{name}: no summary {where} ({len(runs)} episode)")
    singles = [m for m in map(SINGLE.match, lines) if m]
    expected_singles = [r for runs in e["episodes"].values() if len(runs) == 1 for r in runs]
    check(len(singles) == len(expected_singles),
          f"{name}: {len(singles)} single-episode lines == {len(expected_singles)}")
    for m, r in zip(singles, expected_singles):
        check(close(float(m.group(1)), r[0]) and close(float(m.group(2)), r[1]) and
              int(m.group(3)) == r[2], f"{name}: single episode {m.group(0)[:60]} ~ {r}")
    longest = max(len(x) for x in lines)
    check(longest < 400, f"{name}: the longest line has {longest} < 400 characters")


def is_index_column(spec):
    """An integer dataset that holds leg or joint numbers (not a coordinate or a count)."""
    last = spec.path.rsplit("/", 1)[-1]
    return spec.element.startswith("int") and (last in ("leg", "joint") or
                                                last.endswith(("_leg", "_joint")))


def check_zero_based(result_path):
    from hexdyn.results import SCHEMA, DatasetSpec
    columns = [d for d in SCHEMA.values() if isinstance(d, DatasetSpec) and is_index_column(d)]
    check(len(columns) >= 6, f"{len(columns)} integer leg or joint columns declared")
    for d in columns:
        check("0-based" in d.long_name, f"{d.name} {d.path}: long_name {d.long_name!r} says 0-based")
    with h5py.File(result_path, "r") as f:
        for path in ("/contacts/required_friction_leg", "/impacts/leg"):
            name = f[path].attrs["long_name"]
            name = name.decode() if isinstance(name, bytes) else str(name)
            check("0-based" in name, f"{path} in the file: long_name {name!r}")


def main():
    hexdyn, source = args()
    scene = os.path.join(source, "configs", "paper.yaml")
    cases = {"paper": [], "mu 0.02": ["contact.friction_coefficient=0.02"],
             "mu 0.04": ["contact.friction_coefficient=0.04"],
             "no required friction": ["contact.friction_coefficient=0.02",
                                      "output.required_friction=false"]}
    seen_slip = seen_relaxed_out = False
    with tempfile.TemporaryDirectory() as tmp:
        for name, sets in cases.items():
            out = os.path.join(tmp, "out.h5")
            status, err = cli_run(hexdyn, scene, out, sets)
            check(status == 0, f"{name}: exit status {status}")
            if status != 0:
                print(err)
                continue
            lines = err.strip().splitlines()
            e = expected(out)
            seen_slip |= e["slip"] > 0
            seen_relaxed_out |= e["relaxed_out"] > 0
            check_verdict(name, lines[-1], e)
            check_episodes(name, lines, e)
            if name == "paper":
                check_zero_based(out)
    # The cases reach what the verdict counts: else the checks above could not fail.
    check(seen_slip and seen_relaxed_out, "some case slips and relaxes outside touchdowns")
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
