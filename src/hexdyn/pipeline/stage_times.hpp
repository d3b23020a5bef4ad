#pragma once
/// \file stage_times.hpp
/// Wall time of each stage of one scene, for the per-stage benchmark (bench/bench_sweep_stages.cpp,
/// docs/dev/benchmarks.md#where-a-scenario-spends-its-time). A stage adds to its slot only
/// when the caller passes a StageTimes; without one nothing is timed.
#include <array>
#include <chrono>
#include <string_view>

namespace hexdyn {

enum class Stage {
  kModel,       ///< robot model (build_robot_model)
  kPosture,     ///< automatic posture search (choose_posture)
  kPlanning,    ///< trunk motion and gait with the chosen posture (plan_motion_with)
  kTouchdowns,  ///< touchdown transients (resolve_touchdowns: GSL impact ODE)
  kGrid,        ///< output grid
  kKinematics,  ///< sampled kinematics: IK, joint rates, centre of mass
  kContacts,    ///< contact schedule
  kRnea,        ///< per sample: affine split of the equations of motion (RNEA)
  kAllocation,  ///< per sample: allocation problem, back end's solve, forces and torques
  kVerdict,     ///< per sample: measured violations, status, message, result rows
  kGrip,        ///< per sample: utilised and required friction, slip flags
  kRefinement,  ///< the output grid's error estimates and the gathering of refined samples
  kPower,       ///< joint power, energy, cost of transport
  kAssembly,    ///< the result's remaining fields: URDF text, names, terrain profile
  kCount
};

constexpr std::array<std::string_view, static_cast<int>(Stage::kCount)> kStageNames = {
    "model", "posture",    "planning", "touchdowns", "grid",       "kinematics", "contacts",
    "rnea",  "allocation", "verdict",  "grip",       "refinement", "power",      "assembly"};

struct StageTimes {
  std::array<double, static_cast<int>(Stage::kCount)> seconds{};  ///< [s] per Stage
  double& operator[](Stage s) { return seconds[static_cast<int>(s)]; }
  double operator[](Stage s) const { return seconds[static_cast<int>(s)]; }
};

/// Adds the time from its construction to its destruction to `times[stage]` (nothing when
/// `times` is null).
class StageTimer {
 public:
  StageTimer(StageTimes* times, Stage stage) : times_(times), stage_(stage) {
    if (times_) start_ = std::chrono::steady_clock::now();
  }
  ~StageTimer() {
    if (times_)
      (*times_)[stage_] +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  StageTimes* times_;
  Stage stage_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace hexdyn
