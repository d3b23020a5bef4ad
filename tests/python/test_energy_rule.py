"""The energies a result file reports against their recomputation from its series by the rule
/meta energy_rule names (hexdyn.results.energy_by_rule, docs/theory/output-grid.md#energy-from-the-samples):
a computation of its own (Vandermonde systems and numpy.roots per interval, not the writer's
Newton form and bisection), on the paper scene (adaptive grid: the piecewise cubic), a
speed-defined wave gait refined to 1e-4 and the uniform grid (the trapezoid). The cycles add
up to the total; without the pieces the left limits bound, the rule gives another energy
(the test tells); the rule is closer to a converged grid than the trapezoid over the same
samples.
    test_energy_rule.py HEXDYN_BINARY SOURCE_DIR      (PYTHONPATH: the build tree's python/)"""

import os
import tempfile

import numpy as np

import hexdyn
from common import args, cli_run
from hexdyn.results import ENERGY_RULE_CUBIC, ENERGY_RULE_TRAPEZOID, energy_by_rule

HEXDYN, SRC = args()
PAPER = os.path.join(SRC, "configs/paper.yaml")
WAVE = ["motion.cycle_durations=null", "motion.cycles=2", "motion.peak_speed=0.15",
        "motion.ramp_duration=0.8",
        "gait.duty_factor=5/6", "output.tolerance=1e-4"]
CASES = [("paper", [], ENERGY_RULE_CUBIC), ("wave 1e-4", WAVE, ENERGY_RULE_CUBIC),
         ("uniform", ["output.grid=uniform"], ENERGY_RULE_TRAPEZOID)]


def recomputed(r, kind=None):
    kind = r["/sample_kind"] if kind is None else kind
    return energy_by_rule(r["/time"], r["/power/per_joint"], kind, r.meta["energy_rule"])


with tempfile.TemporaryDirectory() as d:
    for name, sets, rule in CASES:
        rc, err = cli_run(HEXDYN, PAPER, f"{d}/{name}.h5", sets)
        assert rc == 0, err
        r = hexdyn.open_result(f"{d}/{name}.h5")
        assert r.meta["energy_rule"] == rule, (name, r.meta["energy_rule"])
        Ej, E = r["/energy/per_joint"], float(r["/energy/total"])
        mine = recomputed(r)
        worst = np.max(np.abs(mine - Ej)) / E
        assert worst < 1e-9, (name, worst)
        assert abs(mine.sum() - E) < 1e-9 * E, (name, mine.sum(), E)
        assert abs(r["/energy/cycle"].sum() - E) < 1e-9 * E, name
        if rule == ENERGY_RULE_CUBIC:
            # The pieces matter: across the jumps the cubics ring.
            plain = recomputed(r, np.zeros_like(r["/sample_kind"])).sum()
            assert abs(plain - E) > 1e-6 * E, (name, plain, E)
        print(f"{name}: {len(r['/time'])} samples, {rule}, {E:.9g} J, "
              f"recomputed to {worst:.1e}")
    # Against a converged grid (0.5 ms, 0.1 ms next to events, refined to 1e-6): the cubic over
    # the paper's 594 samples is closer than the trapezoid over the same samples.
    fine = ["output.sample_step=5e-4", "output.event_step=1e-4", "output.tolerance=1e-6"]
    rc, err = cli_run(HEXDYN, PAPER, f"{d}/fine.h5", fine)
    assert rc == 0, err
    ref = float(hexdyn.open_result(f"{d}/fine.h5")["/energy/total"])
    r = hexdyn.open_result(f"{d}/paper.h5")
    cubic = float(r["/energy/total"])
    trap = energy_by_rule(r["/time"], r["/power/per_joint"], None, ENERGY_RULE_TRAPEZOID).sum()
    print(f"paper: converged {ref:.9g} J, cubic {cubic / ref - 1:+.1e}, trapezoid {trap / ref - 1:+.1e}")
    assert abs(cubic - ref) < abs(trap - ref), (cubic, trap, ref)
    assert abs(cubic - ref) < 1e-4 * ref
