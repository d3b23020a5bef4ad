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

}  // namespace

Vec2 chebyshev_value(const std::vector<Vec2>& c, double y) {
  Vec2 b1 = Vec2::Zero(), b2 = Vec2::Zero();
  for (int j = static_cast<int>(c.size()) - 1; j >= 1; --j) {
    const Vec2 b0 = 2.0 * y * b1 - b2 + c[j];
    b2 = b1;
    b1 = b0;
  }
  return c.empty() ? Vec2::Zero() : Vec2(y * b1 - b2 + c[0]);
}

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
  for (int k = 0; k < K; ++k) {  // ζ forward from ζ(0) = 0
    const OffsetPiece& p = pieces_[k];
    const double decay = std::exp(-omega_ * (p.t1_s - p.t0_s));
    zeta_[k + 1] =
        decay * zeta_[k] + decaying_integral(p, omega_, p.t0_s, p.t1_s, Decay::kFromUpper);
  }
  for (int k = K - 1; k >= 0; --k) {  // ξ backward from ξ(T) = 0
    const OffsetPiece& p = pieces_[k];
    const double decay = std::exp(-omega_ * (p.t1_s - p.t0_s));
    xi_[k] = decay * xi_[k + 1] + decaying_integral(p, omega_, p.t0_s, p.t1_s, Decay::kFromLower);
  }
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
  const Vec2 xi = std::exp(-omega_ * (p.t1_s - t)) * xi_[k + 1] +
                  decaying_integral(p, omega_, t, p.t1_s, Decay::kFromLower);
  const Vec2 zeta = std::exp(-omega_ * (t - p.t0_s)) * zeta_[k] +
                    decaying_integral(p, omega_, p.t0_s, t, Decay::kFromUpper);
  s.e = 0.5 * (xi + zeta);
  s.ed = 0.5 * omega_ * (xi - zeta);
  s.edd = omega_ * omega_ * (s.e - piece_forcing(p, (t - p.t0_s) / (p.t1_s - p.t0_s)));
  return s;
}

}  // namespace hexdyn
