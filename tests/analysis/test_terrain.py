#!/usr/bin/python3
"""The terrain examples end to end (pipelines/terrain.sh, docs/validation/terrain.md).

Runs the pipeline with the given binary into a temporary directory and checks, from the files
it wrote and against computations made here:
  - the figure and the table are written, and the table has one row per example and robot
    (every configs/terrain/*.yaml with the paper hexapod, every configs/terrain/anymal/*.yaml
    with ANYmal C), each with a status; a failed row carries the run's one-line error, and
    the run wrote no result file;
  - every computed run's status and relaxed count equal those counted here from its samples
    (/solver/status, /contacts/phase), its energies those of its file;
  - descent of the paper's stairs by the tripod has no failed sample, and its net joint work
    (positive + negative, /energy) equals the change of the potential energy of the centre of
    mass, m g Δz (/com/position, /model/total_mass), to 1 %: a descent of 0.15 m, from rest
    to rest, with the feet still while they carry load; positive − negative = /energy/total;
  - bad terrain input exits non-zero with one line per bad step, or one line for a bad
    nosing, and writes nothing.

    test_terrain.py --hexdyn BINARY --source SOURCE_DIR
"""

import argparse
import csv
import glob
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what)


def counted(h5):
    """(status word, relaxed samples outside touchdowns, failed samples) from the samples."""
    with h5py.File(h5, "r") as f:
        status = f["/solver/status"][()]
        phase = f["/contacts/phase"][()]
    gait = int(np.count_nonzero((status != 0) & np.all(phase != 1, axis=1)))
    return ("climbs" if gait == 0 else "relaxed"), gait, int(np.count_nonzero(status == 2))


def check_rows(src, out):
    with open(os.path.join(out, "terrain_runs.csv")) as f:
        rows = list(csv.DictReader(f))
    expected = {("paper_hexapod", os.path.basename(p)[:-5])
                for p in glob.glob(os.path.join(src, "configs/terrain/*.yaml"))}
    expected |= {("anymal_c", os.path.basename(p)[:-5])
                 for p in glob.glob(os.path.join(src, "configs/terrain/anymal/*.yaml"))}
    got = {(r["robot"], r["example"]) for r in rows}
    check(got == expected, f"rows {sorted(got)}, expected {sorted(expected)}")
    for r in rows:
        stem = os.path.join(out, "runs", f"{r['robot']}__{r['example']}")
        if r["status"] == "failed":
            check(not os.path.exists(stem + ".h5"), f"{stem}: failed, yet a result was written")
            check(r["message"].startswith("hexdyn: error: ") and "\n" not in r["message"],
                  f"{stem}: message {r['message']!r}")
            continue
        word, gait, _ = counted(stem + ".h5")
        check(r["status"] == word and int(r["relaxed_gait_samples"]) == gait,
              f"{stem}: table says {r['status']}, {r['relaxed_gait_samples']}; counted "
              f"{word}, {gait}")
        with h5py.File(stem + ".h5", "r") as f:
            e, p, n = (float(f[k][()]) for k in ("/energy/total", "/energy/positive_work",
                                                   "/energy/negative_work"))
        check(abs(float(r["energy_J"]) - e) <= 1e-3 * e, f"{stem}: energy {r['energy_J']}")
        check(p >= 0 and n <= 0 and abs(p - n - e) <= 1e-12 * e,
              f"{stem}: positive {p}, negative {n}, energy {e}")
    return rows


def check_descent_balance(out):
    h5 = os.path.join(out, "runs", "paper_hexapod__paper_descent.h5")
    _, _, failed = counted(h5)
    check(failed == 0, f"paper descent by the tripod: {failed} failed samples")
    with h5py.File(h5, "r") as f:
        p, n = f["/energy/positive_work"][()], f["/energy/negative_work"][()]
        m = float(f["/model/total_mass"][()])
        z = f["/com/position"][()][:, 2]
    dpe = m * 9.81 * (z[-1] - z[0])
    net = p + n
    print(f"paper descent: net joint work {net:.4f} J, m g dz {dpe:.4f} J "
          f"(positive {p:.4f} J, negative {n:.4f} J)")
    check(dpe < -1.0 and abs(net - dpe) <= 0.01 * abs(dpe),
          f"paper descent: net joint work {net} J against m g dz {dpe} J")


def check_bad_input(hexdyn, src, d):
    scene = os.path.join(src, "configs/terrain/paper_descent.yaml")
    out = os.path.join(d, "bad.h5")
    cases = [
        ("[{riser: .nan}, {tread: -0.2}, {riser: 0.05, nosing: 0.3}]", 2),
        ("[{riser: 0.05}, {riser: 0.05, nosing: 0.25}]", 1),
        ("[{landing: 0}]", 1),
    ]
    for value, lines in cases:
        p = subprocess.run([hexdyn, "run", scene, "-o", out, "--set", f"terrain.steps={value}"],
                           capture_output=True, text=True)
        errs = [x for x in p.stderr.splitlines() if x.startswith("hexdyn: error: ")]
        check(p.returncode != 0 and len(errs) == lines and not os.path.exists(out),
              f"terrain.steps={value}: status {p.returncode}, {len(errs)} error lines "
              f"(expected {lines}), output written: {os.path.exists(out)}")
        check(all("terrain.steps[" in e for e in errs), f"terrain.steps={value}: {errs}")
    p = subprocess.run([hexdyn, "run", scene, "-o", out, "--set", "terrain.nosing=0.25"],
                       capture_output=True, text=True)
    check(p.returncode != 0 and len(p.stderr.strip().splitlines()) == 1
          and "terrain.nosing" in p.stderr and not os.path.exists(out),
          f"terrain.nosing=0.25: status {p.returncode}, {p.stderr!r}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--hexdyn", required=True)
    ap.add_argument("--source", required=True)
    a = ap.parse_args()
    src = os.path.realpath(a.source)
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "terrain")
        subprocess.run(["bash", os.path.join(src, "pipelines/terrain.sh"), "--hexdyn",
                        os.path.realpath(a.hexdyn), "--out", out], check=True)
        for name in ("terrain_up_down.png", "terrain_runs.csv", "terrain_table.txt"):
            check(os.path.getsize(os.path.join(out, name)) > 0, f"{name} is empty")
        rows = check_rows(src, out)
        check_descent_balance(out)
        check_bad_input(a.hexdyn, src, d)
        print(f"terrain: {len(rows)} example runs, "
              f"{sum(r['status'] != 'failed' for r in rows)} computed")
    if failures:
        print(f"{len(failures)} failures")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
