// describe_violations (allocation/qp.hpp) against a second computation written here the
// plain way: each row's residual by Eigen's row dot product, every violated row's number
// printed by snprintf's %.3g. On random problems shaped like the allocation's (exact zeros,
// equal, one-sided and missing bounds, cones, unnamed rows), the text and the largest
// violation must be the same bit for bit, with one workspace reused across problems of
// changing sizes.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "hexdyn/allocation/qp.hpp"

namespace hexdyn {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The violations of x, row by row (A.row(i).dot(x)), largest first, as "name by %.3g".
std::string plain_violations(const QpProblem& p, const Eigen::VectorXd& x, double tol,
                             double& worst) {
  std::vector<std::pair<double, std::string>> list;
  worst = 0.0;
  auto consider = [&](double violation, double bound, const std::string& name) {
    if (violation > 0.0 || std::isnan(violation)) {
      const double v = std::isfinite(violation) ? violation : kInf;
      worst = std::max(worst, v);
      if (!(v <= tol * std::max(1.0, std::abs(bound)))) list.emplace_back(v, name);
    }
  };
  for (int i = 0; i < p.equalities(); ++i)
    consider(std::abs(p.A.row(i).dot(x) - p.b[i]), p.b[i], p.eq_name(i));
  for (int i = 0; i < p.inequalities(); ++i) {
    const double c = p.C.row(i).dot(x);
    const bool lower = p.lower[i] > -kQpInfinity, upper = p.upper[i] < kQpInfinity;
    const double below = lower ? p.lower[i] - c : -1.0;
    const double above = upper ? c - p.upper[i] : -1.0;
    if (below >= above && lower)
      consider(below, p.lower[i], p.ineq_name(i));
    else if (upper)
      consider(above, p.upper[i], p.ineq_name(i));
  }
  for (std::size_t k = 0; k < p.cones.size(); ++k) {
    const SecondOrderCone& c = p.cones[k];
    const double bound = c.mu * x[c.normal];
    consider(std::hypot(x[c.tangent1], x[c.tangent2]) - bound, bound,
             c.name.empty() ? "cone[" + std::to_string(k) + "]" : c.name);
  }
  std::stable_sort(list.begin(), list.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::string text;
  for (const auto& [v, name] : list) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    text += (text.empty() ? "" : ", ") + name + " by " + buf;
  }
  return text;
}

/// A random problem of n variables: entries of every scale, a third of them exact zeros;
/// rows with both bounds, one, none, or lower = upper; some rows and cones unnamed.
QpProblem random_problem(std::mt19937& rng, int n) {
  std::uniform_int_distribution<int> m_eq_d(0, 4), m_in_d(0, 60), pick(0, 5);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(-4.0, 4.0);
  const auto value = [&] { return pick(rng) < 2 ? 0.0 : u(rng) * std::pow(10.0, e(rng)); };
  QpProblem p;
  const int m_eq = n > 0 ? m_eq_d(rng) : 0;
  p.resize(n, m_eq, m_in_d(rng));
  for (int i = 0; i < p.A.size(); ++i) p.A.data()[i] = value();
  for (int i = 0; i < p.C.size(); ++i) p.C.data()[i] = value();
  for (int i = 0; i < m_eq; ++i) {
    p.b[i] = value();
    if (pick(rng) < 3) p.eq_names[i] = "trunk row " + std::to_string(i);
  }
  for (int i = 0; i < p.inequalities(); ++i) {
    const double a = value(), b = a + std::abs(value());
    switch (pick(rng)) {
      case 0:
        p.lower[i] = p.upper[i] = a;
        break;
      case 1:
        p.lower[i] = a;
        break;
      case 2:
        p.upper[i] = b;
        break;
      case 3:
        break;
      default:
        p.lower[i] = a, p.upper[i] = b;
    }
    if (pick(rng) < 4)
      p.ineq_names[i] = "torque L" + std::to_string(i % 6 + 1) + "_femur (a long row name)";
  }
  for (int o = 0; o + 2 < n && pick(rng) < 3; o += 3)
    p.cones.push_back({o, o + 1, o + 2, 0.3,
                       pick(rng) < 3 ? "friction cone L" + std::to_string(o / 3 + 1) : "", 1.0});
  return p;
}

TEST_CASE("describe_violations: the plain row-by-row text and largest violation, bit for bit",
          "[allocation]") {
  std::mt19937 rng(2311);
  std::uniform_int_distribution<int> n_d(0, 18), pick(0, 9);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(-8.0, 3.0);
  ViolationWorkspace ws;  // reused: sizes change from one problem to the next
  int with_text = 0, without_text = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int n = n_d(rng);
    const QpProblem p = random_problem(rng, n);
    Eigen::VectorXd x(n);
    const double scale = std::pow(10.0, e(rng));
    for (int j = 0; j < n; ++j) x[j] = pick(rng) == 0 ? 0.0 : scale * u(rng);
    if (n > 0 && pick(rng) == 0) x[0] = pick(rng) < 5 ? kInf : std::nan("");
    for (const double tol : {1e-6, 1e-3, 1e3}) {
      double expected_worst = -1.0, worst = -1.0, worst_plain_call = -1.0;
      const std::string expected = plain_violations(p, x, tol, expected_worst);
      const std::string text = describe_violations(p, x, tol, &worst, ws);
      INFO("trial " << trial << " n " << n << " tol " << tol);
      CHECK(text == expected);
      CHECK(std::memcmp(&worst, &expected_worst, sizeof worst) == 0);
      CHECK(describe_violations(p, x, tol, &worst_plain_call) == expected);
      CHECK(std::memcmp(&worst_plain_call, &expected_worst, sizeof worst) == 0);
      ++(expected.empty() ? without_text : with_text);
    }
  }
  // Both outcomes occur often enough to count.
  CHECK(with_text > 1000);
  CHECK(without_text > 1000);
}

TEST_CASE("describe_violations: the numbers read as printf's %.3g", "[allocation]") {
  // One equality row x0 = 0 violated by v for values across the whole double range,
  // roundings at three digits included (9.995, 0.0009995, 99950).
  QpProblem p;
  p.resize(1, 1, 0);
  p.A(0, 0) = 1.0;
  p.eq_names = {"row"};
  std::vector<double> values{1.0,
                             9.995,
                             0.0009995,
                             99950.0,
                             123456.0,
                             1e-300,
                             1.5e300,
                             kInf,
                             std::numeric_limits<double>::denorm_min(),
                             std::numeric_limits<double>::max()};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> m(1.0, 10.0), e(-300.0, 300.0);
  for (int i = 0; i < 20000; ++i) values.push_back(m(rng) * std::pow(10.0, std::floor(e(rng))));
  ViolationWorkspace ws;
  for (const double v : values) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    const std::string text =
        describe_violations(p, Eigen::VectorXd::Constant(1, v), 0.0, nullptr, ws);
    INFO("v " << v);
    CHECK(text == std::string("row by ") + buf);
  }
}

}  // namespace
}  // namespace hexdyn
