"""The required friction (docs/theory/grip.md#required-friction) against a second computation by
other solvers, from the rows hexdyn.sample_problem returns (docs/user/api.md):

  a. The layout: the first six rows are the trunk rows (lower == upper); each friction face
     is cos a_f t1 + sin a_f t2 <= mu cos(pi/N_f) f_n, a_f = 2 pi f / N_f
     (allocation/friction.hpp), at the scene's mu: on a support leg the f_n column holds
     -mu face_reach, on a leg in its touchdown transient the upper bound is
     mu face_reach known_normal_force_N; the cones carry the scene's mu.
  b. Pyramids (allocation.friction pyramid4, pyramid8): mu* by bisection to 1e-8 on the
     feasibility of the LP of the rows at mu (zero objective, the trunk rows as equalities,
     every other row as one or two inequalities), solved by HiGHS
     (scipy.optimize.linprog(method="highs")), against hexdyn's to 1e-6 absolute.
  c. The exact cone (allocation.friction cone): the same bisection on the SOCP
     min s  subject to  every row and cone relaxed by s (s >= -1),  feasible when s <= 0,
     solved by cvxopt.solvers.conelp (the touchdown legs' 16-gon faces as linear rows).
  d. Two feet (a balanced trot's diagonal, configs/robots/solo12_trot_balanced.yaml): no force
     gives a moment about the line through them, so the trunk rows have rank 5, and the planned
     wrench meets that moment only to its rounding (about 1e-9 here), which no LP holds to
     1e-10 at any mu. The reference takes the rows' least-squares part (numpy.linalg.lstsq):
     what hexdyn drops below the allocation's threshold of 1e-6
     (docs/theory/grip.md#the-trunk-rows-reach), and checks that it was below.
  e. A touchdown transient sample where hexdyn says NaN (a leg in phase 1, the allocation
     relaxed): the LP is infeasible at mu = 1000.

Samples of the paper scene (configs/paper.yaml): support samples at several times, a sample
at a contact event (a touchdown transient's end, where its rows can hold), and a faster,
higher-duty-factor variant (gait.duty_factor 3/4, cycles of 1.4, 1.0 and 1.4 s instead of the
paper's 3.0, 2.6 and 3.0 s) so that mu* is not small (up to 0.54 on support, above 1 in
touchdown transients), there also with legs in their touchdown transient.

    test_required_friction.py HEXDYN_BINARY SOURCE_DIR   (PYTHONPATH: the build tree's python/)
"""

import math
import os
import sys

import numpy as np
from cvxopt import matrix, solvers
from scipy.optimize import linprog

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import args  # noqa: E402

import hexdyn  # noqa: E402

HEXDYN, SRC = args()
PAPER = os.path.join(SRC, "configs", "paper.yaml")
TROT = os.path.join(SRC, "configs", "robots", "solo12_trot_balanced.yaml")
UNREACHABLE = 1e-6    # the allocation's verdict threshold, relative to max(1, |b|)
MU_MAX = 1e3          # hexdyn's largest mu (grip/required_friction.hpp)
BRACKET = 1e-8        # bisection's final bracket
AGREEMENT = 1e-6      # |hexdyn - reference|, absolute
FAST = {"gait.duty_factor": "3/4", "motion.cycle_durations": [1.4, 1.0, 1.4]}
# cvxopt's default tolerances (abstol, feastol 1e-7): s within about 1e-7 N of its minimum,
# which moves the cone's mu* by about 1e-7 N / f_n, f_n ~ 20 N. Tighter ones break its
# iterations on these problems (a square root of a negative number in its scaling update).
solvers.options.update({"show_progress": False})


def bounded(v):
    return np.isfinite(v) & (np.abs(v) < 1e19)


def check_layout(p):
    """(a): the rows are those the docs describe, at the scene's mu."""
    mu = p["friction_coefficient"]
    C, lower, upper = p["C"], p["lower"], p["upper"]
    assert C.shape == (len(lower), p["variables"]) == (len(upper), len(p["x"]))
    assert np.array_equal(lower[:6], upper[:6]), "the trunk rows are not lower == upper"
    assert all(name.startswith("trunk") for name in p["ineq_names"][:6])
    for leg in p["legs"]:
        o, nf = leg["offset"], leg["friction_faces"]
        for f in range(nf):
            r = leg["friction_row"] + f
            a = 2 * math.pi * f / nf
            assert abs(leg["face_reach"] - math.cos(math.pi / nf)) < 1e-15
            assert np.allclose(C[r, o:o + 2], [math.cos(a), math.sin(a)], rtol=0, atol=1e-15)
            if leg["count"] == 3:
                assert abs(C[r, o + 2] + mu * leg["face_reach"]) < 1e-15 and upper[r] == 0.0
            else:
                assert leg["count"] == 2
                assert abs(upper[r] - mu * leg["face_reach"] * leg["known_normal_force_N"]) \
                    <= 1e-12 * max(1.0, abs(upper[r]))
    for cone in p["cones"]:
        assert cone["mu"] == mu


