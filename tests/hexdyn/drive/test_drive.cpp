// The drive-train stage (drive/drive.hpp, docs/theory/drive-train.md) against second
// computations: the drive torque's offset and the torque bound against their formulas with
// hand-picked values; the current's two branches and the power balance of motor, gearbox and
// joint; the largest windowed RMS against a brute force over dense window starts with its
// own quadrature; the electrical series and energies of a synthetic run recomputed here.
#include <Eigen/Core>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "hexdyn/drive/drive.hpp"

namespace hexdyn {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A servo of round numbers (an MX-64 class motor, docs/user/servos.md): G k_t = 1.6 N m/A.
ActuatorParams round_servo() {
  ActuatorParams a;
  a.gear_ratio = 200.0;
  a.torque_constant_NmpA = 0.008;
  a.resistance_ohm = 4.0;
  a.gear_efficiency = 0.8;
  return a;
}

/// Relative closeness with a floor of 1 on the scale: |a − b| ≤ tol · max(1, |a|, |b|).
bool close(double a, double b, double tol) {
  return std::abs(a - b) <= tol * std::max({1.0, std::abs(a), std::abs(b)});
}

}  // namespace

TEST_CASE("drive: the torque offset is J_a q̈ + τ_c sgn(q̇) + b q̇ with sgn(0) = 0", "[drive]") {
  // A hexapod's 18 joints and a robot of 8: the offset has one entry per joint.
  const int J = GENERATE(18, 8);
  CAPTURE(J);
  DriveTrainParams drive;
  drive.present = true;
  drive.joints.count = J;
  JointVector qd = JointVector::Zero(J), qdd = JointVector::Zero(J);
  // Joint 0: 0.012 · (−3) + 0.1 · 1 + 0.5 · 2 = 1.064.
  drive.joints[0].armature_kgm2 = 0.012;
  drive.joints[0].coulomb_friction_Nm = 0.1;
  drive.joints[0].viscous_friction_Nmsprad = 0.5;
  qd[0] = 2.0;
  qdd[0] = -3.0;
  // Joint 1, moving backwards: 0.25 · 4 + 0.3 · (−1) + 0.2 · (−0.5) = 0.6.
  drive.joints[1].armature_kgm2 = 0.25;
  drive.joints[1].coulomb_friction_Nm = 0.3;
  drive.joints[1].viscous_friction_Nmsprad = 0.2;
  qd[1] = -0.5;
  qdd[1] = 4.0;
  // Joints 2 and 3 at rest (q̇ = +0 and −0): no friction, only the armature: 0.5 · 2 = 1, 0.
  for (int k : {2, 3}) {
    drive.joints[k].armature_kgm2 = 0.5;
    drive.joints[k].coulomb_friction_Nm = 7.0;
    drive.joints[k].viscous_friction_Nmsprad = 9.0;
  }
  qd[3] = -0.0;
  qdd[2] = 2.0;
  // Joint 4: the smallest positive speed already carries the whole Coulomb torque: 0.7.
  drive.joints[4].coulomb_friction_Nm = 0.7;
  qd[4] = std::numeric_limits<double>::denorm_min();
  // Joint 5: the ideal joint of the defaults gives no offset whatever the motion.
  qd[5] = 3.0;
  qdd[5] = -8.0;
  const JointVector d = drive_torque_offset(drive, qd, qdd);
  REQUIRE(d.size() == J);
  CHECK(d[0] == Approx(1.064).epsilon(1e-14));
  CHECK(d[1] == Approx(0.6).epsilon(1e-14));
  CHECK(d[2] == 1.0);
  CHECK(d[3] == 0.0);
  CHECK(d[4] == 0.7);
  CHECK(d[5] == 0.0);
  for (int k = 6; k < J; ++k) CHECK(d[k] == 0.0);
}

