#pragma once
/// \file dynamics_stage.hpp
/// The dynamic half of the pipeline (DESIGN.md §3): touchdown transients, per-sample
/// torque-optimal foot-force allocation, joint power and energy.
///
/// Contact frame of a foot: n the terrain normal (+z on treads), t1 the world x axis
/// made orthogonal to n, t2 = n × t1. Allocation variables per sample, stacked by leg:
/// (f_t1, f_t2, f_n) for a support leg, (f_t1, f_t2) for a leg in its impact transient
/// (f_n is the transient's force, a known input), nothing for a swing leg (F = 0).
#include <memory>
#include <vector>

#include "hexdyn/allocation/backends.hpp"
#include "hexdyn/contact/impact.hpp"
#include "hexdyn/dynamics/rnea.hpp"
#include "hexdyn/kinematics/kinematics.hpp"
#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// One touchdown and its resolved transient.
struct Touchdown {
  int leg = 0;
  double t_s = 0.0;                  ///< instant the foot reaches the terrain
  double approach_speed_mps = 0.0;   ///< foot speed into the terrain along −n
  double effective_mass_kg = 0.0;    ///< 1 / (nᵀ J M_leg⁻¹ Jᵀ n), trunk held fixed
  Vec3 normal_W = Vec3::UnitZ();
  ImpactTransient transient;
};

/// Effective mass of leg `leg`'s foot along n_W: the leg's operational-space inertia
/// Λ = (J M_ll⁻¹ Jᵀ)⁻¹ with M_ll the leg's 3×3 joint block of M(q) and J its
/// world-frame foot Jacobian (joint columns), i.e. the trunk held by the other legs.
double foot_effective_mass(const RobotModel& model, RobotData& data, const BaseState& base,
                           const VecJ& q, int leg, const Vec3& n_W);

/// Every touchdown of the plan with its transient integrated (contact.hpp).
std::vector<Touchdown> resolve_touchdowns(const RobotModel& model, RobotData& data,
                                          const MotionPlan& plan, const ContactParams& contact);

/// The trunk state of sample i of a kinematics result.
BaseState base_state_at(const KinematicsResult& kin, int i);

/// Contact state of every leg at one sample: its phase (swing and support from the
/// kinematics; impact while a touchdown transient lasts), the transient's normal force
/// and penetration, and the contact frame of the terrain under the foot.
struct SampleContacts {
  std::array<ContactPhase, kLegs> phase{};
  std::array<double, kLegs> impact_force_N{};
  std::array<double, kLegs> impact_penetration_m{};
  std::array<Mat3, kLegs> W_R_contact;
  int impacting_legs = 0;
};
/// Fills `out` for sample i of `kin` (whose contact_phase holds swing/support).
void sample_contacts(const KinematicsResult& kin, int i, const Terrain& terrain,
                     const std::vector<Touchdown>& touchdowns, SampleContacts& out);

/// Builds the allocation problem of one sample. Legs in `phase` kSwing carry no force,
/// kImpact legs carry the known normal force `impact_force_N[l]`. `layout_offset[l]`
/// receives the index of the leg's first variable (−1 without variables).
/// Returns the largest excess of a swing-leg torque over the limit (constant rows that no
/// force can change), 0 when none; `*constant_violation` names it.
double build_allocation_problem(const AllocationParams& alloc, const ContactParams& contact,
                                const ContactSplit& split,
                                const std::array<ContactPhase, kLegs>& phase,
                                const std::array<double, kLegs>& impact_force_N,
                                const std::array<Mat3, kLegs>& W_R_contact, QpProblem& qp,
                                std::array<int, kLegs>& layout_offset,
                                std::string* constant_violation);

/// Foot forces (world) and joint torques of a solution x of build_allocation_problem.
void forces_from_solution(const ContactSplit& split, const std::array<ContactPhase, kLegs>& phase,
                          const std::array<double, kLegs>& impact_force_N,
                          const std::array<Mat3, kLegs>& W_R_contact,
                          const std::array<int, kLegs>& layout_offset, const Eigen::VectorXd& x,
                          std::array<Vec3, kLegs>& F_W, VecJ& tau);

/// Contact frame [t1 t2 n] (columns, world axes) for the terrain normal n_W.
Mat3 contact_frame(const Vec3& n_W);

/// Runs contact, allocation and power over the samples of `kin` (whose contact_phase is
/// updated with the impact windows). `log` receives one line per episode of relaxed or
/// failed samples (may be null).
DynamicsResult solve_dynamics(const Scene& scene, const RobotModel& model, const MotionPlan& plan,
                              KinematicsResult& kin, const std::vector<Touchdown>& touchdowns,
                              std::ostream* log);

/// The limit from the left of |τ_k ω_k| [W] (18) at sample `index`, the first sample of
/// a new contact phase (a touchdown, the end of its transient, a lift-off): the power
/// just before the event, where the sampled series holds the value just after it.
struct PowerJump {
  int index = 0;
  VecJ abs_power_left_W = VecJ::Zero();
};

/// Joint power P = τ ω, total P_in = Σ|τ ω|, energies per joint E_k = ∫ |τ_k ω_k| dt and
/// in total E = Σ E_k (= ∫ P_in dt), and the cost of transport E/(m g d). The power jumps
/// at contact events, so each integral is taken piece by piece between the samples of
/// `jumps` (sorted by index), each piece ending on the jump's left limit (integrate_pieces).
void compute_power(const KinematicsResult& kin, double total_mass_kg, double distance_m,
                   const std::vector<PowerJump>& jumps, DynamicsResult& dyn);

/// ∫ y dt over the samples t (increasing), y[k·stride], split into pieces at the samples
/// `break_index` (increasing): the piece ending at break k uses `left_value[k]` there in
/// place of the sample, and the next piece starts from the sample. Within a piece: the
/// integral of GSL's Steffen interpolant (a monotone piecewise cubic: third order where
/// the series is smooth, never below 0 for data ≥ 0 and no overshoot at the kinks of
/// |τ ω|); the trapezoid for a piece of one interval.
double integrate_pieces(const std::vector<double>& t, const double* y, int stride,
                        const std::vector<int>& break_index, const std::vector<double>& left_value);

/// integrate_pieces without breaks.
double integrate_series(const std::vector<double>& t, const double* y, int stride = 1);

}  // namespace hexdyn
