#pragma once
/// \file hard_case_checks.hpp
/// Checks shared by the hard-case tests (test_hard_cases.cpp, test_hard_contact.cpp):
/// finiteness and flag consistency of a whole run, and readers of its flags and messages.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/result.hpp"

namespace hexdyn::hard {

inline const std::string kPaper = HEXDYN_SOURCE_DIR "/configs/paper.yaml";

inline Scene paper_with(const std::vector<Override>& overrides) {
  return load_scene(kPaper, overrides);
}

inline bool contains(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

inline std::string num(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

template <typename Matrix>
inline bool finite(const Matrix& m) {
  return m.allFinite();
}
inline bool finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

/// Every dataset of a run is finite: kinematics, torques, forces, penetration, power,
/// energies, solver diagnostics and impact records; statuses are 0 or 1 (never failed)
/// and a message accompanies exactly the relaxed samples.
inline void check_run_finite(const RunResult& r) {
  const KinematicsResult& k = r.kin;
  const DynamicsResult& d = r.dyn;
  REQUIRE(d.present);
  REQUIRE(k.samples() > 1);
  CHECK(finite(k.time_s));
  CHECK(finite(k.base_position));
  CHECK(finite(k.base_linear_velocity));
  CHECK(finite(k.base_linear_acceleration));
  CHECK(finite(k.joint_position));
  CHECK(finite(k.joint_velocity));
  CHECK(finite(k.joint_acceleration));
  CHECK(finite(k.foot_position));
  CHECK(finite(k.foot_velocity));
  CHECK(finite(k.com_position));
  CHECK(finite(d.joint_torque));
  CHECK(finite(d.contact_force));
  CHECK(finite(d.penetration));
  CHECK(d.penetration.minCoeff() >= 0.0);
  CHECK(finite(d.joint_power));
  CHECK(finite(d.total_power_W));
  CHECK(finite(d.energy_joint_J));
  CHECK(finite(d.solver_objective));
  CHECK(std::isfinite(d.energy_total_J));
  CHECK(std::isfinite(d.cost_of_transport));
  for (const ImpactRecord& im : d.impacts) {
    CHECK(std::isfinite(im.t_start_s));
    CHECK(std::isfinite(im.duration_s));
    CHECK(im.duration_s > 0.0);
    CHECK(std::isfinite(im.peak_force_N));
    CHECK(im.peak_force_N > 0.0);
    CHECK(std::isfinite(im.impulse_Ns));
    CHECK(std::isfinite(im.effective_mass_kg));
    CHECK(std::isfinite(im.approach_speed_mps));
  }
  bool statuses_ok = true, messages_ok = true;
  for (int i = 0; i < k.samples(); ++i) {
    statuses_ok = statuses_ok && (d.solver_status[i] == SolverStatus::kOptimal ||
                                  d.solver_status[i] == SolverStatus::kRelaxed);
    messages_ok = messages_ok &&
                  (d.solver_messages[i].empty() == (d.solver_status[i] == SolverStatus::kOptimal));
  }
  CHECK(statuses_ok);
  CHECK(messages_ok);
}

inline int count_status(const RunResult& r, SolverStatus status) {
  return static_cast<int>(
      std::count(r.dyn.solver_status.begin(), r.dyn.solver_status.end(), status));
}

inline int legs_in_phase(const RunResult& r, int i, ContactPhase ph) {
  int n = 0;
  for (int l = 0; l < r.kin.contact_phase.cols(); ++l)
    n += r.kin.contact_phase(i, l) == static_cast<std::int8_t>(ph);
  return n;
}

/// Normal force of foot l at sample i [N]: every foothold is on a tread (normal +z).
inline double normal_force(const RunResult& r, int i, int l) {
  return r.dyn.contact_force(i, 3 * l + 2);
}

inline double sum_force(const RunResult& r, int i, int axis) {
  double s = 0.0;
  for (int l = 0; l < r.kin.contact_phase.cols(); ++l) s += r.dyn.contact_force(i, 3 * l + axis);
  return s;
}

/// The allocation's part of a sample's message: what precedes the required friction's note
/// ("; required friction: ...", pipeline/solve_dynamics.cpp).
inline std::string allocation_part(const std::string& msg) {
  return msg.substr(0, msg.find("; required friction"));
}

/// The number after "NAME by " in the allocation's part of a relaxed message; NaN when NAME is
/// not named.
inline double violation_of(const std::string& message, const std::string& name) {
  const std::string msg = allocation_part(message);
  const auto at = msg.find(name + " by ");
  if (at == std::string::npos) return std::nan("");
  return std::strtod(msg.c_str() + at + name.size() + 4, nullptr);
}

/// The rows named by a relaxed message ("relaxed: A by x, B by y (impact ...)"), in its
/// allocation's part.
inline std::vector<std::string> named_rows(const std::string& message) {
  const std::string msg = allocation_part(message);
  std::vector<std::string> rows;
  std::string body = msg.substr(msg.find(':') + 1);
  body = body.substr(0, body.rfind(" (impact "));
  std::stringstream ss(body);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto by = item.find(" by ");
    std::string name = item.substr(0, by);
    name.erase(0, name.find_first_not_of(' '));
    rows.push_back(name);
  }
  return rows;
}

/// Index of the first sample at time t (±1e-9 s); −1 when none.
inline int sample_at(const RunResult& r, double t) {
  const auto& ts = r.kin.time_s;
  const auto it = std::lower_bound(ts.begin(), ts.end(), t - 1e-9);
  if (it == ts.end() || *it > t + 1e-9) return -1;
  return static_cast<int>(it - ts.begin());
}

/// ∫ Σ|τ ω| dt over [t0, t1] by the trapezoid rule on the samples (t0, t1 are samples).
inline double energy_between(const RunResult& r, double t0, double t1) {
  const int a = sample_at(r, t0), b = sample_at(r, t1);
  REQUIRE(a >= 0);
  REQUIRE(b > a);
  double e = 0.0;
  for (int i = a; i < b; ++i)
    e += 0.5 * (r.dyn.total_power_W[i] + r.dyn.total_power_W[i + 1]) *
         (r.kin.time_s[i + 1] - r.kin.time_s[i]);
  return e;
}

}  // namespace hexdyn::hard
