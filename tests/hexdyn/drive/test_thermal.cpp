// The three-phase drive and the thermal model (drive/drive.hpp, drive/thermal.hpp,
// docs/theory/drive-train.md) against second computations written here: the winding's
// step and ramp responses from the scalar second-order equation of the two-node network
// and its roots, the time to the limit by bisection on that closed form, the peak between
// samples against a fine grid; the field-oriented torque bound against the formula of MIT's
// ActuatorModel (mit-biomimetics/Cheetah-Software, common/include/Dynamics/ActuatorModel.h)
// with its constants mapped by the amplitude-invariant convention, on a grid of speeds in
// both directions; one motor stated in either convention gives the same bound and losses.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "hexdyn/drive/drive.hpp"
#include "hexdyn/drive/thermal.hpp"

namespace hexdyn {
namespace {

/// A two-node network of round numbers: winding 1.5 K/W to the housing, 12 J/K; housing
/// 4 K/W to the ambient at 20 °C, 60 J/K.
ThermalParams network() {
  ThermalParams p;
  p.present = true;
  p.winding_housing_KpW = 1.5;
  p.winding_capacity_JpK = 12.0;
  p.housing_ambient_KpW = 4.0;
  p.housing_capacity_JpK = 60.0;
  p.ambient_degC = 20.0;
  return p;
}

/// The winding's rise x(t) over the ambient under the loss P(t) = p0 + α t from rest, solved
/// here as the scalar equation x'' − tr x' + det x = (P' − a₂₂ P) / C_w of the network
/// (the housing eliminated), with x(0) = 0, x'(0) = p0 / C_w.
struct WindingRise {
  double s1 = 0.0, s2 = 0.0, c0 = 0.0, c1 = 0.0, k1 = 0.0, k2 = 0.0;
  WindingRise(const ThermalParams& p, double p0, double alpha) {
    const double R1 = p.winding_housing_KpW, C1 = p.winding_capacity_JpK;
    const double R2 = p.housing_ambient_KpW, C2 = p.housing_capacity_JpK;
    const double a11 = -1.0 / (R1 * C1), a12 = 1.0 / (R1 * C1);
    const double a21 = 1.0 / (R1 * C2), a22 = -1.0 / (R1 * C2) - 1.0 / (R2 * C2);
    const double tr = a11 + a22, det = a11 * a22 - a12 * a21;
    const double root = std::sqrt(tr * tr - 4.0 * det);
    s1 = 0.5 * (tr - root);
    s2 = det / s1;
    // Particular solution c1 t + c0 of the right side (α − a22 (p0 + α t)) / C1.
    c1 = -a22 * alpha / (C1 * det);
    c0 = ((alpha - a22 * p0) / C1 + tr * c1) / det;
    // k1 + k2 = −c0 and s1 k1 + s2 k2 = p0 / C1 − c1.
    const double d0 = -c0, d1 = p0 / C1 - c1;
    k1 = (d1 - s2 * d0) / (s1 - s2);
    k2 = d0 - k1;
  }
  double operator()(double t) const {
    return c1 * t + c0 + k1 * std::exp(s1 * t) + k2 * std::exp(s2 * t);
  }
};

/// Sample times over [0, end]: uneven steps of 0.2 to 3 s, the end included.
std::vector<double> uneven_times(double end, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> step(0.2, 3.0);
  std::vector<double> t{0.0};
  while (t.back() < end) t.push_back(std::min(end, t.back() + step(rng)));
  return t;
}

/// MIT's ActuatorModel::getTorque (friction off), written out: the joint torque the actuator
/// gives for a desired joint torque tau_des at joint speed qd.
double mit_torque(double tau_des, double qd, double gr, double kt, double R, double V,
                  double tau_max) {
  const double i_des = tau_des / gr / (kt * 1.5);
  const double bemf = qd * gr * kt * 2.0;
  const double v = std::clamp(i_des * R + bemf, -V, V);
  return gr * std::clamp(1.5 * kt * (v - bemf) / R, -tau_max, tau_max);
}

}  // namespace

TEST_CASE("thermal: the step response is the network's closed form", "[drive][thermal]") {
  const ThermalParams p = network();
  const double P = 10.0;
  const std::vector<double> t = uneven_times(2000.0, 7);
  const std::vector<double> loss(t.size(), P);
  const ThermalTrace trace = simulate_thermal(p, t, loss.data(), 1);
  const WindingRise rise(p, P, 0.0);
  int checked = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < 0.5) continue;
    const double want = rise(t[i]);
    CAPTURE(t[i], want);
    CHECK(std::abs(trace.winding_degC[i] - p.ambient_degC - want) <= 1e-12 * want);
    ++checked;
  }
  CHECK(checked > 600);
  // The steady rise P (R_wh + R_ha) = 55 K is approached: the last sample is within 1 %.
  CHECK(trace.winding_degC.back() - p.ambient_degC > 0.99 * 55.0);
  // Monotone: the peak is the last sample; no limit given: never reached.
  CHECK(trace.peak_winding_degC == Approx(trace.winding_degC.back()).epsilon(1e-15));
  CHECK(trace.time_to_limit_s == std::numeric_limits<double>::infinity());
  CHECK_FALSE(trace.reached);
}