TEST_CASE("drive: the bound of a peak rating alone is the rating at every speed", "[drive]") {
  ActuatorParams a = round_servo();
  a.peak_torque_Nm = 3.0;
  for (double qd : {0.0, 1.0, -1.0, 1e3, -1e6}) {
    const DriveLimit lim = drive_torque_limit(a, qd);
    CHECK(lim.limit_Nm == 3.0);
    CHECK(lim.bound == DriveBound::kPeak);
  }
  // Neither rating nor supply: no bound, none named (the allocation's limit applies).
  const DriveLimit none = drive_torque_limit(round_servo(), 5.0);
  CHECK(none.limit_Nm == kInf);
  CHECK(none.bound == DriveBound::kNone);
  CHECK(std::string(bound_name(DriveBound::kPeak)) == "peak");
  CHECK(std::string(bound_name(DriveBound::kVoltage)) == "voltage");
  CHECK(std::string(bound_name(DriveBound::kNone)).empty());
}

TEST_CASE("drive: the bound of a supply alone is the torque-speed line", "[drive]") {
  ActuatorParams a = round_servo();
  a.voltage_V = 12.0;
  const double Gk = 200.0 * 0.008;  // 1.6 N m/A
  // At rest: the stall torque G k_t η V / R = 1.6 · 0.8 · 12 / 4 = 3.84 N m.
  const double stall = Gk * 0.8 * 12.0 / 4.0;
  CHECK(stall == Approx(3.84).epsilon(1e-15));
  const DriveLimit at_rest = drive_torque_limit(a, 0.0);
  CHECK(at_rest.limit_Nm == Approx(stall).epsilon(1e-15));
  CHECK(at_rest.bound == DriveBound::kVoltage);
  // The no-load speed V / (G k_t) = 7.5 rad/s: zero there, linear between, the same backwards.
  const double no_load = 12.0 / Gk;
  for (double share : {0.25, 0.5, 0.9}) {
    for (double sign : {1.0, -1.0}) {
      const DriveLimit lim = drive_torque_limit(a, sign * share * no_load);
      CHECK(lim.limit_Nm == Approx((1.0 - share) * stall).epsilon(1e-14));
      CHECK(lim.bound == DriveBound::kVoltage);
    }
  }
  CHECK(drive_torque_limit(a, no_load).limit_Nm == Approx(0.0).margin(1e-14));
  CHECK(drive_torque_limit(a, -no_load).limit_Nm == Approx(0.0).margin(1e-14));
  // Beyond the no-load speed: exactly 0, never negative, still the voltage's bound.
  for (double qd : {1.0001 * no_load, 2.0 * no_load, -10.0 * no_load, 1e9}) {
    const DriveLimit lim = drive_torque_limit(a, qd);
    CHECK(lim.limit_Nm == 0.0);
    CHECK(lim.bound == DriveBound::kVoltage);
  }
}

TEST_CASE("drive: with both, the bound is the smaller and names its source", "[drive]") {
  ActuatorParams a = round_servo();
  a.voltage_V = 12.0;
  a.peak_torque_Nm = 3.0;  // below the stall torque 3.84 N m
  const double Gk = 1.6, stall = 3.84;
  // The line meets the rating where (1 − q̇ G k_t / V) · stall = peak: q̇* = (1 − 3/3.84) · 7.5.
  const double cross = (1.0 - 3.0 / stall) * 12.0 / Gk;
  for (double qd : {0.0, 0.5 * cross, -0.99 * cross}) {
    const DriveLimit lim = drive_torque_limit(a, qd);
    CHECK(lim.limit_Nm == 3.0);
    CHECK(lim.bound == DriveBound::kPeak);
  }
  for (double qd : {1.01 * cross, -2.0 * cross, 7.4}) {
    const DriveLimit lim = drive_torque_limit(a, qd);
    const double line = stall * (1.0 - std::abs(qd) * Gk / 12.0);
    CHECK(lim.limit_Nm == Approx(line).epsilon(1e-14));
    CHECK(lim.limit_Nm < 3.0);
    CHECK(lim.bound == DriveBound::kVoltage);
  }
  // A rating above the stall torque never binds.
  a.peak_torque_Nm = 5.0;
  const DriveLimit lim = drive_torque_limit(a, 0.0);
  CHECK(lim.limit_Nm == Approx(stall).epsilon(1e-15));
  CHECK(lim.bound == DriveBound::kVoltage);
}

