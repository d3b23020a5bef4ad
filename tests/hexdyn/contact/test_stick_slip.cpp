// Friction that holds (contact/stick_slip.hpp, docs/theory/replay.md#stick-slip): a block on an
// incline, integrated as the replay integrates a foot (the normal law linearised over the
// step, the stick–slip force affine in the new velocity, the state settled after the step),
// against the closed forms of statics and of Coulomb sliding:
// - below μ_s it holds: it moves only by the tangential spring's deflection m g sin θ / k_t,
//   and not at all once that has settled;
// - above μ_s it slides with the acceleration g (sin θ − μ_d cos θ);
// - between μ_d and μ_s it holds from rest (stiction), and slides on once pushed.
// The regularised law on the same incline creeps, which is what the stick–slip law removes.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "hexdyn/contact/simulation_contact.hpp"
#include "hexdyn/contact/stick_slip.hpp"
#include "hexdyn/sample_models.hpp"

using namespace hexdyn;

namespace {

/// The contact of configs/paper.yaml in SI (K = 1e5 · 1000^2.2 N/m^2.2, e = 2.2, C_max = 1e4
/// N s/m, p = 1e-5 m) with the given friction and the default stick–slip spring.
ContactParams incline_contact(double mu_s, double mu_d, FrictionLaw law) {
  ContactParams c = test::contact_params(1e5 * std::pow(1000.0, 2.2), 2.2, 1e4, 1e-5);
  c.static_friction = mu_s;
  c.dynamic_friction = mu_d;
  c.friction_law = law;
  return c;
}

/// A plane through the origin rising along +y at angle θ, as a terrain profile.
struct Incline {
  double theta_rad;
  std::vector<double> y{-100.0, 100.0};
  std::vector<double> z;
  explicit Incline(double theta) : theta_rad(theta) {
    z = {y[0] * std::tan(theta), y[1] * std::tan(theta)};
  }
  Vec3 normal() const { return Vec3(0.0, -std::sin(theta_rad), std::cos(theta_rad)); }
  Vec3 downhill() const { return Vec3(0.0, -std::cos(theta_rad), -std::sin(theta_rad)); }
};

/// A point mass on the incline: position, velocity, the tangential state and the anchor's
/// slip so far.
struct Block {
  Vec3 p = Vec3::Zero(), v = Vec3::Zero();
  TangentialContact tangential;
  double slip_m = 0.0;
};

/// One linearly implicit Euler step of length h, as the replay takes one (replay.cpp
/// implicit_step with a single body): m (v' − v) = h (m g + a + B v'), p' = p + h v', the
/// block first sticking, then, if its stick force exceeds its cap, sliding.
void step(const ContactParams& c, const Incline& incline, double m, double h, Block& b) {
  const TerrainContactPoint g = terrain_contact(incline.y, incline.z, b.p, 0.0);
  const Vec3 gravity(0.0, 0.0, -kGravity);
  const Vec3& n = g.normal_W;
  const FootContactForce law = foot_contact_force(c, g.penetration_m, n, b.v);
  const bool touching = g.penetration_m > 0.0;
  const Vec3 grad = (law.dF_dv + h * law.dF_dp).transpose() * n;
  const double fn0 = law.normal_N - n.dot(law.dF_dv * b.v);
  auto solve = [&](const AffineTangentialForce& t, Vec3& force) {
    Vec3 a = fn0 * n + t.a_N;
    Mat3 B = n * grad.transpose() + t.B_Nspm;
    if (!touching) a.setZero(), B.setZero();
    const Vec3 v =
        (m * Mat3::Identity() - h * B).partialPivLu().solve(m * b.v + h * (m * gravity + a));
    force = a + B * v;
    return v;
  };
  Vec3 force;
  Vec3 v_new;
  if (c.friction_law == FrictionLaw::kStickSlip) {
    v_new = solve(stick_affine(c, b.tangential, n, h), force);
    Vec3 ft = force - n.dot(force) * n;
    const bool slides = touching && ft.norm() > friction_cap(c, b.tangential, n.dot(force));
    const Vec3 e = ft.normalized();
    if (slides) v_new = solve(slip_affine(c, e, fn0, grad), force);
    if (touching) {
      const TangentialUpdate u =
          settle_stick_slip(c, b.tangential, n, std::max(0.0, n.dot(force)),
                            v_new - n.dot(v_new) * n, h, slides ? &e : nullptr);
      b.tangential = u.next;
      b.slip_m += u.slip_W.norm();
    }
  } else {
    AffineTangentialForce t;
    t.a_N = law.tangential_W;  // the regularised law, explicit in the test
    v_new = solve(t, force);
  }
  b.v = v_new;
  b.p += h * v_new;
}

/// The block at rest on the incline at its penetration under m g cos θ.
Block resting_block(const ContactParams& c, const Incline& incline, double m) {
  Block b;
  const double delta =
      std::pow(m * kGravity * std::cos(incline.theta_rad) / c.stiffness, 1.0 / c.exponent);
  b.p = -delta * incline.normal();
  return b;
}

}  // namespace