TEST_CASE("thermal: a ramp of loss is integrated exactly whatever the step", "[drive][thermal]") {
  const ThermalParams p = network();
  const double p0 = 2.0, alpha = 0.05;  // W, W/s
  const WindingRise rise(p, p0, alpha);
  for (unsigned seed : {1u, 2u}) {
    const std::vector<double> t = uneven_times(400.0, seed);
    std::vector<double> loss(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) loss[i] = p0 + alpha * t[i];
    const ThermalTrace trace = simulate_thermal(p, t, loss.data(), 1);
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (t[i] < 2.0) continue;
      const double want = rise(t[i]);
      CAPTURE(seed, t[i], want);
      CHECK(std::abs(trace.winding_degC[i] - p.ambient_degC - want) <= 1e-12 * want);
    }
  }
}

TEST_CASE("thermal: the time to the limit is the closed form's crossing", "[drive][thermal]") {
  ThermalParams p = network();
  p.limit_degC = 60.0;  // a rise of 40 K of the 55 K the step reaches
  const double P = 10.0;
  const std::vector<double> t = uneven_times(600.0, 11);
  const std::vector<double> loss(t.size(), P);
  const ThermalTrace trace = simulate_thermal(p, t, loss.data(), 1);
  const WindingRise rise(p, P, 0.0);
  double lo = 0.0, hi = 600.0;  // the rise grows monotonically: bisect it here
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (rise(mid) < p.limit_degC - p.ambient_degC ? lo : hi) = mid;
  }
  REQUIRE(trace.reached);
  CHECK(trace.time_to_limit_s == Approx(hi).epsilon(1e-9));
  // A limit above the steady rise is never reached.
  p.limit_degC = 80.0;
  const ThermalTrace never = simulate_thermal(p, t, loss.data(), 1);
  CHECK_FALSE(never.reached);
  CHECK(never.time_to_limit_s == std::numeric_limits<double>::infinity());
}

TEST_CASE("thermal: the peak between two samples is found", "[drive][thermal]") {
  // 30 W for 20 s, then down to 0 over one coarse interval of 40 s: the winding peaks
  // inside it. The same loss on a grid 4000 times finer has its largest sample there.
  const ThermalParams p = network();
  const auto loss_at = [](double t) {
    return t <= 20.0 ? 30.0 : std::max(0.0, 30.0 - 0.75 * (t - 20.0));
  };
  const std::vector<double> coarse{0.0, 10.0, 20.0, 60.0, 100.0};
  std::vector<double> fine;
  for (int i = 0; i <= 400000; ++i) fine.push_back(100.0 * i / 400000.0);
  std::vector<double> lc, lf;
  for (double x : coarse) lc.push_back(loss_at(x));
  for (double x : fine) lf.push_back(loss_at(x));
  const ThermalTrace a = simulate_thermal(p, coarse, lc.data(), 1);
  const ThermalTrace b = simulate_thermal(p, fine, lf.data(), 1);
  const double fine_peak = *std::max_element(b.winding_degC.begin(), b.winding_degC.end());
  const double coarse_samples = *std::max_element(a.winding_degC.begin(), a.winding_degC.end());
  CHECK(a.peak_winding_degC > coarse_samples + 1.0);  // between samples, well above them
  const double rise = fine_peak - p.ambient_degC;
  CHECK(a.peak_winding_degC >= fine_peak - 1e-11 * rise);
  CHECK(a.peak_winding_degC - fine_peak <= 1e-9 * rise);
}

