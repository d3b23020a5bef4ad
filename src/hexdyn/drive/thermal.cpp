#include "hexdyn/drive/thermal.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace hexdyn {
namespace {

/// (e^x − 1) / x, 1 at 0.
double phi1(double x) { return x == 0.0 ? 1.0 : std::expm1(x) / x; }

/// (e^x − 1 − x) / x², by its series Σ xⁿ / (n + 2)! where the closed form cancels.
double phi2(double x) {
  if (std::abs(x) > 0.1) return (std::expm1(x) - x) / (x * x);
  double term = 0.5, sum = 0.0;
  for (int n = 0; n < 24 && term != 0.0; ++n) {
    sum += term;
    term *= x / (n + 3);
  }
  return sum;
}

/// The rise over ambient x = (T_w − T_a, T_h − T_a) in the modal coordinates z of
/// dx/dt = A x + B P: A = V Λ V⁻¹ with real eigenvalues λ₀ < λ₁ < 0 (an RC network's), the
/// eigenvectors (A₀₁, λᵢ − A₀₀), and each mode zᵢ' = λᵢ zᵢ + gᵢ P, g = V⁻¹ B.
class TwoNode {
 public:
  explicit TwoNode(const ThermalParams& p) {
    a_ = -1.0 / (p.winding_housing_KpW * p.winding_capacity_JpK);
    b_ = 1.0 / (p.winding_housing_KpW * p.winding_capacity_JpK);
    const double c = 1.0 / (p.winding_housing_KpW * p.housing_capacity_JpK);
    const double d = -c - 1.0 / (p.housing_ambient_KpW * p.housing_capacity_JpK);
    const double disc = std::sqrt(0.25 * (a_ - d) * (a_ - d) + b_ * c);
    lambda_[0] = 0.5 * (a_ + d) - disc;
    lambda_[1] = (a_ * d - b_ * c) / lambda_[0];  // the product of the eigenvalues is det A
    e_[0] = lambda_[0] - a_;
    e_[1] = lambda_[1] - a_;
    const double det_v = b_ * (e_[1] - e_[0]);
    g_[0] = e_[1] / (p.winding_capacity_JpK * det_v);
    g_[1] = -e_[0] / (p.winding_capacity_JpK * det_v);
  }

  using Modes = std::array<double, 2>;

  /// The modes s after z, the loss p0 + slope·u over u ∈ [0, s].
  Modes advance(const Modes& z, double p0, double slope, double s) const {
    Modes out{};
    for (int i = 0; i < 2; ++i) {
      const double x = lambda_[i] * s;
      out[i] = std::exp(x) * z[i] + g_[i] * (p0 * s * phi1(x) + slope * s * s * phi2(x));
    }
    return out;
  }
  /// d/ds of the winding's rise at z, under the loss p.
  double winding_rate(const Modes& z, double p) const {
    return b_ * (lambda_[0] * z[0] + g_[0] * p + lambda_[1] * z[1] + g_[1] * p);
  }
  double winding(const Modes& z) const { return b_ * (z[0] + z[1]); }
  double housing(const Modes& z) const { return e_[0] * z[0] + e_[1] * z[1]; }

 private:
  double a_ = 0.0, b_ = 0.0;
  Modes lambda_{}, e_{}, g_{};
};

/// The u ∈ [lo, hi] where f changes sign, f(lo) < 0 ≤ f(hi), to the doubles' resolution.
template <class F>
double bisect(const F& f, double lo, double hi) {
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    (f(mid) < 0.0 ? lo : hi) = mid;
  }
  return hi;
}

}  // namespace

ThermalTrace simulate_thermal(const ThermalParams& p, const std::vector<double>& t,
                              const double* loss, int stride) {
  const TwoNode model(p);
  const std::size_t n = t.size();
  const double ambient = p.ambient_degC, limit = p.limit_degC - p.ambient_degC;
  ThermalTrace out;
  out.winding_degC.assign(n, ambient);
  out.housing_degC.assign(n, ambient);
  out.peak_winding_degC = ambient;
  if (limit <= 0.0) {
    out.time_to_limit_s = n ? t.front() : 0.0;
    out.reached = true;
  }
  TwoNode::Modes z{0.0, 0.0};
  for (std::size_t k = 1; k < n; ++k) {
    const double h = t[k] - t[k - 1];
    const double p0 = loss[(k - 1) * stride], p1 = loss[k * stride];
    if (!(h > 0.0)) continue;  // a left limit at the same time: no time passes
    const double slope = (p1 - p0) / h;
    const auto at = [&](double s) { return model.advance(z, p0, slope, s); };
    const TwoNode::Modes next = at(h);
    // The interval's largest rise: at its end, or where the rise's rate falls through zero.
    double top_s = h, top = model.winding(next);
    const double r0 = model.winding_rate(z, p0), r1 = model.winding_rate(next, p1);
    if (r0 > 0.0 && r1 < 0.0) {
      const double s =
          bisect([&](double u) { return -model.winding_rate(at(u), p0 + slope * u); }, 0.0, h);
      const double w = model.winding(at(s));
      if (w > top) top_s = s, top = w;
    }
    out.peak_winding_degC = std::max(out.peak_winding_degC, ambient + top);
    if (!out.reached && top >= limit) {
      const double s = bisect([&](double u) { return model.winding(at(u)) - limit; }, 0.0, top_s);
      out.time_to_limit_s = t[k - 1] + s;
      out.reached = true;
    }
    z = next;
    out.winding_degC[k] = ambient + model.winding(z);
    out.housing_degC[k] = ambient + model.housing(z);
  }
  return out;
}

}  // namespace hexdyn