def rows_at(p, mu):
    """(C, lower, upper) with every friction face at mu (the cones are set by the caller)."""
    C, upper = p["C"].copy(), p["upper"].copy()
    for leg in p["legs"]:
        for r in range(leg["friction_row"], leg["friction_row"] + leg["friction_faces"]):
            if leg["count"] == 3:
                C[r, leg["offset"] + 2] = -mu * leg["face_reach"]
            else:
                upper[r] = mu * leg["face_reach"] * leg["known_normal_force_N"]
    return C, p["lower"], upper


def one_sided(C, lower, upper):
    """The rows after the trunk rows as G x <= h."""
    G, h = [], []
    for i in range(6, C.shape[0]):
        if bounded(upper[i]):
            G.append(C[i])
            h.append(upper[i])
        if bounded(lower[i]):
            G.append(-C[i])
            h.append(-lower[i])
    return np.array(G).reshape(-1, C.shape[1]), np.array(h)


def lp_feasible(p, mu):
    """(b): HiGHS on the feasibility LP of the rows at mu."""
    C, lower, upper = rows_at(p, mu)
    A_ub, b_ub = one_sided(C, lower, upper)
    n = C.shape[1]
    res = linprog(np.zeros(n), A_ub=A_ub, b_ub=b_ub, A_eq=C[:6], b_eq=lower[:6],
                  bounds=[(None, None)] * n, method="highs",
                  options={"primal_feasibility_tolerance": 1e-10})
    assert res.status in (0, 2), f"HiGHS at mu = {mu}: {res.message}"
    return res.status == 0


def socp_feasible(p, mu):
    """(c): cvxopt on min s over (x, s) subject to the trunk rows and every other row and cone
    relaxed by s, s >= -1; feasible when the solution's own margin, measured on the rows, is
    not positive."""
    C, lower, upper = rows_at(p, mu)
    n = C.shape[1]
    G, h = one_sided(C, lower, upper)
    rows = G.shape[0]
    G = np.vstack([np.hstack([G, -np.ones((rows, 1))]), np.eye(1, n + 1, n) * -1.0])
    h = np.concatenate([h, [1.0]])  # -s <= 1
    for cone in p["cones"]:  # s0 = mu x_n + s >= ||(x_t1, x_t2)|| = ||(s1, s2)||
        q = np.zeros((3, n + 1))
        q[0, cone["normal"]], q[0, n] = -mu, -1.0
        q[1, cone["tangent1"]] = q[2, cone["tangent2"]] = -1.0
        G = np.vstack([G, q])
        h = np.concatenate([h, np.zeros(3)])
    A, b = C[:6], lower[:6]
    U, sigma, _ = np.linalg.svd(A)
    rank = int(np.sum(sigma > 1e-9 * sigma[0]))
    if rank < 6:  # conelp needs independent equality rows: their range's basis
        A, b = U[:, :rank].T @ A, U[:, :rank].T @ b
    A = np.hstack([A, np.zeros((A.shape[0], 1))])
    c = np.eye(1, n + 1, n).ravel()
    sol = solvers.conelp(matrix(c), matrix(G), matrix(h),
                         dims={"l": rows + 1, "q": [3] * len(p["cones"]), "s": []},
                         A=matrix(A), b=matrix(b))
    assert sol["x"] is not None, f"cvxopt at mu = {mu}: {sol['status']}"
    x = np.array(sol["x"]).ravel()[:n]
    margin = np.max(G[:rows, :n] @ x - h[:rows], initial=-math.inf)
    for cone in p["cones"]:
        use = math.hypot(x[cone["tangent1"]], x[cone["tangent2"]]) - mu * x[cone["normal"]]
        margin = max(margin, use)
    return margin <= 0.0


def within_reach(p):
    """(d): p with its trunk rows' part outside the range of their columns removed, when that
    part is at most UNREACHABLE of each row's scale max(1, |b|); p itself otherwise."""
    C, b = p["C"][:6], p["lower"][:6]
    scale = np.maximum(1.0, np.abs(b))
    x = np.linalg.lstsq(C / scale[:, None], b / scale, rcond=1e-9)[0]
    part = b - C @ x
    if np.max(np.abs(part) / scale) > UNREACHABLE:
        return p
    q = dict(p, lower=p["lower"].copy(), upper=p["upper"].copy())
    q["lower"][:6] = q["upper"][:6] = b - part
    return q