TEST_CASE("drive: the current of a driving and of a back-driven joint", "[drive]") {
  const ActuatorParams a = round_servo();  // G k_t = 1.6 N m/A, η = 0.8
  // Driving (τ q̇ > 0, or q̇ = 0): the motor gives τ / η through the gearbox.
  CHECK(motor_current(a, 2.0, 1.0) == Approx(2.0 / (1.6 * 0.8)).epsilon(1e-15));
  CHECK(motor_current(a, -2.0, -1.0) == Approx(-2.0 / (1.6 * 0.8)).epsilon(1e-15));
  CHECK(motor_current(a, 2.0, 0.0) == Approx(2.0 / (1.6 * 0.8)).epsilon(1e-15));
  CHECK(motor_current(a, -2.0, 0.0) == Approx(-2.0 / (1.6 * 0.8)).epsilon(1e-15));
  // Back-driven (τ q̇ < 0): the motor holds only η τ.
  CHECK(motor_current(a, 2.0, -1.0) == Approx(2.0 * 0.8 / 1.6).epsilon(1e-15));
  CHECK(motor_current(a, -2.0, 3.0) == Approx(-2.0 * 0.8 / 1.6).epsilon(1e-15));
  CHECK(motor_current(a, 0.0, 3.0) == 0.0);
  // The copper-loss weight is the loss per τ² of a driving joint.
  CHECK(copper_loss_weight(a) * 4.0 ==
        Approx(a.resistance_ohm * std::pow(motor_current(a, 2.0, 1.0), 2)).epsilon(1e-14));
}

TEST_CASE("drive: the motor's power is copper loss plus the joint's power, less the gearbox's",
          "[drive]") {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  ActuatorParams ideal = round_servo();
  ideal.gear_efficiency = 1.0;
  const ActuatorParams lossy = round_servo();  // η = 0.8
  for (int i = 0; i < 200; ++i) {
    const double tau = u(rng), qd = u(rng);
    const double Gk = 1.6;
    // η = 1: R I² + G k_t q̇ I = R I² + τ q̇ in both branches.
    const double I = motor_current(ideal, tau, qd);
    CHECK(close(ideal.resistance_ohm * I * I + Gk * qd * I, ideal.resistance_ohm * I * I + tau * qd,
                1e-14));
    // η < 1: the motor's mechanical power G k_t q̇ I exceeds the joint's τ q̇ by the gearbox's
    // loss, (1/η − 1) τ q̇ driving, (1 − η) |τ q̇| back-driven.
    const double Il = motor_current(lossy, tau, qd);
    const double motor = Gk * qd * Il, joint = tau * qd;
    const double loss = joint >= 0.0 ? (1.0 / 0.8 - 1.0) * joint : (1.0 - 0.8) * -joint;
    CHECK(close(motor - joint, loss, 1e-13));
    CHECK(loss >= 0.0);
  }
}

