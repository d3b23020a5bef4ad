"""The required friction of a run, sample by sample, against a second computation on fast gaits
of the stairs range (configs/sweeps/stairs_base.yaml, the range of bench/sweep_1000.yaml):

A run computes each sample's mu* with what the previous samples left (the active set of the
previous sample, the first probes around its mu*, a probe at mu = 1000 first after a sample
without mu*; docs/theory/grip.md#where-the-active-set-comes-from). Here the run's
/contacts/required_friction is compared, on samples chosen for where those shortcuts act, with
the least mu at which HiGHS finds the sample's rows feasible (scipy.optimize.linprog(method=
"highs"), bisection to 1e-8; the rows from hexdyn.sample_problem at the sample's time):
  - the samples just after a contact event (the row layout changes: no warm active set; a
    leg starting its touchdown transient without load);
  - the last samples, coming to rest (mu* near 0);
  - the samples of least positive mu* (near rest and near a leg without load: degenerate
    vertices, where several faces of a leg are active at once);
  - the first and the last sample without mu* (NaN) and the sample after each;
  - the largest mu* of the run, and a spread over the run.
Agreement: NaN where the reference is NaN, else within 1e-6 max(1, mu*).

    test_required_friction_stairs.py HEXDYN_BINARY SOURCE_DIR   (PYTHONPATH: the build tree's python/)
"""

import math
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import args  # noqa: E402

import hexdyn  # noqa: E402
from scipy.optimize import linprog  # noqa: E402
from test_required_friction import bisection, one_sided, rows_at  # noqa: E402

HEXDYN, SRC = args()
BASE = os.path.join(SRC, "configs", "sweeps", "stairs_base.yaml")
AGREEMENT = 1e-6
# (riser [m], peak speed [m/s], duty factor): fast gaits of the range, where the samples
# after contact events, the touchdown transients and the relaxed samples are many.
SCENES = [(0.02, 0.2, "3/4"), (0.02, 0.12, "2/3"), (0.05, 0.12, "3/4"), (0.09, 0.12, "1/2")]


def lp_feasible(p, mu):
    """HiGHS on the feasibility LP of the rows at mu (as test_required_friction.py); when HiGHS
    ends that LP in an unknown status (degenerate rows of a leg without load), on its phase-one
    form instead: min s subject to every row but the trunk rows relaxed by s >= 0, feasible
    when s <= 1e-10."""
    C, lower, upper = rows_at(p, mu)
    A_ub, b_ub = one_sided(C, lower, upper)
    n = C.shape[1]
    opts = {"primal_feasibility_tolerance": 1e-10}
    res = linprog(np.zeros(n), A_ub=A_ub, b_ub=b_ub, A_eq=C[:6], b_eq=lower[:6],
                  bounds=[(None, None)] * n, method="highs", options=opts)
    if res.status in (0, 2):
        return res.status == 0
    res = linprog(np.eye(1, n + 1, n).ravel(), A_ub=np.hstack([A_ub, -np.ones((len(b_ub), 1))]),
                  b_ub=b_ub, A_eq=np.hstack([C[:6], np.zeros((6, 1))]), b_eq=lower[:6],
                  bounds=[(None, None)] * n + [(0, None)], method="highs", options=opts)
    assert res.status in (0, 2), f"HiGHS at mu = {mu}: {res.message}"
    return res.status == 0 and res.x[n] <= 1e-10


def chosen(time, mu, phase):
    """Sample indices of the run to check (module comment)."""
    events = [i for i in range(1, len(time)) if (phase[i] != phase[i - 1]).any()]
    finite = np.isfinite(mu)
    positive = np.where(finite & (mu > 0))[0]
    nan = np.where(~finite)[0]
    picks = set(events) | set(range(max(0, len(time) - 8), len(time)))
    picks.update(positive[np.argsort(mu[positive])][:4].tolist())
    for i in (nan[:1].tolist() + nan[-1:].tolist()):
        picks.update({i, min(i + 1, len(time) - 1)})
    if finite.any():
        picks.add(int(np.nanargmax(np.where(finite, mu, -1.0))))
    picks.update(range(0, len(time), max(1, len(time) // 5)))
    return sorted(picks)


def main():
    failures, checked, nan_checked = [], 0, 0
    with tempfile.TemporaryDirectory(prefix="hexdyn_rf_stairs_") as work:
        for riser, speed, duty in SCENES:
            sets = {"terrain.riser_height": riser, "motion.peak_speed": speed,
                    "gait.duty_factor": duty}
            out = os.path.join(work, "run.h5")
            cmd = [HEXDYN, "run", BASE, "-o", out]
            for k, v in sets.items():
                cmd += ["--set", f"{k}={v}"]
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            with h5py.File(out, "r") as f:
                time = f["time"][()]
                mu = f["contacts/required_friction"][()]
                phase = f["contacts/phase"][()]
            for i in chosen(time, mu, phase):
                p = hexdyn.sample_problem(BASE, float(time[i]), set=sets)
                if p["constant_excess_Nm"] > 1e-6 or not p["legs"] or p["variables"] == 0:
                    reference = math.nan
                else:
                    reference = bisection(lambda m: lp_feasible(p, m))
                where = f"riser {riser}, speed {speed}, duty {duty}, t = {time[i]!r} s"
                checked += 1
                if math.isnan(reference) or math.isnan(mu[i]):
                    nan_checked += math.isnan(reference)
                    if not (math.isnan(reference) and math.isnan(mu[i])):
                        failures.append(f"{where}: run {mu[i]!r}, HiGHS {reference!r}")
                elif abs(mu[i] - reference) > AGREEMENT * max(1.0, reference):
                    failures.append(f"{where}: run {mu[i]!r}, HiGHS {reference!r}, "
                                    f"difference {mu[i] - reference!r}")
    print(f"{checked} samples checked ({nan_checked} without mu*)")
    assert nan_checked > 0, "no sample without mu* was checked"
    assert not failures, "run's required friction off HiGHS:\n  " + "\n  ".join(failures)
    print("ok")


if __name__ == "__main__":
    main()