def bisection(feasible):
    """The least mu in [0, MU_MAX] at which feasible(mu) holds, within BRACKET above; NaN when
    MU_MAX does not suffice."""
    if not feasible(MU_MAX):
        return math.nan
    lo, hi = 0.0, MU_MAX
    while hi - lo > BRACKET:
        mid = 0.5 * (lo + hi)
        if feasible(mid):
            hi = mid
        else:
            lo = mid
    return hi


def describe(model, overrides, t, p):
    return (f"friction {model}, overrides {overrides}, t = {t!r} s: phases {p['phase'].tolist()},"
            f" status {p['status']}")


def compare(model, overrides, t, scene=PAPER):
    """hexdyn's mu* of one sample against the bisection's; returns hexdyn's."""
    sets = dict(overrides, **{"allocation.friction": model})
    p = hexdyn.sample_problem(scene, t, set=sets)
    assert p["friction"] == model
    check_layout(p)
    if p["constant_excess_Nm"] > 1e-6:
        reference = math.nan
    else:
        q = within_reach(p)
        reference = bisection(lambda mu: (socp_feasible if q["cones"] else lp_feasible)(q, mu))
    ours = p["required_friction"]
    where = describe(model, overrides, t, p)
    print(f"{where}: hexdyn {ours!r}, reference {reference!r}")
    if math.isnan(reference) or math.isnan(ours):
        if not (math.isnan(reference) and math.isnan(ours)):
            FAILURES.append(f"{where}: hexdyn {ours!r}, reference {reference!r}")
    elif abs(ours - reference) > AGREEMENT:
        FAILURES.append(f"{where}: hexdyn {ours!r}, reference {reference!r}, "
                        f"difference {ours - reference!r}")
    return p


FAILURES = []


# Sample times are instants of the scenes' output grids (hexdyn.run(...)["/time"]).
SAMPLES = [
    # (friction model, overrides, time [s], what the sample is)
    ("pyramid4", {}, 0.35, "support, speeding up"),
    ("pyramid4", {}, 2.25, "support, cruise"),
    ("pyramid4", {}, 1.6999999998999988, "support, the left limit of a lift-off and touchdown"),
    ("pyramid4", {}, 1.7104615489399955, "support, the end of a touchdown transient"),
    ("pyramid8", {}, 0.35, "support, speeding up"),
    ("cone", {}, 0.35, "support, speeding up"),
    ("cone", {}, 2.25, "support, cruise"),
    ("pyramid4", FAST, 1.0, "support, mu* above the scene's 0.3 (the allocation relaxed)"),
    ("pyramid4", FAST, 1.0705678994404955, "support, the largest mu* of the run"),
    ("pyramid8", FAST, 1.0, "support"),
    ("cone", FAST, 1.0, "support"),
    ("cone", FAST, 2.575, "support"),
    ("pyramid4", FAST, 0.6479761648517712, "two legs in their touchdown transient"),
    ("cone", FAST, 0.6479761648517712, "two legs in their touchdown transient"),
]
# (d): a balanced trot's two feet (times of its grid where mu* is far below the friction its
# allocation uses, 0.26-0.31).
TROT_SAMPLES = [
    ("pyramid8", 6.09),
    ("pyramid4", 3.36),
    ("pyramid8", 2.36),
    ("cone", 4.36),
]
# (e): touchdown transients where no mu holds the trunk rows.
NAN_SAMPLES = [
    ("pyramid4", {}, 1.7000286569047833),
    ("cone", {}, 1.7000286569047833),
]


def main():
    mus = []
    for model, overrides, t, _ in SAMPLES:
        mus.append(compare(model, overrides, t)["required_friction"])
    assert all(math.isfinite(m) for m in mus), mus
    assert max(mus) > 0.5, f"every mu* is small: {mus}"
    for model, t in TROT_SAMPLES:
        p = compare(model, {}, t, TROT)
        stance = [leg["count"] for leg in p["legs"] if leg["count"]]
        assert stance == [3, 3], f"trot at t = {t!r} s: legs with forces {stance}, expected two"
        assert np.linalg.matrix_rank(p["C"][:6]) == 5, f"trot at t = {t!r} s: trunk rows' rank"
        if not p["cones"]:  # the rows as planned hold at no mu: the case this guards
            assert not lp_feasible(p, MU_MAX), f"trot at t = {t!r} s: rows hold as planned"
        assert math.isfinite(p["required_friction"]), f"trot at t = {t!r} s"
    for model, overrides, t in NAN_SAMPLES:
        p = compare(model, overrides, t)
        where = describe(model, overrides, t, p)
        assert 1 in p["phase"] and p["status"] == 1, f"{where}: not a relaxed touchdown transient"
        assert math.isnan(p["required_friction"]), where
    assert not FAILURES, "required friction off its second computation:\n  " + \
        "\n  ".join(FAILURES)
    print("ok")


if __name__ == "__main__":
    main()