TEST_CASE("stick-slip: a block below mu_s holds, moving only by its spring",
          "[contact][friction]") {
  const double m = 1.0, h = 2e-4;
  const ContactParams c = incline_contact(0.3, 0.3, FrictionLaw::kStickSlip);
  // Set down on the incline with its spring slack (tan θ = 0.18, 0.23): the spring takes the
  // load with some overshoot (damping ratio c_t / (2 √(k_t m)) = 0.5), still below μ_s F_n.
  for (const double theta_deg : {10.0, 13.0}) {
    const Incline incline(theta_deg * M_PI / 180.0);
    Block b = resting_block(c, incline, m);
    const Vec3 start = b.p;
    Vec3 settled = Vec3::Zero();
    for (int i = 1; i <= 6000; ++i) {  // 1.2 s
      step(c, incline, m, h, b);
      if (i == 1000) settled = b.p;  // 0.2 s: the spring's transient has decayed
    }
    // The closed form of statics: the spring carries m g sin θ, so it is stretched by
    // m g sin θ / k_t along the slope, and the anchor never moved.
    const double deflection =
        m * kGravity * std::sin(incline.theta_rad) / c.tangential_stiffness_Npm;
    const Vec3 moved = b.p - start;
    INFO("theta " << theta_deg << " deg: moved " << moved.transpose() << " m, deflection "
                  << deflection << " m, held within " << (b.p - settled).norm() << " m");
    CHECK((b.p - settled).norm() < 1e-6);
    CHECK(moved.dot(incline.downhill()) == Approx(deflection).epsilon(1e-6));
    CHECK(b.slip_m == 0.0);
    CHECK_FALSE(b.tangential.sliding);
  }
  // At rest on a slope of tan θ = 0.296, 1.3 % below μ_s = 0.3, its spring at its static
  // deflection: held within 1e-6 m over 1 s.
  const Incline steep(std::atan(0.296));
  Block b = resting_block(c, steep, m);
  b.tangential.deflection_W =
      m * kGravity * std::sin(steep.theta_rad) / c.tangential_stiffness_Npm * steep.downhill();
  const Vec3 start = b.p;
  for (int i = 0; i < 5000; ++i) step(c, steep, m, h, b);
  INFO("tan theta 0.296: moved " << (b.p - start).norm() << " m in 1 s");
  CHECK((b.p - start).norm() < 1e-6);
  CHECK(b.slip_m == 0.0);
}

TEST_CASE("stick-slip: above mu_s a block slides at g (sin - mu_d cos)", "[contact][friction]") {
  const double m = 1.0, h = 2e-4;
  struct Case {
    double theta_deg, mu_s, mu_d;
  };
  for (const Case k : {Case{21.8, 0.3, 0.3}, Case{25.0, 0.4, 0.25}, Case{35.0, 0.6, 0.1}}) {
    const Incline incline(k.theta_deg * M_PI / 180.0);
    const ContactParams c = incline_contact(k.mu_s, k.mu_d, FrictionLaw::kStickSlip);
    Block b = resting_block(c, incline, m);
    Vec3 v_early = Vec3::Zero();
    for (int i = 1; i <= 3500; ++i) {  // 0.7 s
      step(c, incline, m, h, b);
      if (i == 1000) v_early = b.v;
    }
    const double closed_form =
        kGravity * (std::sin(incline.theta_rad) - k.mu_d * std::cos(incline.theta_rad));
    const double measured = (b.v - v_early).dot(incline.downhill()) / (2500 * h);
    INFO("theta " << k.theta_deg << " deg, mu_s " << k.mu_s << ", mu_d " << k.mu_d
                  << ": acceleration " << measured << " m/s^2, closed form " << closed_form);
    CHECK(b.tangential.sliding);
    CHECK(std::abs(measured / closed_form - 1.0) < 1e-3);
    // It slides straight down the slope, and the anchor's slip is the distance slid but for
    // the spring's deflection, k_t |z| = μ_d F_n.
    CHECK(std::abs(b.v.x()) < 1e-12);
    CHECK(b.v.normalized().dot(incline.downhill()) == Approx(1.0).epsilon(1e-9));
    const double spring =
        k.mu_d * m * kGravity * std::cos(incline.theta_rad) / c.tangential_stiffness_Npm;
    const double slid = (b.p - resting_block(c, incline, m).p).dot(incline.downhill());
    CHECK(b.slip_m == Approx(slid - spring).epsilon(1e-6));
  }
}