namespace {

/// Samples (t, s) with s = y², linear between samples (the windowed RMS's model).
struct SquaredSeries {
  std::vector<double> t, s;
};

SquaredSeries squared(const std::vector<double>& t, const std::vector<double>& y) {
  SquaredSeries d{t, {}};
  for (double v : y) d.s.push_back(v * v);
  return d;
}

/// ∫_a^b s by the midpoint rule on `cells` equal cells, the piece of each midpoint found by
/// walking the samples. The rule is exact on a cell where s is linear; a cell of width h
/// holding a sample where s's slope jumps by m errs by at most m h² / 8 (s = m·max(0, x − c)
/// with the kink c at the midpoint is the worst case).
double midpoint_integral(const SquaredSeries& d, double a, double b, int cells) {
  const double h = (b - a) / cells;
  std::size_t i = 0;
  double sum = 0.0;
  for (int c = 0; c < cells; ++c) {
    const double x = a + (c + 0.5) * h;
    while (i + 2 < d.t.size() && d.t[i + 1] <= x) ++i;
    const double w = (x - d.t[i]) / (d.t[i + 1] - d.t[i]);
    sum += (1.0 - w) * d.s[i] + w * d.s[i + 1];
  }
  return sum * h;
}

/// The largest |slope| of s, and the jump of its slope at each sample (0 at the ends).
void slopes(const SquaredSeries& d, double& max_slope, std::vector<double>& jump) {
  max_slope = 0.0;
  jump.assign(d.t.size(), 0.0);
  double prev = 0.0;
  for (std::size_t i = 0; i + 1 < d.t.size(); ++i) {
    const double m = (d.s[i + 1] - d.s[i]) / (d.t[i + 1] - d.t[i]);
    max_slope = std::max(max_slope, std::abs(m));
    if (i > 0) jump[i] = std::abs(m - prev);
    prev = m;
  }
}

/// Bounds on the largest F(a) = ∫_a^{a+W} s over a ∈ [t_0, t_end − W], from equally spaced
/// window starts Δa apart (both ends among them), each window integrated on cells of width
/// h ≤ `resolution`. F'(a) = s(a + W) − s(a) is continuous and |F''| ≤ 2 max|s'|: at an
/// interior maximum a* (F'(a*) = 0) the nearest start is below F(a*) by at most
/// max|s'| Δa² / 4; a maximum at an end is a start. Each window's quadrature errs by at most
/// h² / 8 times the slope jumps inside it (midpoint_integral), plus its sum's rounding
/// (≤ 1e-12 W max s for at most ~1e5 cells).
struct BruteForce {
  double lower, upper;
  double best_start;  ///< the start of the largest quadrature
};

BruteForce brute_force(const SquaredSeries& d, double W, double resolution) {
  const double t0 = d.t.front(), span = d.t.back() - W - t0;
  const int starts = std::max(1000, static_cast<int>(std::ceil(span / resolution)));
  const int cells = std::max(1000, static_cast<int>(std::ceil(W / resolution)));
  double max_slope = 0.0, s_max = 0.0;
  std::vector<double> jump;
  slopes(d, max_slope, jump);
  for (double v : d.s) s_max = std::max(s_max, v);
  const double h = W / cells, da = span / starts;
  double best = -1.0, best_a = t0, best_err = 0.0, worst_err = 0.0;
  for (int k = 0; k <= starts; ++k) {
    const double a = k == starts ? t0 + span : t0 + span * k / starts;
    double inside = 0.0;
    for (std::size_t j = 0; j < d.t.size(); ++j)
      if (d.t[j] > a && d.t[j] < a + W) inside += jump[j];
    const double err = inside * h * h / 8.0 + 1e-12 * W * s_max;
    worst_err = std::max(worst_err, err);
    const double F = midpoint_integral(d, a, a + W, cells);
    if (F > best) best = F, best_a = a, best_err = err;
  }
  return {best - best_err, best + worst_err + max_slope * da * da / 4.0, best_a};
}

/// The exact ∫ s over the run: the trapezoid rule is exact for s linear between samples.
double exact_integral(const SquaredSeries& d) {
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < d.t.size(); ++i)
    sum += 0.5 * (d.s[i] + d.s[i + 1]) * (d.t[i + 1] - d.t[i]);
  return sum;
}

/// largest_window_rms of y given as column 1 of a T×3 row-major matrix (stride 3).
double window_rms_strided(const std::vector<double>& t, const std::vector<double>& y, double W) {
  RowMatrix m = RowMatrix::Constant(static_cast<int>(t.size()), 3, 1e6);
  for (std::size_t i = 0; i < t.size(); ++i) m(static_cast<int>(i), 1) = y[i];
  return largest_window_rms(t, m.data() + 1, 3, W);
}

}  // namespace

TEST_CASE("drive: the largest windowed RMS against a brute force over window starts", "[drive]") {
  // Random non-uniform grids: steps 0.05 to 0.3 s and |y| ≤ 2, so |s'| ≤ 80 /s; at a
  // resolution of 5e-4 s the brute force's bounds are at most ~1e-4 apart (quadrature:
  // 20 jumps ≤ 160 /s each, × h²/8 = 3e-8 s²; starts: 80 · Δa²/4 = 5e-6), on windowed
  // integrals of O(0.1) to O(10) N² m² s.
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> step(0.05, 0.3), val(-2.0, 2.0), start(-1.0, 1.0);
  for (int run = 0; run < 8; ++run) {
    const int n = 6 + run * 2;
    std::vector<double> t{start(rng)}, y{val(rng)};
    for (int i = 1; i < n; ++i) {
      t.push_back(t.back() + step(rng));
      y.push_back(val(rng));
    }
    const SquaredSeries d = squared(t, y);
    const double duration = t.back() - t.front();
    // A window inside one step, a few steps, most of the run.
    for (double share : {0.02, 0.2, 0.55, 0.95}) {
      const double W = share * duration;
      const BruteForce b = brute_force(d, W, 5e-4);
      const double F = W * std::pow(window_rms_strided(t, y, W), 2);
      INFO("run " << run << ", " << n << " samples, window " << W << " s of " << duration
                  << " s: brute force in [" << b.lower << ", " << b.upper << "], got " << F);
      CHECK(b.upper - b.lower < 3e-4 * std::max(1.0, b.upper));
      CHECK(F >= b.lower);
      CHECK(F <= b.upper);
    }
    // A window as long as the run or longer: the run's RMS, sqrt(∫ s / duration).
    const double run_rms = std::sqrt(exact_integral(d) / duration);
    for (double W : {duration, 1.5 * duration, kInf})
      CHECK(window_rms_strided(t, y, W) == Approx(run_rms).epsilon(1e-13));
  }
  // One sample: |y_0| whatever the window.
  for (double W : {0.1, 10.0, kInf}) CHECK(window_rms_strided({0.7}, {-1.3}, W) == 1.3);
}

