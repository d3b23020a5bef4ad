"""Energies recomputed from a result's stored series by the rule its /meta energy_rule names
(docs/theory/output-grid.md#energy-from-the-samples): a computation of its own, with numpy,
that a reader uses to check or share out the stored totals."""
import numpy as np

from .schema import SCHEMA

ENERGY_RULE_CUBIC = SCHEMA["kEnergyRuleCubic"]
ENERGY_RULE_TRAPEZOID = SCHEMA["kEnergyRuleTrapezoid"]


def _abs_polynomial_integrals(c):
    """∫_0^1 |Σ_i c[..., i] u^i| du for polynomial coefficients c (..., n), lowest first: where
    the polynomial keeps its sign at 33 points of [0, 1] the signed integral, elsewhere split at
    its real roots in (0, 1) (numpy.roots)."""
    n = c.shape[-1]
    u = np.linspace(0.0, 1.0, 33)
    values = np.einsum("...i,ui->...u", c, u[:, None] ** np.arange(n))
    signed = np.sum(c / np.arange(1, n + 1), axis=-1)
    out = np.abs(signed)
    mixed = (values.min(axis=-1) < 0) & (values.max(axis=-1) > 0)
    for index in zip(*np.nonzero(mixed)):
        coef = c[index]
        roots = np.roots(coef[::-1]) if np.any(coef[1:]) else np.array([])
        cuts = np.sort([r.real for r in roots if abs(r.imag) < 1e-12 and 0 < r.real < 1])
        points = np.r_[0.0, cuts, 1.0]
        anti = np.r_[0.0, coef / np.arange(1, n + 1)]  # antiderivative coefficients
        prim = np.polynomial.polynomial.polyval(points, anti)
        out[index] = np.sum(np.abs(np.diff(prim)))
    return out


def energy_by_rule(time, power, sample_kind, rule=ENERGY_RULE_CUBIC, per_interval=False):
    """The energies (per column of `power`, J) recomputed from /time (T), /power/per_joint
    (T×J, signed) and /sample_kind (T) by the rule /meta energy_rule names (schema.hpp
    kEnergyRuleCubic, docs/theory/output-grid.md#energy-from-the-samples): per piece between a
    left-limit sample (kind 1) and its event, each interval integrates |p| of the polynomial
    interpolating the 4 samples nearest it in the piece (3 on a piece of 2 intervals, 2 on one
    of 1), a left limit's interval the trapezoid; or the trapezoid of |power|. /energy/total is
    their sum. A computation of its own (Vandermonde systems, numpy.roots), not the writer's.
    With per_interval, the integral over each interval instead ((T − 1)×J): they add up to the
    energies, so that a share of the energy (over some of the intervals) is by the same rule."""
    t = np.asarray(time, dtype=float)
    P = np.asarray(power, dtype=float).reshape(len(t), -1)
    h = np.diff(t)
    A = np.abs(P)
    trapezoid = 0.5 * h[:, None] * (A[1:] + A[:-1])
    if rule == ENERGY_RULE_TRAPEZOID:
        return trapezoid if per_interval else trapezoid.sum(axis=0)
    if rule != ENERGY_RULE_CUBIC:
        raise ValueError(f"unknown energy rule {rule!r}")
    kind = np.zeros(len(t), dtype=int) if sample_kind is None else np.asarray(sample_kind)
    ends = [int(k) for k in np.nonzero(kind[:-1] == 1)[0]] + [len(t) - 1]
    interval = np.zeros_like(trapezoid)
    s = 0
    for e in ends:
        if e < len(t) - 1:
            interval[e] = trapezoid[e]  # the left limit's interval
        n = e - s
        if n >= 1:
            k = np.arange(s, e)
            width = min(n + 1, 4)
            first = np.clip(k - 1, s, e + 1 - width) if n >= 3 else np.full(n, s)
            idx = first[:, None] + np.arange(width)
            u = (t[idx] - t[k][:, None]) / h[k][:, None]
            V = u[:, :, None] ** np.arange(width)
            coef = np.linalg.solve(V, P[idx])  # (n, width, J)
            interval[k] = h[k][:, None] * _abs_polynomial_integrals(np.moveaxis(coef, 1, 2))
        s = e + 1
    return interval if per_interval else interval.sum(axis=0)