TEST_CASE("stick-slip: between mu_d and mu_s a block holds from rest, slides once pushed",
          "[contact][friction]") {
  const double m = 1.0, h = 2e-4;
  const Incline incline(std::atan(0.4));
  const ContactParams c = incline_contact(0.5, 0.3, FrictionLaw::kStickSlip);
  Block held = resting_block(c, incline, m);
  for (int i = 0; i < 2500; ++i) step(c, incline, m, h, held);
  CHECK_FALSE(held.tangential.sliding);
  CHECK(held.slip_m == 0.0);
  CHECK(held.v.norm() < 1e-9);
  // Pushed at 0.1 m/s down the slope it slides on and speeds up at g (sin θ − μ_d cos θ).
  Block pushed = resting_block(c, incline, m);
  pushed.v = 0.1 * incline.downhill();
  for (int i = 0; i < 500; ++i) step(c, incline, m, h, pushed);
  const Vec3 v0 = pushed.v;
  for (int i = 0; i < 2500; ++i) step(c, incline, m, h, pushed);
  const double closed_form =
      kGravity * (std::sin(incline.theta_rad) - 0.3 * std::cos(incline.theta_rad));
  CHECK(pushed.tangential.sliding);
  CHECK((pushed.v - v0).dot(incline.downhill()) / (2500 * h) == Approx(closed_form).epsilon(1e-3));
}

TEST_CASE("the regularised law creeps where stick-slip holds", "[contact][friction]") {
  // Below v_s the regularised law is a damper of F_n 1.5 μ_s / v_s: on a slope it creeps at
  // about v_s tan θ / (1.5 μ_s), the creep the stick–slip law removes.
  const double m = 1.0, h = 2e-4;
  const Incline incline(16.0 * M_PI / 180.0);
  const ContactParams c = incline_contact(0.3, 0.3, FrictionLaw::kRegularised);
  Block b = resting_block(c, incline, m);
  const Vec3 start = b.p;
  for (int i = 0; i < 5000; ++i) step(c, incline, m, h, b);
  const double creep_speed =
      c.stiction_velocity_mps * std::tan(incline.theta_rad) / (1.5 * c.static_friction);
  const double moved = (b.p - start).dot(incline.downhill());
  INFO("regularised: moved " << moved << " m in 1 s, creep speed about " << creep_speed);
  CHECK(moved > 0.5 * creep_speed);
}

TEST_CASE("stick_slip_force caps at mu_s F_n while sticking and is mu_d F_n when sliding",
          "[contact][friction]") {
  ContactParams c = incline_contact(0.5, 0.3, FrictionLaw::kStickSlip);
  const Vec3 n = Vec3::UnitZ();
  TangentialContact s;
  s.deflection_W = Vec3(2e-6, 0.0, 0.0);  // k_t z = 2 N
  CHECK(stick_slip_force(c, s, n, 10.0, Vec3::Zero()).isApprox(Vec3(-2.0, 0.0, 0.0), 1e-12));
  CHECK(stick_slip_force(c, s, n, 2.0, Vec3::Zero()).isApprox(Vec3(-1.0, 0.0, 0.0), 1e-12));
  CHECK(friction_cap(c, s, 2.0) == Approx(1.0));
  s.sliding = true;
  CHECK(friction_cap(c, s, 2.0) == Approx(0.6));
  CHECK(stick_slip_force(c, s, n, 2.0, Vec3::Zero()).isApprox(Vec3(-0.6, 0.0, 0.0), 1e-12));
  CHECK(stick_slip_force(c, s, n, 0.0, Vec3::Zero()).isZero(0.0));
  CHECK(tangential_spring_energy(c, s) == Approx(0.5 * 1e6 * 4e-12));
}