TEST_CASE("drive: the largest windowed RMS finds a maximum strictly inside a piece", "[drive]") {
  // s = y² rises 0 → 1 over [0, 1.2], holds 1 to t = 2, falls to 0 at t = 3.2 (a symmetric
  // hump on a non-uniform grid). With W = 1.6 the start a runs over [0, 1.6]; its breakpoints
  // (a or a + W at a sample) are 0, 0.4, 1.2, 1.6. On [0.4, 1.2] a lies in the rise and a + W
  // in the fall: F'(a) = s(a + W) − s(a) = (3.2 − a − W)/1.2 − a/1.2 falls through 0 at
  // a* = 0.8, the hump's centre. F(a*) = 2 · 0.4 · (2/3 + 1)/2 + 0.8 = 22/15, above
  // F(0.4) = F(1.2) = 0.8 · (1/3 + 1)/2 + 0.8 = 20/15 and F(0) = F(1.6) = 1.2 / 2 + 0.4 = 1.
  const std::vector<double> t{0.0, 1.2, 2.0, 3.2};
  const std::vector<double> y{0.0, -1.0, 1.0, 0.0};
  const double W = 1.6;
  const double rms = window_rms_strided(t, y, W);
  CHECK(rms == Approx(std::sqrt(22.0 / 15.0 / W)).epsilon(1e-14));
  // The brute force agrees, and its best start is inside the piece, away from its ends.
  const SquaredSeries d = squared(t, y);
  const BruteForce b = brute_force(d, W, 5e-4);
  CHECK(W * rms * rms >= b.lower);
  CHECK(W * rms * rms <= b.upper);
  CHECK(b.best_start == Approx(0.8).margin(1e-3));
  // The breakpoints' values are clearly below: a search of breakpoints alone would miss the
  // maximum by 2/15, far beyond the brute force's uncertainty.
  for (double a : {0.0, 0.4, 1.2, 1.6})
    CHECK(midpoint_integral(d, a, a + W, 4000) < 20.0 / 15.0 + 1e-6);
  CHECK(b.upper - b.lower < 1e-3 * 2.0 / 15.0);
}

namespace {

/// A synthetic run: T non-uniform samples, random joint speeds and drive torques, with
/// some speeds and torques exactly 0 (both current branches, sgn and P = 0 edge cases).
struct SyntheticRun {
  std::vector<double> t;
  RowMatrix qd, tau;
};

SyntheticRun synthetic_run(int T, unsigned seed, int joints) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> step(0.005, 0.08), u(-1.0, 1.0);
  SyntheticRun r;
  r.qd.resize(T, joints);
  r.tau.resize(T, joints);
  double t = 0.3;
  for (int i = 0; i < T; ++i) {
    r.t.push_back(t);
    t += step(rng);
    for (int k = 0; k < joints; ++k) {
      r.qd(i, k) = (i + k) % 11 == 0 ? 0.0 : 6.0 * u(rng);
      r.tau(i, k) = (i + 2 * k) % 13 == 0 ? 0.0 : 4.0 * u(rng);
    }
  }
  return r;
}

