#include "hexdyn/model/link_scaling.hpp"

namespace hexdyn {

BodyParams stretch_link(const BodyParams& ref, double ratio) {
  if (ratio == 1.0) return ref;
  const double r = ratio, r3 = ratio * ratio * ratio;
  const Vec3& I = ref.inertia_kgm2;
  // Second moments of mass about the COM along the link axes (file comment).
  const double sxx = 0.5 * (I.y() + I.z() - I.x());
  const double syy = 0.5 * (I.x() + I.z() - I.y());
  const double szz = 0.5 * (I.x() + I.y() - I.z());
  BodyParams out;
  out.mass_kg = r * ref.mass_kg;
  out.com_m = Vec3(r * ref.com_m.x(), ref.com_m.y(), ref.com_m.z());
  // I_xx' = r (Σ_yy + Σ_zz) = r I_xx, taken as the latter: no cancellation for a slender link.
  out.inertia_kgm2 = Vec3(r * I.x(), r3 * sxx + r * szz, r3 * sxx + r * syy);
  return out;
}

}  // namespace hexdyn
