#include "hexdyn/allocation/problem.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <utility>

#include "hexdyn/allocation/friction.hpp"
#include "hexdyn/allocation/goldfarb_idnani.hpp"

namespace hexdyn {
namespace {

int friction_faces(FrictionModel m) {
  switch (m) {
    case FrictionModel::kPyramid4:
      return 4;
    case FrictionModel::kPyramid8:
      return 8;
    case FrictionModel::kCone:
      return 0;
  }
  return 4;
}

/// The row layout as a key (QpProblem::structure): the friction faces per leg in the low
/// byte, then two bits per leg for its phase. Equal keys give equal row kinds and names.
std::uint64_t structure_key(int faces, int legs, std::span<const ContactPhase> phase) {
  std::uint64_t key = static_cast<std::uint64_t>(faces);
  for (int l = 0; l < legs; ++l)
    key |= static_cast<std::uint64_t>(static_cast<std::uint8_t>(phase[l])) << (8 + 2 * l);
  return key;
}

constexpr const char* kTrunkRowNames[AllocationLayout::kTrunkRows] = {
    "trunk force x",  "trunk force y",  "trunk force z",
    "trunk moment x", "trunk moment y", "trunk moment z"};
/// Slack weights (allocation/qp.hpp ineq_penalty) set which rows give way when the
/// constraints cannot all hold: torque limits first (weight 1: the actuators are too
/// weak), then the trunk rows (the prescribed motion cannot be produced, as during a
/// touchdown transient with no other foot on the ground), and the contact rows last
/// (the ground cannot pull; more friction than μ means slipping, which the model
/// excludes).
constexpr double kTrunkRowPenaltyWeight = 1e2;
constexpr double kContactRowPenaltyWeight = 1e3;
/// Impact legs keep a fixed normal force, so their friction limit is a polygon even in
/// the exact-cone model (friction.hpp).
constexpr int kImpactConeFaces = kInscribedConeFaces;
static_assert(AllocationLayout::kTrunkRows == 6 && kImpactConeFaces <= kActiveSetMaxLegFaces &&
                  8 <= kActiveSetMaxLegFaces,
              "the active-set row budget (allocation/goldfarb_idnani.hpp) holds every problem");

/// Σ v_k² and Σ w_k v_k² of n entries, summed in the order Eigen sums a vector of the fixed
/// size n, whatever n (the order the hexapods' fixed 18-vectors were summed in): a dynamic
/// size sums in another order, and the objective's constant would change in its last bits.
template <int N>
double fixed_order_squared_norm(const double* v) {
  return Eigen::Map<const Eigen::Matrix<double, N, 1>>(v).squaredNorm();
}
template <int N>
double fixed_order_weighted_squares(const double* v, const double* w) {
  const Eigen::Map<const Eigen::Matrix<double, N, 1>> a(v), b(w);
  return a.dot(b.cwiseProduct(a));
}
template <int... N>
constexpr auto squared_norm_table(std::integer_sequence<int, N...>) {
  return std::array{&fixed_order_squared_norm<N + 1>...};
}
template <int... N>
constexpr auto weighted_squares_table(std::integer_sequence<int, N...>) {
  return std::array{&fixed_order_weighted_squares<N + 1>...};
}
double squared_norm(const JointVector& v) {
  static constexpr auto kTable = squared_norm_table(std::make_integer_sequence<int, kMaxJoints>{});
  return v.size() ? kTable[static_cast<std::size_t>(v.size() - 1)](v.data()) : 0.0;
}
double weighted_squares(const JointVector& v, const JointVector& w) {
  static constexpr auto kTable =
      weighted_squares_table(std::make_integer_sequence<int, kMaxJoints>{});
  return v.size() ? kTable[static_cast<std::size_t>(v.size() - 1)](v.data(), w.data()) : 0.0;
}

/// Row names, built once for every leg and joint position the capacities allow: building
/// them per sample would cost more than the solve.
struct RowNames {
  /// Joint j of leg l's torque row, by bound kind (DriveRows::bound: the allocation's limit, a
  /// drive's peak, its voltage) and label (joint_name: [0] a leg of three joints, [1] other).
  using LegJointNames = LegArray<std::array<std::string, kMaxLegJoints>>;
  std::array<std::array<LegJointNames, 2>, 3> torque_by_bound;
  LegArray<std::string> normal;
  LegArray<std::array<std::string, kImpactConeFaces>> face;
  RowNames() {
    for (int l = 0; l < kMaxLegs; ++l) {
      for (int j = 0; j < kMaxLegJoints; ++j) {
        for (int label = 0; label < 2; ++label) {
          if (label == 0 && j >= 3) continue;  // a leg of three joints has no fourth
          const std::string torque = "torque " + joint_name(l, j, label == 0 ? 3 : kMaxLegJoints);
          torque_by_bound[0][label][l][j] = torque;
          torque_by_bound[1][label][l][j] = torque + " (peak)";
          torque_by_bound[2][label][l][j] = torque + " (voltage)";
        }
      }
      normal[l] = "normal " + leg_name(l);
      for (int f = 0; f < kImpactConeFaces; ++f)
        face[l][f] = "friction " + leg_name(l) + " face " + std::to_string(f + 1);
    }
  }
  const std::string& torque(int bound, int l, int j, int leg_joints) const {
    return torque_by_bound[bound][leg_joints == 3 ? 0 : 1][l][j];
  }
};
const RowNames& row_names() {
  static const RowNames names;
  return names;
}

/// The variable layout (which legs carry which force components) and the number of
/// inequality rows: six trunk rows, then per leg with variables its torque rows, a support
/// leg's normal force row and its friction faces.
AllocationLayout variable_layout(const AllocationLegs& legs, std::span<const ContactPhase> phase,
                                 std::span<const double> impact_force_N,
                                 std::span<const Mat3> W_R_c, int faces, int& rows) {
  AllocationLayout layout;
  layout.n_legs = legs.legs;
  int n = 0, m_in = AllocationLayout::kTrunkRows;
  for (int l = 0; l < legs.legs; ++l) {
    AllocationLayout::Leg& leg = layout.legs[l];
    leg.W_R_contact = W_R_c[l];
    if (phase[l] == ContactPhase::kSwing) continue;
    const bool support = phase[l] == ContactPhase::kSupport;
    leg.offset = n;
    leg.count = support ? 3 : 2;
    if (!support) leg.known_normal_force_N = impact_force_N[l];
    n += support ? 3 : 2;
    m_in += legs.n_joints[l];  // torque rows
    if (support) m_in += 1;    // normal force row
    m_in += support ? faces : (faces ? faces : kImpactConeFaces);
  }
  layout.variables = n;
  rows = m_in;
  return layout;
}

// At most kMaxLegForces variables: the matrices live on the stack, of which the leading
// joints × variables block is used.
using GMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxJoints,
                              kMaxLegForces>;
using BMatrix = Eigen::Matrix<double, AllocationLayout::kTrunkRows, Eigen::Dynamic, Eigen::ColMajor,
                              AllocationLayout::kTrunkRows, kMaxLegForces>;

/// The problem's linear terms in its variables x (contact-frame forces [N]): joint torques
/// τ = tau_known − G x [N m] and trunk rows B x = trunk_rhs, where the known forces (the
/// impact legs' normal forces, world axes) are already moved to tau_known and trunk_rhs.
struct LinearTerms {
  JointVector tau_known;
  Vec6 trunk_rhs;
  GMatrix G;  ///< joints × variables
  BMatrix B;  ///< 6 × variables
};

template <class Split>
LinearTerms linear_terms(const AllocationLegs& legs, const Split& split,
                         const AllocationLayout& layout, std::span<const ContactPhase> phase,
                         std::span<const double> impact_force_N, std::span<const Mat3> W_R_c) {
  LinearTerms t;
  // Known forces: the normal force of impact legs.
  t.tau_known = split.tau0;
  t.trunk_rhs = split.trunk_rhs;
  for (int l = 0; l < legs.legs; ++l) {
    if (phase[l] != ContactPhase::kImpact) continue;
    const Vec3 F_fixed = impact_force_N[l] * W_R_c[l].col(2);
    t.tau_known -= split.JjT[l] * F_fixed;
    t.trunk_rhs -= split.JbT[l] * F_fixed;
  }
  const int n = layout.variables;
  t.G = GMatrix::Zero(legs.joints, n);
  t.B = BMatrix::Zero(AllocationLayout::kTrunkRows, n);
  for (int l = 0; l < legs.legs; ++l) {
    const AllocationLayout::Leg& leg = layout.legs[l];
    if (leg.offset < 0) continue;
    const int k = leg.count;
    t.G.middleCols(leg.offset, k) = split.JjT[l] * W_R_c[l].leftCols(k);
    t.B.middleCols(leg.offset, k) = split.JbT[l] * W_R_c[l].leftCols(k);
  }
  return t;
}

/// Joint k's torque bounds lower ≤ τ ≤ upper [N m]: a drive's bounds, or ∓ a URDF robot's effort
/// limit or one limit for every joint.
struct TorqueBounds {
  double lower, upper;
};
TorqueBounds joint_torque_bounds(const AllocationParams& alloc, const DriveRows* drive, int k) {
  if (drive) return {drive->lower_Nm[k], drive->limit_Nm[k]};
  const double limit =
      alloc.joint_torque_limit_Nm ? (*alloc.joint_torque_limit_Nm)[k] : alloc.torque_limit_Nm;
  return {-limit, limit};
}

/// A swing leg's torques are constants no force changes: the largest excess over its limit
/// [N m] is kept in the layout, with the row's name.
void note_swing_leg_excess(const AllocationLegs& legs, const AllocationParams& alloc,
                           const DriveRows* drive, const JointVector& tau_known, int l,
                           AllocationLayout& layout) {
  for (int j = 0; j < legs.n_joints[l]; ++j) {
    const int k = legs.first_joint[l] + j;
    const TorqueBounds b = joint_torque_bounds(alloc, drive, k);
    const double excess = std::max(tau_known[k] - b.upper, b.lower - tau_known[k]);
    if (excess > layout.constant_excess_Nm) {
      layout.constant_excess_Nm = excess;
      std::ostringstream os;
      os.precision(3);
      os << "torque " << joint_name(l, j, legs.n_joints[l]) << " (swing leg";
      if (drive && drive->bound[k] != 0) os << ", " << (drive->bound[k] == 1 ? "peak" : "voltage");
      os << ") by " << excess;
      layout.constant_violation = os.str();
    }
  }
}

/// Leg l's rows from `row` on: its torque limits, a support leg's minimum normal force,
/// its friction faces (faces per leg, 0 for the exact cone; friction coefficient mu), and
/// a support leg's second-order cone under the exact cone. Returns the next row.
int add_leg_rows(const AllocationLegs& legs, const AllocationParams& alloc, const DriveRows* drive,
                 const LinearTerms& t, AllocationLayout& layout,
                 std::span<const ContactPhase> phase, std::span<const double> impact_force_N,
                 int faces, double mu, int l, int row, QpProblem& qp) {
  const int o = layout.legs[l].offset;
  const int m = legs.n_joints[l];
  for (int j = 0; j < m; ++j, ++row) {
    const int kk = legs.first_joint[l] + j;
    const TorqueBounds b = joint_torque_bounds(alloc, drive, kk);
    qp.C.row(row) = t.G.row(kk);
    qp.lower[row] = t.tau_known[kk] - b.upper;
    qp.upper[row] = t.tau_known[kk] - b.lower;
    qp.ineq_names[row] = row_names().torque(drive ? drive->bound[kk] : 0, l, j, m);
  }
  const bool support = phase[l] == ContactPhase::kSupport;
  if (support) {
    qp.C(row, o + 2) = 1.0;
    qp.lower[row] = alloc.min_normal_force_N;
    qp.upper[row] = std::numeric_limits<double>::infinity();
    qp.ineq_penalty[row] = kContactRowPenaltyWeight;
    qp.ineq_names[row++] = row_names().normal[l];
  }
  const int nf = faces ? faces : (support ? 0 : kImpactConeFaces);
  AllocationLayout::Leg& leg = layout.legs[l];
  leg.friction_row = nf ? row : -1;
  leg.friction_faces = nf;
  leg.face_reach = nf ? std::cos(M_PI / nf) : 1.0;
  for (int f = 0; f < nf; ++f, ++row) {
    const FrictionFace face = inscribed_friction_face(f, nf, mu);
    qp.C(row, o) = face.cos_a;
    qp.C(row, o + 1) = face.sin_a;
    qp.lower[row] = -std::numeric_limits<double>::infinity();
    if (support) {
      qp.C(row, o + 2) = -face.reach;
      qp.upper[row] = 0.0;
    } else {
      qp.upper[row] = face.reach * impact_force_N[l];
    }
    qp.ineq_penalty[row] = kContactRowPenaltyWeight;
    qp.ineq_names[row] = row_names().face[l][f];
  }
  if (!faces && support) {
    leg.cone = static_cast<int>(qp.cones.size());
    qp.cones.push_back(
        {o, o + 1, o + 2, mu, "friction cone " + leg_name(l), kContactRowPenaltyWeight});
  }
  return row;
}

template <class Split>
AllocationLayout build_problem(const AllocationLegs& legs, const AllocationParams& alloc,
                               const ContactParams& contact, const Split& split,
                               std::span<const ContactPhase> phase,
                               std::span<const double> impact_force_N, std::span<const Mat3> W_R_c,
                               QpProblem& qp, const DriveRows* drive) {
  const int faces = friction_faces(alloc.friction);
  const double mu = contact.friction_coefficient;
  int m_in = 0;
  AllocationLayout layout = variable_layout(legs, phase, impact_force_N, W_R_c, faces, m_in);
  qp.resize(layout.variables, 0, m_in);
  qp.structure = structure_key(faces, legs.legs, phase);
  LinearTerms t = linear_terms(legs, split, layout, phase, impact_force_N, W_R_c);
  if (!drive) {
    // Objective Σ τ² = |tau_known − G x|² = ½ xᵀ (2 GᵀG) x − 2 (Gᵀ tau_known)ᵀ x + |tau_known|².
    qp.H = 2.0 * t.G.transpose() * t.G;
    qp.g = -2.0 * t.G.transpose() * t.tau_known;
    qp.constant = squared_norm(t.tau_known);
  } else {
    // The drive torques τ + offset = (tau_known + offset) − G x: the rows and the objective
    // Σ w (τ + offset)² read the known part shifted by the offset.
    const int J = legs.joints;
    t.tau_known += drive->offset_Nm.head(J);
    const GMatrix WG = drive->weight.head(J).asDiagonal() * t.G;
    qp.H = 2.0 * t.G.transpose() * WG;
    qp.g = -2.0 * WG.transpose() * t.tau_known;
    const JointVector w = drive->weight.head(J);
    qp.constant = weighted_squares(t.tau_known, w);
  }
  int row = 0;
  for (int r = 0; r < AllocationLayout::kTrunkRows; ++r, ++row) {
    qp.C.row(row) = t.B.row(r);
    qp.lower[row] = qp.upper[row] = t.trunk_rhs[r];
    qp.ineq_names[row] = kTrunkRowNames[r];
    qp.ineq_penalty[row] = kTrunkRowPenaltyWeight;
  }
  for (int l = 0; l < legs.legs; ++l) {
    if (layout.legs[l].offset < 0)
      note_swing_leg_excess(legs, alloc, drive, t.tau_known, l, layout);
    else
      row =
          add_leg_rows(legs, alloc, drive, t, layout, phase, impact_force_N, faces, mu, l, row, qp);
  }
  return layout;
}

}  // namespace

AllocationLegs allocation_legs(const RobotModel& model) {
  AllocationLegs legs;
  legs.legs = model.legs();
  legs.joints = model.joints();
  for (int l = 0; l < model.legs(); ++l) {
    legs.first_joint[l] = model.joint(l, 0);
    legs.n_joints[l] = model.leg(l).n_joints;
  }
  return legs;
}

AllocationLegs uniform_allocation_legs(int legs, int leg_joints) {
  AllocationLegs out;
  out.legs = legs;
  out.joints = legs * leg_joints;
  for (int l = 0; l < legs; ++l) {
    out.first_joint[l] = l * leg_joints;
    out.n_joints[l] = leg_joints;
  }
  return out;
}

AllocationLayout build_allocation_problem(const AllocationLegs& legs, const AllocationParams& alloc,
                                          const ContactParams& contact, const ContactSplit& split,
                                          std::span<const ContactPhase> phase,
                                          std::span<const double> impact_force_N,
                                          std::span<const Mat3> W_R_contact, QpProblem& qp,
                                          const DriveRows* drive) {
  return build_problem(legs, alloc, contact, split, phase, impact_force_N, W_R_contact, qp, drive);
}

AllocationLayout build_allocation_problem(const AllocationParams& alloc,
                                          const ContactParams& contact, const ContactSplit& split,
                                          std::span<const ContactPhase> phase,
                                          std::span<const double> impact_force_N,
                                          std::span<const Mat3> W_R_contact, QpProblem& qp,
                                          const DriveRows* drive) {
  const int joints = static_cast<int>(split.tau0.size());
  const AllocationLegs legs = uniform_allocation_legs(joints / 3, 3);
  return build_problem(legs, alloc, contact, split, phase, impact_force_N, W_R_contact, qp, drive);
}

}  // namespace hexdyn
