#include "hexdyn/planning/trunk_offset.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace hexdyn {
namespace {

/// 16-point Gauss–Legendre nodes (the positive half) and weights on [−1, 1], as
/// numpy.polynomial.legendre.leggauss(16) gives them: exact for polynomials of degree 31, and
/// to rounding for a piece's forcing (a polynomial of modest degree) times an exponential whose
/// exponent stays within a few units.
constexpr std::array<double, 8> kGaussX = {
    0.09501250983763745, 0.2816035507792589, 0.45801677765722737, 0.6178762444026438,
    0.755404408355003,   0.8656312023878318, 0.9445750230732326,  0.9894009349916499};
constexpr std::array<double, 8> kGaussW = {
    0.18945061045506859, 0.1826034150449236,  0.16915651939500262,  0.14959598881657676,
    0.12462897125553403, 0.09515851168249259, 0.062253523938647706, 0.027152459411754037};

using Vec4 = Eigen::Vector4d;

/// The forcing's Chebyshev coefficients in y = 2x − 1 (at least two: u is at least linear).
std::vector<Vec2> forcing_series(const OffsetPiece& p) {
  std::vector<Vec2> u(std::max<std::size_t>(2, p.r_cheb.size()), Vec2::Zero());
  for (std::size_t j = 0; j < p.r_cheb.size(); ++j) u[j] = -p.r_cheb[j];
  u[0] += 0.5 * (p.w0 + p.w1);
  u[1] += 0.5 * (p.w1 - p.w0);
  return u;
}

/// Terms past the forcing's degree after which the series' coefficients, falling as
/// (a/2)^m / m!, are below rounding (trunk_offset.hpp).
int extra_terms(double a) {
  constexpr int kLeast = 8, kMost = 400;
  double term = 1.0;
  int m = 0;
  while ((m < kLeast || term > 1e-20) && m < kMost) {
    ++m;
    term *= 0.5 * a / m;
  }
  return m;
}

/// One piece's system (trunk_offset.hpp) solved for ξ(y) and, with u mirrored (y → −y), for
/// ζ(−y), whose equation is ξ's: the coefficients X_j = P_j + X_0 Q_j, j ≥ 1, from the rows
/// j = 1 … M (X_{M+1} = 0); P holds ξ's particular part in its first two entries and ζ(−y)'s in
/// its last two; Q, the homogeneous part, is the same for both. X_0 follows from the end value
/// (TrunkOffset's sweeps), and the sums give the series' values at y = ±1.
struct PieceSystem {
  std::vector<Vec4> p;                              ///< P_0 … P_M (P_0 = 0)
  std::vector<double> q;                            ///< Q_0 … Q_M (Q_0 = 0)
  Vec4 p_sum = Vec4::Zero(), p_alt = Vec4::Zero();  ///< Σ_{j≥1} P_j and Σ_{j≥1} (−1)^j P_j
  double q_sum = 0.0, q_alt = 0.0;                  ///< the same of Q
  /// X_0 from X(1) = Σ X_j = end; then X(−1). `half` 0: ξ's, 2: ζ(−y)'s.
  Vec2 first(const Vec2& end, int half) const {
    return (end - p_sum.segment<2>(half)) / (1.0 + q_sum);
  }
  Vec2 value_at_start(const Vec2& x0, int half) const {
    return x0 * (1.0 + q_alt) + p_alt.segment<2>(half);
  }
};

/// The rows −a c_{j−1} X_{j−1} + 2j X_j + a X_{j+1} = a (u_{j+1} − c_{j−1} u_{j−1}) by the
/// Thomas algorithm (diagonally dominant for a < 2), row 1's −2a X_0 giving Q.
PieceSystem solve_piece(const OffsetPiece& piece, double omega) {
  const double a = 0.5 * omega * (piece.t1_s - piece.t0_s);
  const std::vector<Vec2> u = forcing_series(piece);
  const int n = static_cast<int>(u.size()) - 1, M = n + extra_terms(a);
  const auto U = [&](int j) {  // u_j of ξ's forcing and of ζ(−y)'s
    if (j > n) return Vec4(Vec4::Zero());
    return Vec4(u[j].x(), u[j].y(), j % 2 ? -u[j].x() : u[j].x(), j % 2 ? -u[j].y() : u[j].y());
  };
  PieceSystem S;
  S.p.assign(M + 1, Vec4::Zero());
  S.q.assign(M + 1, 0.0);
  std::vector<double> c(M + 1, 0.0);
  for (int j = 1; j <= M; ++j) {  // forward elimination
    const double m = 2.0 * j + (j > 1 ? a * c[j - 1] : 0.0);
    c[j] = a / m;
    S.p[j] = (a * (U(j + 1) - (j == 1 ? 2.0 : 1.0) * U(j - 1)) + a * S.p[j - 1]) / m;
    S.q[j] = ((j == 1 ? 2.0 * a : 0.0) + a * S.q[j - 1]) / m;
  }
  for (int j = M - 1; j >= 1; --j) {  // back substitution
    S.p[j] -= c[j] * S.p[j + 1];
    S.q[j] -= c[j] * S.q[j + 1];
  }
  for (int j = M; j >= 1; --j) {
    const double sign = j % 2 ? -1.0 : 1.0;
    S.p_sum += S.p[j];
    S.p_alt += sign * S.p[j];
    S.q_sum += S.q[j];
    S.q_alt += sign * S.q[j];
  }
  return S;
}

/// The coefficients of (e, ė) of a piece from its system and X_0 of ξ(y) and of ζ(−y):
/// e = (ξ + ζ)/2, ė = ω (ξ − ζ)/2, ζ_j = (−1)^j ζ(−y)_j. Reuses the system's storage.
std::vector<Vec4> offset_series(PieceSystem&& S, const Vec2& xi0, const Vec2& zeta0, double omega) {
  std::vector<Vec4> s = std::move(S.p);
  for (std::size_t j = 0; j < s.size(); ++j) {
    const Vec2 xi = s[j].head<2>() + S.q[j] * xi0, zm = s[j].tail<2>() + S.q[j] * zeta0;
    const Vec2 zeta = j % 2 ? Vec2(-zm) : zm;
    s[j] << 0.5 * (xi + zeta), 0.5 * omega * (xi - zeta);
  }
  s[0] << 0.5 * (xi0 + zeta0), 0.5 * omega * (xi0 - zeta0);
  return s;
}

/// Σ c_j T_j(y) (Clenshaw), for vectors of any fixed size.
template <class V>
V clenshaw(const std::vector<V>& c, double y) {
  V b1 = V::Zero(), b2 = V::Zero();
  for (int j = static_cast<int>(c.size()) - 1; j >= 1; --j) {
    const V b0 = 2.0 * y * b1 - b2 + c[j];
    b2 = b1;
    b1 = b0;
  }
  return c.empty() ? V(V::Zero()) : V(y * b1 - b2 + c[0]);
}

}  // namespace

