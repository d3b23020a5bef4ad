// The balanced trunk's offset (planning/trunk_offset.hpp, docs/theory/balance.md#the-offset):
// on random pieces, e(t) against a fourth-order Runge–Kutta integration of ë = ω² (e − u) started
// from the offset's own state at the start of a piece (an independent solution of the same
// equation, its error O(h⁴)), ė and ë against central differences of e and ė, continuity across
// breakpoints, and rest at both ends when the forcing meets the two conditions of the file
// comment (here: a forcing whose conditions hold by construction, the derivative of a pendulum
// path that starts and ends at rest), and against GSL's adaptive quadrature of the two integrals
// that define ξ and ζ over the whole run (no sweep, no series), for pieces from very short to
// several pendulum time constants long.
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "hexdyn/planning/trunk_offset.hpp"

namespace hexdyn {
namespace {

/// Random pieces on [0, T]: waypoints and Chebyshev coefficients of a few centimetres.
std::vector<OffsetPiece> random_pieces(std::mt19937& rng, int K) {
  std::uniform_real_distribution<double> len(0.02, 0.06), val(-0.03, 0.03);
  std::vector<OffsetPiece> p(K);
  double t = 0.0;
  Vec2 w(val(rng), val(rng));
  for (int k = 0; k < K; ++k) {
    p[k].t0_s = t;
    t += len(rng);
    p[k].t1_s = t;
    p[k].w0 = w;
    w = Vec2(val(rng), val(rng));
    p[k].w1 = w;
    for (int j = 0; j < 6; ++j) p[k].r_cheb.push_back(Vec2(val(rng), val(rng)) / (1.0 + j * j));
  }
  // Continuous forcing: each piece's r at its start equals the previous piece's at its end.
  for (int k = 1; k < K; ++k) {
    const Vec2 jump = chebyshev_value(p[k].r_cheb, -1.0) - chebyshev_value(p[k - 1].r_cheb, 1.0);
    p[k].r_cheb[0] -= jump;
  }
  return p;
}

TEST_CASE("trunk offset: e solves e − ë/ω² = u, as a Runge–Kutta integration does",
          "[balance][offset]") {
  std::mt19937 rng(4401u);
  const double omega = 7.3;
  const TrunkOffset off(omega, random_pieces(rng, 30));
  double worst = 0.0;
  for (int k : {0, 7, 18, 29}) {
    const OffsetPiece& p = off.pieces()[k];
    OffsetState s = off.at(p.t0_s);
    Vec2 e = s.e, v = s.ed;
    const int steps = 400;
    const double h = (p.t1_s - p.t0_s) / steps;
    const auto acc = [&](double t, const Vec2& x) {
      return Vec2(omega * omega * (x - piece_forcing(p, (t - p.t0_s) / (p.t1_s - p.t0_s))));
    };
    for (int i = 0; i < steps; ++i) {
      const double t = p.t0_s + i * h;
      const Vec2 k1x = v, k1v = acc(t, e);
      const Vec2 k2x = v + 0.5 * h * k1v, k2v = acc(t + 0.5 * h, e + 0.5 * h * k1x);
      const Vec2 k3x = v + 0.5 * h * k2v, k3v = acc(t + 0.5 * h, e + 0.5 * h * k2x);
      const Vec2 k4x = v + h * k3v, k4v = acc(t + h, e + h * k3x);
      e += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
      v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    }
    const OffsetState end = off.at(p.t1_s);
    worst = std::max({worst, (end.e - e).norm(), (end.ed - v).norm() / omega});
  }
  INFO("largest difference from RK4 " << worst << " m");
  CHECK(worst < 1e-12);
  // And the identity itself, with ë from e's own differences.
  const double h = 1e-5;
  for (double t : {0.11, 0.37, 0.62, 0.91}) {
    const OffsetState a = off.at(t - h), b = off.at(t), c = off.at(t + h);
    CHECK((b.ed - (c.e - a.e) / (2.0 * h)).norm() < 1e-7);
    CHECK((b.edd - (c.ed - a.ed) / (2.0 * h)).norm() < 1e-5);
    CHECK((b.e - b.edd / (omega * omega) - off.forcing(t)).norm() < 1e-14);
  }
}

TEST_CASE("trunk offset: e and ė continuous across breakpoints", "[balance][offset]") {
  std::mt19937 rng(4402u);
  const TrunkOffset off(5.1, random_pieces(rng, 20));
  for (std::size_t k = 1; k < off.pieces().size(); ++k) {
    const double t = off.pieces()[k].t0_s;
    const OffsetState left = off.at(std::nextafter(t, 0.0)), right = off.at(t);
    CHECK((left.e - right.e).norm() < 1e-14);
    CHECK((left.ed - right.ed).norm() < 1e-12);
  }
}

TEST_CASE("trunk offset: at rest at both ends when the forcing is a pendulum path's",
          "[balance][offset]") {
  // e*(t) = A sin⁴(π t / T): a path at rest at 0 and T (e, ė, ë zero); its forcing
  // u = e* − ë*/ω² as one Chebyshev series per piece (fitted at many nodes) makes both
  // conditions hold, and the offset must give e* back.
  const double omega = 6.0, T = 1.2;
  const auto path = [&](double t) {
    const double s = std::sin(M_PI * t / T);
    return Vec2(Vec2(0.04, -0.02) * (s * s * s * s));
  };
  const auto path_dd = [&](double t) {
    const double a = M_PI / T, s = std::sin(a * t), c = std::cos(a * t);
    return Vec2(Vec2(0.04, -0.02) * (a * a * (12.0 * s * s * c * c - 4.0 * s * s * s * s)));
  };
  const int K = 24, N = 24;
  std::vector<OffsetPiece> pieces(K);
  for (int k = 0; k < K; ++k) {
    OffsetPiece& p = pieces[k];
    p.t0_s = T * k / K;
    p.t1_s = T * (k + 1) / K;
    // r = −u on the piece (w = 0): Chebyshev coefficients from N + 1 Lobatto nodes.
    std::vector<Vec2> f(N + 1);
    for (int j = 0; j <= N; ++j) {
      const double t = p.t0_s + 0.5 * (1.0 + std::cos(M_PI * j / N)) * (p.t1_s - p.t0_s);
      f[j] = -(path(t) - path_dd(t) / (omega * omega));
    }
    p.r_cheb.assign(N + 1, Vec2::Zero());
    for (int m = 0; m <= N; ++m) {
      for (int j = 0; j <= N; ++j)
        p.r_cheb[m] += ((j == 0 || j == N) ? 0.5 : 1.0) * f[j] * std::cos(M_PI * m * j / N);
      p.r_cheb[m] *= 2.0 / N;
    }
    p.r_cheb[0] *= 0.5;
    p.r_cheb[N] *= 0.5;
  }
  // The fitted forcing is the path's.
  for (const OffsetPiece& p : pieces)
    for (double x : {0.0, 0.3, 0.77, 1.0}) {
      const double t = p.t0_s + x * (p.t1_s - p.t0_s);
      CHECK((piece_forcing(p, x) - (path(t) - path_dd(t) / (omega * omega))).norm() < 1e-14);
    }
  const TrunkOffset off(omega, pieces);
  for (double t : {0.0, 0.05, 0.3, 0.6, 0.95, T}) {
    const OffsetState s = off.at(t);
    INFO("t " << t);
    CHECK((s.e - path(t)).norm() < 1e-12);
  }
  CHECK(off.at(0.0).ed.norm() < 1e-12);
  CHECK(off.at(T).ed.norm() < 1e-12);
}

/// ξ(t) = ω ∫_t^T e^{−ω(σ − t)} u(σ) dσ and ζ(t) = ω ∫_0^t e^{−ω(t − σ)} u(σ) dσ of one axis by
/// GSL's adaptive Gauss–Kronrod rule (QAG, 61 points), piece by piece (u is smooth on each).
struct Integrand {
  const std::vector<OffsetPiece>* pieces;
  double omega, t;
  int k, axis;
  bool forward;  // ζ's weight e^{−ω(t − σ)}, else ξ's e^{−ω(σ − t)}
};

double integrand(double sigma, void* data) {
  const auto& d = *static_cast<const Integrand*>(data);
  const OffsetPiece& p = (*d.pieces)[d.k];
  const double u = piece_forcing(p, (sigma - p.t0_s) / (p.t1_s - p.t0_s))[d.axis];
  return d.omega * std::exp(-d.omega * (d.forward ? d.t - sigma : sigma - d.t)) * u;
}

double gsl_component(const std::vector<OffsetPiece>& pieces, double omega, double t, int axis,
                     bool forward, gsl_integration_workspace* ws) {
  double total = 0.0;
  for (int k = 0; k < static_cast<int>(pieces.size()); ++k) {
    const double lo = forward ? pieces[k].t0_s : std::max(pieces[k].t0_s, t);
    const double hi = forward ? std::min(pieces[k].t1_s, t) : pieces[k].t1_s;
    if (hi <= lo) continue;
    Integrand d{&pieces, omega, t, k, axis, forward};
    gsl_function f{&integrand, &d};
    double value = 0.0, error = 0.0;
    REQUIRE(gsl_integration_qag(&f, lo, hi, 1e-16, 1e-13, 1000, GSL_INTEG_GAUSS61, ws, &value,
                                &error) == GSL_SUCCESS);
    total += value;
  }
  return total;
}

TEST_CASE("trunk offset: e and ė equal GSL's adaptive quadrature of their integrals",
          "[balance][offset]") {
  gsl_set_error_handler_off();
  gsl_integration_workspace* ws = gsl_integration_workspace_alloc(1000);
  std::mt19937 rng(4403u);
  // ω (t_{k+1} − t_k) / 2 from about 0.002 to 3 over the cases: a few short pieces, the
  // balanced trunk's (0.02–0.06 s at 4–9 rad/s), long ones.
  for (const auto& [omega, stretch] :
       {std::pair{7.3, 1.0}, std::pair{4.4, 1.0}, std::pair{0.2, 1.0}, std::pair{9.0, 12.0}}) {
    std::vector<OffsetPiece> pieces = random_pieces(rng, 12);
    for (OffsetPiece& p : pieces) {
      p.t0_s *= stretch;
      p.t1_s *= stretch;
    }
    const TrunkOffset off(omega, pieces);
    std::vector<double> times;
    for (const OffsetPiece& p : pieces)
      for (double x : {0.0, 0.13, 0.5, 0.86, 1.0}) times.push_back(p.t0_s + x * (p.t1_s - p.t0_s));
    double e_scale = 0.0, ed_scale = 0.0, e_err = 0.0, ed_err = 0.0;
    for (double t : times) {
      const OffsetState s = off.at(t);
      for (int axis = 0; axis < 2; ++axis) {
        const double xi = gsl_component(pieces, omega, t, axis, false, ws);
        const double zeta = gsl_component(pieces, omega, t, axis, true, ws);
        e_scale = std::max(e_scale, std::abs(0.5 * (xi + zeta)));
        ed_scale = std::max(ed_scale, std::abs(0.5 * omega * (xi - zeta)));
        e_err = std::max(e_err, std::abs(s.e[axis] - 0.5 * (xi + zeta)));
        ed_err = std::max(ed_err, std::abs(s.ed[axis] - 0.5 * omega * (xi - zeta)));
      }
    }
    INFO("omega " << omega << ", pieces x" << stretch << ": |e| up to " << e_scale << " m, error "
                  << e_err << " m; |ė| up to " << ed_scale << " m/s, error " << ed_err << " m/s");
    CHECK(e_err < 1e-12 * e_scale);
    CHECK(ed_err < 1e-12 * ed_scale);
  }
  gsl_integration_workspace_free(ws);
}

}  // namespace
}  // namespace hexdyn
