#include "hexdyn/robustness/world.hpp"

#include <algorithm>
#include <cmath>

#include "hexdyn/core/stairs.hpp"
#include "hexdyn/planning/terrain.hpp"

namespace hexdyn {
namespace {

using P = Perturbation;

bool any_nonzero(const std::vector<double>& v) {
  return std::any_of(v.begin(), v.end(), [](double x) { return x != 0.0; });
}

/// `part` with its mass and inertia times s (its centre of mass kept): what a relative change
/// s of a body adds to the body that holds it (combine_inertias is linear in the masses, so a
/// negative s removes that share exactly).
RigidInertia scaled_part(const RigidInertia& part, double s) {
  RigidInertia r = part;
  r.mass_kg *= s;
  r.inertia_com *= s;
  return r;
}

void perturb_terrain(World& w, const ReplayPlan& plan, const WorldDraw& d) {
  const bool steps = any_nonzero(d[P::kRiserHeight]) || any_nonzero(d[P::kTreadDepth]) ||
                     any_nonzero(d[P::kNosing]);
  const double shift = d[P::kFootPlacement].front();
  if (!steps && shift == 0.0) return;  // the plan's profile, bit for bit
  TerrainParams& t = w.terrain;
  if (steps) {
    std::vector<StairStep> list = stair_step_list(t);
    for (std::size_t k = 0; k < list.size(); ++k) {
      list[k].riser_m += d[P::kRiserHeight][k];
      list[k].tread_m += d[P::kTreadDepth][k];
      list[k].nosing_m += d[P::kNosing][k];
    }
    t.step_list = std::move(list);
  }
  if (t.type == TerrainType::kStairs) t.first_riser_y_m += shift;
  if (t.type == TerrainType::kSlope) t.slope_origin_y_m += shift;
  if (t.type == TerrainType::kHeightMap && shift != 0.0) {
    auto map = std::make_shared<HeightMap>(*t.map);
    map->y0_m += shift;
    t.map = map;
    w.terrain_map = map;
  }
  TerrainProfile profile = terrain_profile(t, plan.terrain_y_m.front(), plan.terrain_y_m.back());
  w.terrain_y_m = std::move(profile.y_m);
  w.terrain_z_m = std::move(profile.z_m);
}

void perturb_masses(RobotModel& m, const WorldDraw& d) {
  const double trunk = d[P::kTrunkMass].front();
  if (trunk != 0.0) m.inertia[0] = combine_inertias(m.inertia[0], scaled_part(m.trunk_only, trunk));
  const std::vector<double>& link = d[P::kLinkMass];
  for (int b = 1; b < m.bodies(); ++b) {
    const double s = link[static_cast<std::size_t>(b - 1)];
    if (s == 0.0) continue;
    m.inertia[b].mass_kg *= 1.0 + s;
    m.inertia[b].inertia_com *= 1.0 + s;
  }
  const double payload = d[P::kPayloadMass].front();
  if (payload != 0.0) {
    RigidInertia point;
    point.mass_kg = payload;
    const std::vector<double>& c = d[P::kPayloadCom];
    point.com_m = m.trunk_only.com_m + Vec3(c[0], c[1], c[2]);
    m.inertia[0] = combine_inertias(m.inertia[0], point);
  }
  m.total_mass_kg = 0.0;
  for (int b = 0; b < m.bodies(); ++b) m.total_mass_kg += m.inertia[b].mass_kg;
}

void perturb_drives(RobotModel& m, const WorldDraw& d) {
  if (!m.drive.present) return;
  for (int j = 0; j < m.joints(); ++j) {
    ActuatorParams& a = m.drive.joints[static_cast<std::size_t>(j)];
    const auto k = static_cast<std::size_t>(j);
    const double kt = 1.0 + d[P::kTorqueConstant][k];
    a.torque_constant_NmpA *= kt;  // a current-limited drive: its torque ratings with k_t
    a.peak_torque_Nm *= kt;
    a.continuous_torque_Nm *= kt;
    a.resistance_ohm *= 1.0 + d[P::kResistance][k];
    a.coulomb_friction_Nm *= 1.0 + d[P::kJointFriction][k];
    a.viscous_friction_Nmsprad *= 1.0 + d[P::kJointFriction][k];
  }
}

}  // namespace

DrawSizes world_draw_sizes(const RobotModel& model, const TerrainParams& terrain) {
  return {static_cast<int>(stair_step_list(terrain).size()), model.bodies() - 1, model.joints()};
}

World perturbed_world(const RobotModel& model, const ContactParams& contact,
                      const TerrainParams& terrain, const ReplayPlan& plan, const WorldDraw& d) {
  World w{model, contact, terrain, plan.terrain_y_m, plan.terrain_z_m, plan.terrain_map};
  perturb_terrain(w, plan, d);
  perturb_masses(w.model, d);
  perturb_drives(w.model, d);
  const double mu = d[P::kFriction].front();
  w.contact.friction_coefficient += mu;
  w.contact.static_friction += mu;
  w.contact.dynamic_friction += mu;
  w.contact.stiffness *= 1.0 + d[P::kContactStiffness].front();
  return w;
}

}  // namespace hexdyn