Vec2 chebyshev_value(const std::vector<Vec2>& c, double y) { return clenshaw(c, y); }

Vec2 piece_forcing(const OffsetPiece& piece, double x) {
  return piece.w0 + (piece.w1 - piece.w0) * x - chebyshev_value(piece.r_cheb, 2.0 * x - 1.0);
}

Vec2 decaying_integral(const OffsetPiece& piece, double omega, double a_s, double b_s,
                       Decay decay) {
  const double half = 0.5 * (b_s - a_s);
  if (half <= 0.0) return Vec2::Zero();
  const double mid = 0.5 * (a_s + b_s), span = piece.t1_s - piece.t0_s;
  Vec2 sum = Vec2::Zero();
  for (std::size_t i = 0; i < kGaussX.size(); ++i) {
    for (const double sign : {-1.0, 1.0}) {
      const double s = mid + sign * half * kGaussX[i];
      const double from = decay == Decay::kFromLower ? s - a_s : b_s - s;
      sum += kGaussW[i] * std::exp(-omega * from) * piece_forcing(piece, (s - piece.t0_s) / span);
    }
  }
  return omega * half * sum;
}

TrunkOffset::TrunkOffset(double omega_radps, std::vector<OffsetPiece> pieces)
    : omega_(omega_radps), pieces_(std::move(pieces)) {
  if (!(omega_ > 0.0)) throw std::invalid_argument("trunk offset: omega must be positive");
  const int K = static_cast<int>(pieces_.size());
  xi_.assign(K + 1, Vec2::Zero());
  zeta_.assign(K + 1, Vec2::Zero());
  std::vector<PieceSystem> system;
  system.reserve(K);
  for (const OffsetPiece& p : pieces_) system.push_back(solve_piece(p, omega_));
  std::vector<Vec2> xi0(K), zeta0(K);  // X_0 of ξ(y) and of ζ(−y) per piece
  for (int k = 0; k < K; ++k) {        // ζ forward from ζ(0) = 0
    zeta0[k] = system[k].first(zeta_[k], 2);
    zeta_[k + 1] = system[k].value_at_start(zeta0[k], 2);
  }
  for (int k = K - 1; k >= 0; --k) {  // ξ backward from ξ(T) = 0
    xi0[k] = system[k].first(xi_[k + 1], 0);
    xi_[k] = system[k].value_at_start(xi0[k], 0);
  }
  series_.reserve(K);
  for (int k = 0; k < K; ++k)
    series_.push_back(offset_series(std::move(system[k]), xi0[k], zeta0[k], omega_));
}

int TrunkOffset::piece_at(double t) const {
  if (pieces_.empty() || t < 0.0 || t > pieces_.back().t1_s) return -1;
  const auto it = std::upper_bound(pieces_.begin(), pieces_.end(), t,
                                   [](double v, const OffsetPiece& p) { return v < p.t1_s; });
  return it == pieces_.end() ? static_cast<int>(pieces_.size()) - 1
                             : static_cast<int>(it - pieces_.begin());
}

Vec2 TrunkOffset::forcing(double t) const {
  const int k = piece_at(t);
  if (k < 0) return Vec2::Zero();
  const OffsetPiece& p = pieces_[k];
  return piece_forcing(p, (t - p.t0_s) / (p.t1_s - p.t0_s));
}

OffsetState TrunkOffset::at(double t) const {
  OffsetState s;
  const int k = piece_at(t);
  if (k < 0) return s;
  const OffsetPiece& p = pieces_[k];
  const double x = (t - p.t0_s) / (p.t1_s - p.t0_s);
  const Vec4 v = clenshaw(series_[k], 2.0 * x - 1.0);
  s.e = v.head<2>();
  s.ed = v.tail<2>();
  s.edd = omega_ * omega_ * (s.e - piece_forcing(p, x));
  return s;
}

}  // namespace hexdyn
