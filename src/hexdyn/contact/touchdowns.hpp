#pragma once
/// \file touchdowns.hpp
/// The contact stage (docs/theory/contact.md): every touchdown of a plan with its
/// transient (impact.hpp), and the contact state of every leg at every sample.
///
/// Contact frame of a foot: n the terrain normal (+z on treads), t1 the world x axis
/// made orthogonal to n, t2 = n × t1.
#include <array>
#include <vector>

#include "hexdyn/contact/impact.hpp"
#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"
#include "hexdyn/core/sizes.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/planning/plan.hpp"

namespace hexdyn {

/// One touchdown and its resolved transient.
struct Touchdown {
  int leg = 0;
  double t_s = 0.0;  ///< the plan's touchdown: the swing's end, where the leg's phase changes
  double approach_speed_mps = 0.0;  ///< foot speed into the terrain along −n
  double effective_mass_kg = 0.0;   ///< 1 / (nᵀ J M_leg⁻¹ Jᵀ n), trunk held fixed
  Vec3 normal_W = Vec3::UnitZ();
  ImpactTransient transient;
  /// Loaded: how long before t_s the foot meets the tread (touchdown_sink over the approach
  /// speed), where the transient's own time starts; its load starts at t_s. 0 otherwise.
  double contact_lead_s() const { return transient.load_delay_s; }
  /// The transient's time from t_s on to its end [s].
  double after_touchdown_s() const { return transient.duration_s - transient.load_delay_s; }
};

/// Effective mass of leg `leg`'s foot along n_W [kg]: the leg's operational-space inertia
/// Λ = (J M_ll⁻¹ Jᵀ)⁻¹ with M_ll the leg's 3×3 joint block of M(q) and J its
/// world-frame foot Jacobian (joint columns) at the contact point on a surface of normal n_W
/// (a sphere foot's, dynamics/rnea.hpp), i.e. the trunk held by the other legs. For a sphere
/// the normal mass is that of its centre: the arm −r n of the contact point is along n
/// (docs/theory/contact.md#touchdown-transient).
/// Uses only the pose of `base`; q: the joint angles [rad] (joints). M_ll and J are the
/// leg's m × m and 3 × m blocks for a leg of m joints.
double foot_effective_mass(const RobotModel& model, RobotData& data, const BaseState& base,
                           const JointVector& q, int leg, const Vec3& n_W);

/// The load a leg takes over at its touchdown at t_s on a surface of normal n_W [N], the input
/// of a loaded transient (docs/theory/contact.md#loaded-touchdowns): of the robot's weight m g,
/// the vertical share of the leg among the feet standing just after t_s (the landing one in,
/// one lifting off at t_s out) that puts no moment about the centre of mass's vertical line,
/// the minimum-norm such shares (least squares when the feet cannot balance it: two feet, or the
/// centre of mass outside their polygon), taken along n_W and at least 0. Quasi-static: the
/// trunk's acceleration is left out.
double touchdown_load_share(const RobotModel& model, RobotData& data, const MotionPlan& plan,
                            double t_s, int leg, const Vec3& n_W);

/// How far below its planned height the robot stands at a foot's planned touchdown at t_s on
/// p_W [m], so how much sooner the foot meets the tread (docs/theory/contact.md#loaded-touchdowns):
/// the plane through the static penetrations (impact.hpp static_penetration) of the feet
/// standing just before t_s under their quasi-static loads (as touchdown_load_share's), at
/// p_W's x and y; at least 0.
double touchdown_sink(const RobotModel& model, RobotData& data, const MotionPlan& plan,
                      const ContactParams& contact, double t_s, const Vec3& p_W);

/// Every touchdown of the plan with its transient integrated (impact.hpp; none for rigid
/// contact; loaded under touchdown_load_share with contact.touchdown: loaded), sorted by time
/// then leg.
std::vector<Touchdown> resolve_touchdowns(const RobotModel& model, RobotData& data,
                                          const MotionPlan& plan, const ContactParams& contact);

/// The /impacts records of the touchdowns whose transient occurred, in their order.
std::vector<ImpactRecord> impact_records(const std::vector<Touchdown>& touchdowns);

/// Contact frame [t1 t2 n] (columns, world axes) for the terrain normal n_W.
Mat3 contact_frame(const Vec3& n_W);

/// Contact state of every leg at one sample: its phase (swing and support from the
/// kinematics; impact while a touchdown transient lasts), the transient's normal force
/// and penetration, and the contact frame of the terrain under the foot; the first legs
/// entries are the robot's.
struct SampleContacts {
  LegArray<ContactPhase> phase{};
  LegArray<double> impact_force_N{};
  LegArray<double> impact_penetration_m{};
  LegArray<Mat3> W_R_contact;
  int impacting_legs = 0;
};
/// Fills `out` for sample i of `kin` (whose contact_phase holds swing/support, as
/// sample_kinematics leaves it; one column per leg).
void sample_contacts(const KinematicsResult& kin, int i, const Terrain& terrain,
                     const std::vector<Touchdown>& touchdowns, SampleContacts& out);

/// The contact state of every sample of a kinematics result.
struct ContactSchedule {
  std::vector<SampleContacts> samples;  ///< T
  RowMatrixI8 phase;                    ///< T×legs, ContactPhase values (/contacts/phase)
};
/// sample_contacts for every sample of `kin`.
ContactSchedule schedule_contacts(const KinematicsResult& kin, const Terrain& terrain,
                                  const std::vector<Touchdown>& touchdowns);

}  // namespace hexdyn