/// Every joint a different drive: G, k_t, R, η, friction, regeneration and window vary.
DriveTrainParams varied_drive(double efficiency, double regeneration, int joints) {
  DriveTrainParams drive;
  drive.present = true;
  drive.joints.count = joints;
  for (int k = 0; k < joints; ++k) {
    ActuatorParams& a = drive.joints[k];
    a.gear_ratio = 150.0 + 10.0 * k;
    a.torque_constant_NmpA = 0.006 + 0.0002 * k;
    a.resistance_ohm = 2.0 + 0.25 * k;
    a.coulomb_friction_Nm = 0.01 * (k % 4);
    a.viscous_friction_Nmsprad = 0.005 * (k % 3);
    a.gear_efficiency = efficiency < 0.0 ? 0.6 + 0.02 * k : efficiency;
    a.regeneration = regeneration < 0.0 ? (k % 3) / 2.0 : regeneration;
    a.continuous_torque_Nm = k % 2 ? 1.0 + 0.1 * k : kInf;
    // Joint 4 a window of 0.4 s, joint 9 one longer than any run here, the others none.
    a.thermal_window_s = k == 4 ? 0.4 : (k == 9 ? 100.0 : kInf);
  }
  return drive;
}

/// The trapezoid rule of f(i) over the sample times.
template <class F>
double trapezoid_of(const std::vector<double>& t, F f) {
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < t.size(); ++i)
    sum += 0.5 * (f(static_cast<int>(i)) + f(static_cast<int>(i) + 1)) * (t[i + 1] - t[i]);
  return sum;
}

}  // namespace

TEST_CASE("drive: the electrical series and energies of a run, computed again", "[drive]") {
  // A hexapod's 18 joints and a quadruped's 12: the joints are the drive's count.
  const int J = GENERATE(18, 12);
  CAPTURE(J);
  const SyntheticRun run = synthetic_run(60, 7, J);
  const DriveTrainParams drive = varied_drive(-1.0, -1.0, J);
  const double mass_kg = 6.7, distance_m = 0.9;
  const ElectricalResult e = compute_electrical(drive, run.t, run.qd, run.tau, mass_kg, distance_m);
  const int T = static_cast<int>(run.t.size());
  REQUIRE(e.current_A.rows() == T);
  REQUIRE(e.power_W.rows() == T);
  REQUIRE(e.total_power_W.size() == run.t.size());
  // Per sample and joint, from the formulas of
  // docs/theory/drive-train.md#current-and-electrical-power.
  RowMatrix P(T, J), drawn(T, J), copper(T, J), friction(T, J);
  for (int i = 0; i < T; ++i) {
    double total = 0.0;
    for (int k = 0; k < J; ++k) {
      const ActuatorParams& a = drive.joints[k];
      const double w = run.qd(i, k), tau = run.tau(i, k),
                   Gk = a.gear_ratio * a.torque_constant_NmpA;
      const double I =
          tau * w >= 0.0 ? tau / (Gk * a.gear_efficiency) : tau * a.gear_efficiency / Gk;
      copper(i, k) = a.resistance_ohm * I * I;
      P(i, k) = copper(i, k) + Gk * w * I;
      drawn(i, k) = P(i, k) >= 0.0 ? P(i, k) : a.regeneration * P(i, k);
      friction(i, k) = a.coulomb_friction_Nm * std::abs(w) + a.viscous_friction_Nmsprad * w * w;
      total += drawn(i, k);
      CHECK(close(e.current_A(i, k), I, 1e-14));
      CHECK(close(e.power_W(i, k), drawn(i, k), 1e-13));
    }
    CHECK(close(e.total_power_W[i], total, 1e-13));
  }
  // Energies: the trapezoid over the sample times of each integrand.
  const auto row_sum = [](const RowMatrix& m) { return [&m](int i) { return m.row(i).sum(); }; };
  CHECK(close(e.energy_J, trapezoid_of(run.t, row_sum(drawn)), 1e-12));
  CHECK(close(e.copper_loss_J, trapezoid_of(run.t, row_sum(copper)), 1e-12));
  CHECK(close(e.friction_loss_J, trapezoid_of(run.t, row_sum(friction)), 1e-12));
  const double regenerated = trapezoid_of(run.t, [&](int i) {
    double r = 0.0;
    for (int k = 0; k < J; ++k) r += drive.joints[k].regeneration * std::max(0.0, -P(i, k));
    return r;
  });
  CHECK(regenerated > 0.0);
  CHECK(close(e.regenerated_J, regenerated, 1e-12));
  REQUIRE(e.energy_joint_J.size() == static_cast<std::size_t>(J));
  double per_joint_sum = 0.0;
  for (int k = 0; k < J; ++k) {
    CHECK(
        close(e.energy_joint_J[k], trapezoid_of(run.t, [&](int i) { return drawn(i, k); }), 1e-12));
    per_joint_sum += e.energy_joint_J[k];
  }
  CHECK(close(per_joint_sum, e.energy_J, 1e-12));
  // The cost of transport E / (m g d), g = 9.81 m/s² (docs/theory/conventions.md).
  CHECK(e.cost_of_transport == Approx(e.energy_J / (mass_kg * 9.81 * distance_m)).epsilon(1e-15));
  // Without a thermal window, or with one longer than the run, each joint's windowed RMS is
  // its RMS over the run, sqrt(∫ τ² / duration); joint 4's 0.4 s window is within the brute
  // force's bounds for its column.
  const double duration = run.t.back() - run.t.front();
  REQUIRE(e.rms_torque_Nm.size() == static_cast<std::size_t>(J));
  REQUIRE(e.window_rms_torque_Nm.size() == static_cast<std::size_t>(J));
  REQUIRE(e.continuous_torque_Nm.size() == static_cast<std::size_t>(J));
  for (int k = 0; k < J; ++k) {
    const double ms = trapezoid_of(run.t, [&](int i) { return run.tau(i, k) * run.tau(i, k); });
    CHECK(e.rms_torque_Nm[k] == Approx(std::sqrt(ms / duration)).epsilon(1e-13));
    CHECK(e.continuous_torque_Nm[k] == drive.joints[k].continuous_torque_Nm);
    if (k != 4) {
      CHECK(e.window_rms_torque_Nm[k] == e.rms_torque_Nm[k]);
      continue;
    }
    std::vector<double> column(run.t.size());
    for (int i = 0; i < T; ++i) column[i] = run.tau(i, k);
    const double W = drive.joints[k].thermal_window_s;
    const BruteForce b = brute_force(squared(run.t, column), W, 2e-4);
    const double F = W * std::pow(e.window_rms_torque_Nm[k], 2);
    INFO("joint 4: brute force in [" << b.lower << ", " << b.upper << "], got " << F);
    CHECK(F >= b.lower);
    CHECK(F <= b.upper);
    CHECK(b.upper - b.lower < 1e-2 * b.upper);
    CHECK(e.window_rms_torque_Nm[k] > e.rms_torque_Nm[k]);
  }
}

