#pragma once
/// \file robustness_params.hpp
/// A scene's `robustness:` section (docs/user/robustness.md): the errors a robustness study
/// draws for the worlds it replays a plan on, what counts as a failed climb, and the search for
/// the largest tolerated error. The study itself is robustness/robustness.hpp; the draws
/// robustness/perturbation.hpp.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace hexdyn {

/// The perturbed quantities, in the order of the keys robustness.perturbations.* and of the
/// files' datasets.
enum class Perturbation : std::int8_t {
  kRiserHeight = 0,       ///< each riser's rise, added [m] (stairs)
  kTreadDepth = 1,        ///< each tread's going, added [m] (stairs)
  kNosing = 2,            ///< each nosing's overhang, added [m] (stairs)
  kFriction = 3,          ///< the contact's friction coefficients μ, μ_s and μ_d, added [1]
  kPayloadMass = 4,       ///< a point mass added to the trunk [kg]
  kPayloadCom = 5,        ///< its position from the trunk's centre of mass, trunk frame [m]
  kTrunkMass = 6,         ///< the trunk structure's mass and inertia, relative change [1]
  kLinkMass = 7,          ///< each leg link's mass and inertia, relative change [1]
  kTorqueConstant = 8,    ///< each actuator's k_t (and its torque ratings), relative [1]
  kResistance = 9,        ///< each actuator's winding resistance, relative [1]
  kJointFriction = 10,    ///< each actuator's Coulomb and viscous friction, relative [1]
  kFootPlacement = 11,    ///< the terrain displaced along +y under the plan [m]
  kContactStiffness = 12  ///< the contact's normal stiffness K, relative [1]
};
inline constexpr int kPerturbationCount = 13;

/// How many values one replay draws of a perturbation.
enum class PerturbationExtent : std::int8_t {
  kOnce,      ///< one value
  kPerStep,   ///< one per step of the staircase (each riser of its count or list)
  kPerLink,   ///< one per leg link (the robot's bodies but the trunk)
  kPerJoint,  ///< one per joint
  kXyz,       ///< three components x, y, z
};

/// "riser_height", "tread_depth", ... (the keys robustness.perturbations.*).
const char* perturbation_name(Perturbation p);
/// UDUNITS-2 unit of the drawn error: "m", "kg" or "1".
const char* perturbation_unit(Perturbation p);
PerturbationExtent perturbation_extent(Perturbation p);
/// Whether the error is relative (the quantity × (1 + error)) rather than added.
bool perturbation_relative(Perturbation p);

enum class DistributionKind : std::int8_t { kNone = 0, kNormal = 1, kUniform = 2 };

/// The distribution of one perturbation's error, each value drawn independently.
struct Distribution {
  DistributionKind kind = DistributionKind::kNone;  ///< kNone: the error is 0
  double sigma = 0.0;  ///< normal: standard deviation before truncation (≥ 0)
  double bound = 0.0;  ///< normal: values truncated to [−bound, bound] (> 0 when sigma > 0)
  double low = 0.0, high = 0.0;  ///< uniform on [low, high] (low ≤ high)
  /// The same distribution with every parameter times s ≥ 0 (a tolerance search's scale).
  Distribution scaled(double s) const;
  /// The largest |value| it can draw: bound, or max(|low|, |high|); 0 for kNone.
  double largest_magnitude() const;
  /// The smallest and the largest value it can draw.
  double lowest() const;
  double highest() const;
};

/// Every perturbation's distribution (kNone where the scene does not name it).
struct PerturbationSpec {
  std::array<Distribution, kPerturbationCount> of{};
  const Distribution& operator[](Perturbation p) const { return of[static_cast<std::size_t>(p)]; }
  Distribution& operator[](Perturbation p) { return of[static_cast<std::size_t>(p)]; }
  /// The perturbations that draw (kind other than kNone), in table order.
  std::vector<Perturbation> active() const;
};

/// The stated bounds of a successful climb (robustness.failure.*).
struct FailureBounds {
  /// Largest horizontal distance of the trunk's end from the plan's end [m]; NaN: half the
  /// nominal terrain's shallowest going (replay/replay.hpp arrival_tolerance).
  double drift_m = std::numeric_limits<double>::quiet_NaN();
  double slip_m = 0.02;        ///< largest slip distance of any foot over the replay [m]
  double saturation_s = 0.05;  ///< longest time any joint's drive spends at its bound [s]
  /// A foot the plan has in swing that carries more than stub_force_fraction of the robot's
  /// weight on a face tilted more than this from the horizontal has stubbed its toe [rad].
  double stub_tilt_rad = M_PI / 4.0;
  double stub_force_fraction = 0.01;  ///< [1]
};

/// The search for the largest tolerated error (robustness.tolerance.*;
/// docs/user/robustness.md#tolerated-error): per perturbation of the scene, alone, its
/// distribution scaled by s; the largest s in [0, max_scale] whose `replays` replays succeed
/// with a fraction ≥ `target`, found by bisection (`bisections` halvings after a probe at
/// max_scale), on the same draws at every s (common random numbers).
struct ToleranceSearch {
  bool enabled = false;  ///< robustness.tolerance.replays given
  int replays = 100;
  double max_scale = 4.0;
  int bisections = 5;
  double target = 0.95;
};

/// Largest number of replays of one study (and of one scale of a tolerance search).
inline constexpr int kMaxRobustnessReplays = 1000000;

/// `robustness:` (absent: replays 0, no study in a sweep's scenarios; `hexdyn robustness`
/// then replays kDefaultRobustnessReplays worlds).
struct RobustnessParams {
  int replays = 0;  ///< robustness.replays; 0 when the scene has no robustness section
  std::uint64_t seed = 1;
  PerturbationSpec perturbations;
  FailureBounds failure;
  ToleranceSearch search;
};
inline constexpr int kDefaultRobustnessReplays = 100;

}  // namespace hexdyn