TEST_CASE("drive: the three-phase bound is MIT's ActuatorModel on a grid of speeds",
          "[drive][voltage]") {
  // Mini Cheetah's constants (MiniCheetah.h): kt 0.05, R 0.173, 24 V, 3 N m at the motor, 6:1.
  const double kt = 0.05, R = 0.173, V = 24.0, tau_max = 3.0;
  for (double gr : {6.0, 9.33}) {
    ActuatorParams a;
    a.winding = Winding::kThreePhaseAmplitude;
    a.gear_ratio = gr;
    a.torque_constant_NmpA = 1.5 * kt;  // per ampere of q-axis amplitude
    a.resistance_ohm = 0.5 * R;         // per phase: R is line to line
    a.voltage_V = V;
    a.voltage_utilization = 0.5;  // the phase amplitude V / 2
    a.peak_torque_Nm = gr * tau_max;
    int voltage_bound = 0, peak_bound = 0, beyond_no_load = 0;
    for (int i = -600; i <= 600; ++i) {
      const double qd = 0.1 * i;  // rad/s at the joint, ±60 (no load near ±40 and ±26)
      const DriveLimit lim = drive_torque_limit(a, qd);
      const double up = mit_torque(1e9, qd, gr, kt, R, V, tau_max);
      const double down = mit_torque(-1e9, qd, gr, kt, R, V, tau_max);
      CAPTURE(gr, qd, up, down);
      CHECK(std::abs(lim.limit_Nm - up) <= 1e-12 * std::max(1.0, std::abs(up)));
      CHECK(std::abs(lim.lower_Nm - down) <= 1e-12 * std::max(1.0, std::abs(down)));
      voltage_bound += std::abs(up) < gr * tau_max * (1 - 1e-9) ? 1 : 0;
      peak_bound += std::abs(up) == gr * tau_max ? 1 : 0;
      beyond_no_load += up < 0.0 || down > 0.0 ? 1 : 0;
    }
    // Each regime is on the grid: the peak, the voltage line, a speed past no load.
    CHECK(voltage_bound > 100);
    CHECK(peak_bound > 100);
    CHECK(beyond_no_load > 50);
  }
}

TEST_CASE("drive: one motor stated amplitude- or power-invariant gives the same drive",
          "[drive][voltage]") {
  ActuatorParams amp;
  amp.winding = Winding::kThreePhaseAmplitude;
  amp.gear_ratio = 9.0;
  amp.torque_constant_NmpA = 0.025;
  amp.resistance_ohm = 0.23;
  amp.voltage_V = 24.0;
  amp.voltage_utilization = 0.5;
  amp.gear_efficiency = 0.9;
  amp.regeneration = 0.5;
  ActuatorParams pow = amp;
  pow.winding = Winding::kThreePhasePower;
  pow.torque_constant_NmpA = amp.torque_constant_NmpA / std::sqrt(1.5);  // I' = √(3/2) I
  // DC of the same k_t and R: copper loss R I², a third less.
  ActuatorParams dc = amp;
  dc.winding = Winding::kDc;
  for (double qd : {-30.0, -3.0, 0.0, 2.0, 25.0}) {
    const DriveLimit la = drive_torque_limit(amp, qd), lp = drive_torque_limit(pow, qd);
    CHECK(la.limit_Nm == Approx(lp.limit_Nm).epsilon(1e-13));
    CHECK(la.lower_Nm == Approx(lp.lower_Nm).epsilon(1e-13));
    for (double tau : {-2.0, -0.3, 0.7, 2.2}) {
      const double Ia = motor_current(amp, tau, qd), Ip = motor_current(pow, tau, qd);
      CHECK(Ip == Approx(std::sqrt(1.5) * Ia).epsilon(1e-14));
      CHECK(copper_loss(amp, Ia) == Approx(copper_loss(pow, Ip)).epsilon(1e-13));
      CHECK(copper_loss(amp, Ia) == Approx(1.5 * copper_loss(dc, Ia)).epsilon(1e-15));
      CHECK(electrical_power(amp, tau, qd) ==
            Approx(electrical_power(pow, tau, qd)).epsilon(1e-13));
    }
  }
  CHECK(copper_loss_weight(amp) == Approx(copper_loss_weight(pow)).epsilon(1e-13));
  CHECK(copper_loss_weight(amp) == Approx(1.5 * copper_loss_weight(dc)).epsilon(1e-15));
}

}  // namespace hexdyn