TEST_CASE("drive: with η = 1 and r = 1 the electrical energy is copper loss plus mechanical",
          "[drive]") {
  // P = R I² + τ q̇ when η = 1, and every negative P returns with r = 1: the energy drawn is
  // the copper loss plus the signed mechanical work ∫ Σ τ q̇, and what returns is ∫ Σ max(0, −P).
  const int J = 18;
  const SyntheticRun run = synthetic_run(80, 11, J);
  const DriveTrainParams drive = varied_drive(1.0, 1.0, J);
  const ElectricalResult e = compute_electrical(drive, run.t, run.qd, run.tau, 3.2, 1.25);
  const double mechanical =
      trapezoid_of(run.t, [&](int i) { return run.tau.row(i).dot(run.qd.row(i)); });
  // The mechanical term is far above the tolerance: the identity is not the copper term alone.
  CHECK(std::abs(mechanical) > 0.1);
  CHECK(close(e.energy_J, e.copper_loss_J + mechanical, 1e-12));
  const double returned = trapezoid_of(run.t, [&](int i) {
    double r = 0.0;
    for (int k = 0; k < J; ++k) {
      const ActuatorParams& a = drive.joints[k];
      const double I = run.tau(i, k) / (a.gear_ratio * a.torque_constant_NmpA);
      r += std::max(0.0, -(a.resistance_ohm * I * I + run.tau(i, k) * run.qd(i, k)));
    }
    return r;
  });
  CHECK(returned > 0.0);
  CHECK(close(e.regenerated_J, returned, 1e-12));
  CHECK(e.cost_of_transport == Approx(e.energy_J / (3.2 * 9.81 * 1.25)).epsilon(1e-15));
}

}  // namespace hexdyn
