// A link stretched along its axis (model/link_scaling.hpp, robot.links_follow_length:
// uniform_density) against closed forms of uniform solids computed here: a box and a solid
// cylinder along x, stretched by r about the joint with their cross-section kept, have
// mass r m, COM r x_c, and the textbook moments of the longer solid.
#include <catch2/catch.hpp>
#include <cmath>

#include "hexdyn/model/link_scaling.hpp"

namespace hexdyn {
namespace {

/// A uniform box of density rho over x in [x0, x0 + a], |y| <= b/2, |z| <= c/2 (link frame).
BodyParams box(double rho, double x0, double a, double b, double c) {
  BodyParams p;
  p.mass_kg = rho * a * b * c;
  p.com_m = Vec3(x0 + 0.5 * a, 0.0, 0.0);
  p.inertia_kgm2 = p.mass_kg / 12.0 * Vec3(b * b + c * c, a * a + c * c, a * a + b * b);
  return p;
}

/// A uniform solid cylinder of density rho along x over [x0, x0 + a], radius R, its axis
/// offset by (0, y, z) from the link's x axis.
BodyParams cylinder(double rho, double x0, double a, double R, double y, double z) {
  BodyParams p;
  p.mass_kg = rho * M_PI * R * R * a;
  p.com_m = Vec3(x0 + 0.5 * a, y, z);
  const double m = p.mass_kg;
  p.inertia_kgm2 =
      Vec3(0.5 * m * R * R, m * (3 * R * R + a * a) / 12.0, m * (3 * R * R + a * a) / 12.0);
  return p;
}

void require_close(const BodyParams& got, const BodyParams& want) {
  const double rel = 1e-12;
  CHECK(got.mass_kg == Approx(want.mass_kg).epsilon(rel));
  for (int i = 0; i < 3; ++i) {
    CHECK(got.com_m[i] == Approx(want.com_m[i]).epsilon(rel).margin(1e-15));
    CHECK(got.inertia_kgm2[i] == Approx(want.inertia_kgm2[i]).epsilon(rel));
  }
}

bool triangle_holds(const Vec3& I) {
  return I.x() <= I.y() + I.z() && I.y() <= I.x() + I.z() && I.z() <= I.x() + I.y();
}

TEST_CASE("a stretched uniform box is the longer box", "[model][link_scaling]") {
  // Slender, flat and stubby boxes (the paper's tibia moments are those of a stubby link).
  const double dims[][3] = {{0.12, 0.01, 0.02}, {0.10, 0.03, 0.08}, {0.02, 0.06, 0.05}};
  for (const auto& d : dims) {
    for (double r : {0.4, 0.75, 1.3, 2.5}) {
      INFO("box " << d[0] << " x " << d[1] << " x " << d[2] << ", r = " << r);
      const double rho = 2700.0, x0 = 0.004;
      require_close(stretch_link(box(rho, x0, d[0], d[1], d[2]), r),
                    box(rho, r * x0, r * d[0], d[1], d[2]));
    }
  }
}

TEST_CASE("a stretched offset cylinder is the longer cylinder", "[model][link_scaling]") {
  for (double r : {0.5, 1.5}) {
    INFO("r = " << r);
    const double rho = 1200.0;
    require_close(stretch_link(cylinder(rho, 0.0, 0.1, 0.012, 0.003, -0.005), r),
                  cylinder(rho, 0.0, r * 0.1, 0.012, 0.003, -0.005));
  }
}

TEST_CASE("a slender link: transverse moments grow as r^3, the axial one as r",
          "[model][link_scaling]") {
  const BodyParams rod = cylinder(1000.0, 0.0, 0.2, 1e-5, 0.0, 0.0);
  const double r = 1.7;
  const BodyParams s = stretch_link(rod, r);
  CHECK(s.inertia_kgm2.x() / rod.inertia_kgm2.x() == Approx(r).epsilon(1e-12));
  CHECK(s.inertia_kgm2.y() / rod.inertia_kgm2.y() == Approx(r * r * r).epsilon(1e-8));
  CHECK(s.inertia_kgm2.z() / rod.inertia_kgm2.z() == Approx(r * r * r).epsilon(1e-8));
}

TEST_CASE("stretching keeps physical moments where the slender rule would not",
          "[model][link_scaling]") {
  // The paper's tibia (configs/paper.yaml): Ixx the largest. Scaling Iyy, Izz by r^3 and Ixx
  // by r breaks the triangle inequality at r = 0.6; the stretch keeps it at every r.
  BodyParams tibia;
  tibia.mass_kg = 0.110;
  tibia.inertia_kgm2 = Vec3(9.8e-5, 8.7e-5, 2.1e-5);
  tibia.com_m = Vec3(0.05, 0.0, 0.0);
  const double r = 0.6;
  const Vec3 slender(r * 9.8e-5, r * r * r * 8.7e-5, r * r * r * 2.1e-5);
  CHECK_FALSE(triangle_holds(slender));
  for (double k : {0.2, 0.6, 1.0, 1.8, 4.0}) {
    INFO("r = " << k);
    CHECK(triangle_holds(stretch_link(tibia, k).inertia_kgm2));
  }
}

TEST_CASE("stretches compose, and r = 1 keeps the link bit for bit", "[model][link_scaling]") {
  BodyParams femur;
  femur.mass_kg = 0.041;
  femur.inertia_kgm2 = Vec3(2.0e-5, 8.7e-5, 10.0e-5);
  femur.com_m = Vec3(0.060, 0.001, -0.002);
  const BodyParams same = stretch_link(femur, 1.0);
  CHECK(same.mass_kg == femur.mass_kg);
  CHECK(same.com_m == femur.com_m);
  CHECK(same.inertia_kgm2 == femur.inertia_kgm2);
  require_close(stretch_link(stretch_link(femur, 1.25), 0.8 / 1.25), stretch_link(femur, 0.8));
}

}  // namespace
}  // namespace hexdyn
