#pragma once
// Shared set-up of the sweep tests (tests/hexdyn/sweep/test_*.cpp): temporary
// directories, sweep files over the stair base scene, and YAML look-ups.
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/result.hpp"
#include "hexdyn/sweep/spec.hpp"

namespace sweep_test {

namespace fs = std::filesystem;
using namespace hexdyn;

inline const std::string kConfigs = std::string(HEXDYN_SOURCE_DIR) + "/configs";

/// A fresh directory removed with its contents at scope exit.
struct TempDir {
  fs::path path;
  TempDir() {
    static int counter = 0;
    path = fs::temp_directory_path() /
           ("hexdyn_test_sweep_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = path / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
};

/// A sweep file in `dir` over the stair base scene (absolute path), with `body` after
/// the base line.
inline std::string sweep_file(const TempDir& dir, const std::string& body,
                              const std::string& name = "s.yaml") {
  return dir.write(name, "base: " + kConfigs + "/sweeps/stairs_base.yaml\n" + body);
}

inline const std::string kSmallAxes =
    "set:\n  output.grid: uniform\n  motion.cycles: 1\n"
    "axes:\n"
    "  - key: terrain.riser_height\n    range: {from: 0.03, to: 0.06, count: 4}\n"
    "  - key: gait.duty_factor\n    values: [1/2, 2/3, 0.75]\n"
    "  - key: allocation.friction\n    values: [pyramid4, cone]\n";

inline std::string message_of(const std::string& path) {
  try {
    (void)load_sweep(path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

inline YAML::Node at(const YAML::Node& root, const std::string& dotted) {
  YAML::Node cur = YAML::Clone(root);
  std::stringstream ss(dotted);
  std::string key;
  while (std::getline(ss, key, '.')) {
    YAML::Node next = cur[key];
    cur.reset(next);
  }
  return cur;
}

/// A run with torques τ_k(t) = a_k + b_k t on a grid that is uniform except for a dense
/// cluster of samples (as the adaptive grid has at touchdowns), for `joints` joints.
inline hexdyn::RunResult linear_torque_run(double t0, double t1, std::vector<double>& a,
                                           std::vector<double>& b, int joints = 18) {
  std::vector<double> t;
  const int coarse = 2000;
  for (int i = 0; i <= coarse; ++i) t.push_back(t0 + (t1 - t0) * i / coarse);
  for (int i = 1; i < 400; ++i) t.push_back(t0 + 0.3 * (t1 - t0) + 1e-6 * i);  // dense cluster
  std::sort(t.begin(), t.end());
  const int T = static_cast<int>(t.size());
  hexdyn::RunResult r;
  r.kin.time_s = t;
  r.dyn.present = true;
  r.dyn.joint_torque.resize(T, joints);
  a.resize(static_cast<std::size_t>(joints));
  b.resize(static_cast<std::size_t>(joints));
  for (int k = 0; k < joints; ++k) {
    a[k] = 0.3 * (k - 8.5);
    b[k] = 0.1 * ((k * 7) % 5 - 2);
    for (int i = 0; i < T; ++i) r.dyn.joint_torque(i, k) = a[k] + b[k] * t[i];
  }
  r.dyn.solver_status.assign(T, SolverStatus::kOptimal);
  r.dyn.solver_status[3] = SolverStatus::kRelaxed;
  r.dyn.solver_status[4] = SolverStatus::kRelaxed;
  r.dyn.solver_status[9] = SolverStatus::kFailed;
  r.dyn.energy_total_J = 12.5;
  r.dyn.cost_of_transport = 0.8;
  r.dyn.distance_m = 0.25;
  r.dyn.impacts = {{1, 0.1, 1e-3, 40.0, 0.01, 0.1, 0.05}, {3, 0.2, 1e-3, 64.5, 0.01, 0.1, 0.05}};
  return r;
}

}  // namespace sweep_test
