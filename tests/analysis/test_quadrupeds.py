#!/usr/bin/python3
"""The quadruped study, reduced (pipelines/quadrupeds.sh --quick; docs/validation/quadrupeds.md),
checked against readings of its files made here with h5py, csv and xml:

  - the pipeline writes its five figures, the CSV and the Markdown table;
  - the CSV holds one line per scenario of every sweep file, failed ones included, each with
    the status /scenarios/status names (its flag_meanings) and the relaxed counts of the file;
    its verdict follows from them (climbs: ok and no relaxed sample outside touchdowns);
  - for every computed scenario, from its kept run:
      the relaxed samples outside touchdowns are the samples with /solver/status 1 and no leg
      in phase 1 (/contacts/phase);
      the cost of transport is /energy/total over m g d and the electrical one the trapezoid
      rule of /power/electrical_total over /time over m g d, with m the sum of the link masses
      of the URDF text in /model/urdf, g 9.81 m/s² and d the trunk's displacement from the
      first to the last sample of /base/position;
      the required friction is the largest finite /contacts/required_friction over the samples
      with no leg in phase 1;
      the peak winding temperature is at least the largest /thermal/winding_temperature.
  - at least one scenario per robot is computed (so the checks above ran).

usage: test_quadrupeds.py --hexdyn BUILD/hexdyn --source SOURCE_DIR   (PYTHONPATH=BUILD/python)
"""

import argparse
import csv
import glob
import math
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

import h5py
import numpy as np

GRAVITY = 9.81  # m/s², the program's constant (docs/theory/conventions.md)
FIGURES = ("quadrupeds_cot_speed.png", "quadrupeds_cot_riser.png", "quadrupeds_envelope.png",
           "quadrupeds_friction.png", "quadrupeds_thermal.png")
failures = []


def check(ok, what, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail and not ok else ''}")
    if not ok:
        failures.append(what)


def close(a, b, rel):
    a, b = float(a), float(b)
    return (math.isnan(a) and math.isnan(b)) or math.isclose(a, b, rel_tol=rel, abs_tol=1e-15)


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def urdf_mass(urdf_text):
    """Σ of the <inertial><mass value> of every link of the URDF text."""
    root = ET.fromstring(urdf_text)
    return sum(float(m.get("value")) for m in root.iter("mass"))


def trapezoid(t, y):
    return float(np.sum(0.5 * np.diff(t) * (y[1:] + y[:-1])))


def check_run(tag, run, row):
    """The CSV row's values against the kept run, each recomputed here."""
    phase = run["contacts/phase"][()]
    outside = ~(phase == 1).any(axis=1)
    status = run["solver/status"][()]
    check(int(row["relaxed_gait_samples"]) == int(((status == 1) & outside).sum()),
          f"{tag} relaxed samples outside touchdowns")
    m = urdf_mass(text(run["model/urdf"][()]))
    p = run["base/position"][()]
    d = float(np.linalg.norm(p[-1] - p[0]))
    cot = float(run["energy/total"][()]) / (m * GRAVITY * d)
    check(close(row["cost_of_transport"], cot, 1e-9), f"{tag} cost of transport = E/(m g d)",
          f"{row['cost_of_transport']} vs {cot}")
    t = run["time"][()]
    e_el = trapezoid(t, run["power/electrical_total"][()])
    cot_el = e_el / (m * GRAVITY * d)
    check(close(row["cost_of_transport_electrical"], cot_el, 1e-9),
          f"{tag} electrical cost of transport = trapezoid of the power / (m g d)",
          f"{row['cost_of_transport_electrical']} vs {cot_el}")
    mu = run["contacts/required_friction"][()]
    sel = outside & np.isfinite(mu)
    mu_max = float(mu[sel].max()) if sel.any() else math.nan
    check(close(row["required_friction_support"], mu_max, 1e-12),
          f"{tag} required friction outside touchdowns", f"{row['required_friction_support']} vs "
          f"{mu_max}")
    tw = run["thermal/winding_temperature"][()]
    check(float(row["peak_winding_temperature_max"]) >= float(tw.max()) - 1e-12,
          f"{tag} peak winding temperature >= the series' largest")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--hexdyn", required=True)
    ap.add_argument("--source", required=True)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as d:
        subprocess.run(["bash", os.path.join(args.source, "pipelines", "quadrupeds.sh"), "--quick",
                        "--hexdyn", args.hexdyn, "--out", d], check=True)
        for name in FIGURES + ("quadrupeds.csv", "quadrupeds_table.txt"):
            path = os.path.join(d, name)
            check(os.path.isfile(path) and os.path.getsize(path) > 0, f"pipeline writes {name}")
        with open(os.path.join(d, "quadrupeds.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
        files = sorted(glob.glob(os.path.join(d, "*.h5")))
        check(len(files) == 8, "eight sweep files", str(len(files)))
        computed = {}
        seen = 0
        for path in files:
            with h5py.File(path, "r") as f:
                name = text(f["meta"].attrs["name"])
                sc = f["scenarios"]
                names = text(sc["status"].attrs["flag_meanings"]).split()
                mine = [r for r in rows if r["sweep"] == name]
                ids = [text(v) for v in sc["id"][()]]
                check(len(mine) == len(ids), f"{name}: a CSV line per scenario")
                for i, sid in enumerate(ids):
                    row = next((r for r in mine if r["id"] == sid), None)
                    if row is None:
                        check(False, f"{name} {sid} in the CSV")
                        continue
                    seen += 1
                    status = names[int(sc["status"][i])]
                    relaxed = int(sc["relaxed_gait_samples"][i])
                    check(row["status"] == status, f"{name} {sid} status {status}")
                    check(int(row["relaxed_gait_samples"]) == relaxed,
                          f"{name} {sid} relaxed count")
                    want = "failed" if status != "ok" else ("climbs" if relaxed == 0 else "relaxed")
                    check(row["verdict"] == want, f"{name} {sid} verdict {want}")
                    if status == "ok":
                        check_run(f"{name} {sid}", f["runs"][sid], row)
                        computed[row["robot"]] = computed.get(row["robot"], 0) + 1
        check(seen == len(rows), "every CSV line is a scenario of a file", f"{seen} vs {len(rows)}")
        check(len(computed) == 2, "some scenario of each robot computed", str(computed))
    if failures:
        print(f"{len(failures)} check(s) failed", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
