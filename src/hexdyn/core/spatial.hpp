#pragma once
/// \file spatial.hpp
/// Minimal spatial (6D) algebra for the dynamics algorithms, after Featherstone,
/// "Rigid Body Dynamics Algorithms" (2008), ch. 2, on fixed-size Eigen types.
///
/// Conventions
///  - A motion vector (twist, spatial velocity or acceleration) is stored as its
///    angular part ω and its linear part v, where v is the velocity of the body-fixed
///    point that currently coincides with the origin of the frame of expression.
///    The 6-vector form is Featherstone's order [ω; v].
///  - A force vector (wrench, momentum) is stored as its moment n about the origin of
///    the frame of expression and its force f. The 6-vector form is [n; f].
///  - A `Transform` A_X_B is the pose of frame B in frame A: rotation A_R_B (B → A)
///    and p = origin of B expressed in A [m]. `apply` maps B-coordinates to
///    A-coordinates, `apply_inverse` maps A-coordinates to B-coordinates.
///  - A spatial inertia is kept as (mass, centre of mass, rotational inertia about the
///    centre of mass), all in the frame of expression (Pinocchio's representation).
///
/// Everything here is inline, fixed-size and allocation-free.
#include "hexdyn/core/common.hpp"

namespace hexdyn {

/// Skew-symmetric matrix: skew(a) b = a × b.
inline Mat3 skew(const Vec3& a) {
  Mat3 S;
  S << 0.0, -a.z(), a.y(),  //
      a.z(), 0.0, -a.x(),   //
      -a.y(), a.x(), 0.0;
  return S;
}

/// Spatial motion vector: angular [rad/s] and linear [m/s] parts (or their rates).
struct Motion {
  Vec3 angular = Vec3::Zero();
  Vec3 linear = Vec3::Zero();

  static Motion Zero() { return Motion{}; }
  /// From a 6-vector in Featherstone order [ω; v].
  static Motion from_vector(const Vec6& m) { return Motion{m.head<3>(), m.tail<3>()}; }
  /// Featherstone order [ω; v].
  Vec6 vector() const {
    Vec6 m;
    m << angular, linear;
    return m;
  }
  Motion& operator+=(const Motion& o) {
    angular += o.angular;
    linear += o.linear;
    return *this;
  }
};

inline Motion operator+(const Motion& a, const Motion& b) {
  return Motion{a.angular + b.angular, a.linear + b.linear};
}
inline Motion operator-(const Motion& a, const Motion& b) {
  return Motion{a.angular - b.angular, a.linear - b.linear};
}
inline Motion operator*(double s, const Motion& m) { return Motion{s * m.angular, s * m.linear}; }

/// Spatial force vector: moment about the frame origin [N m] and force [N]
/// (or angular momentum [kg m²/s] and linear momentum [kg m/s]).
struct Force {
  Vec3 angular = Vec3::Zero();
  Vec3 linear = Vec3::Zero();

  static Force Zero() { return Force{}; }
  /// From a 6-vector in Featherstone order [n; f].
  static Force from_vector(const Vec6& f) { return Force{f.head<3>(), f.tail<3>()}; }
  /// Featherstone order [n; f].
  Vec6 vector() const {
    Vec6 f;
    f << angular, linear;
    return f;
  }
  Force& operator+=(const Force& o) {
    angular += o.angular;
    linear += o.linear;
    return *this;
  }
  Force& operator-=(const Force& o) {
    angular -= o.angular;
    linear -= o.linear;
    return *this;
  }
};

inline Force operator+(const Force& a, const Force& b) {
  return Force{a.angular + b.angular, a.linear + b.linear};
}
inline Force operator-(const Force& a, const Force& b) {
  return Force{a.angular - b.angular, a.linear - b.linear};
}
inline Force operator*(double s, const Force& f) { return Force{s * f.angular, s * f.linear}; }

/// Power of a force on a motion, f · m (scalar pairing of the dual spaces) [W].
inline double dot(const Force& f, const Motion& m) {
  return f.angular.dot(m.angular) + f.linear.dot(m.linear);
}

/// Motion cross product a × m (Featherstone's crm(a) m): rate of change of the motion
/// vector m, fixed in a frame moving with a.
inline Motion cross(const Motion& a, const Motion& m) {
  return Motion{a.angular.cross(m.angular), a.angular.cross(m.linear) + a.linear.cross(m.angular)};
}

/// Force cross product a ×* f (Featherstone's crf(a) f).
inline Force cross(const Motion& a, const Force& f) {
  return Force{a.angular.cross(f.angular) + a.linear.cross(f.linear), a.angular.cross(f.linear)};
}

/// Spatial inertia of a rigid body (or of a composite of rigidly connected bodies).
struct Inertia {
  double mass = 0.0;          ///< [kg]
  Vec3 com = Vec3::Zero();    ///< centre of mass in the frame of expression [m]
  Mat3 I_com = Mat3::Zero();  ///< rotational inertia about the COM, frame axes [kg m²]

  static Inertia Zero() { return Inertia{}; }

  /// Momentum h = I m of a body moving with motion m (same frame) [kg m/s, kg m²/s].
  Force operator*(const Motion& m) const {
    const Vec3 p = mass * (m.linear + m.angular.cross(com));  // linear momentum m v_com
    return Force{I_com * m.angular + com.cross(p), p};
  }

  /// 6×6 matrix in Featherstone order: [[Ī, m [c]], [m [c]ᵀ, m 1]], Ī = I_c − m [c]².
  Mat6 matrix() const {
    const Mat3 C = skew(com);
    Mat6 M;
    M.topLeftCorner<3, 3>() = I_com - mass * C * C;
    M.topRightCorner<3, 3>() = mass * C;
    M.bottomLeftCorner<3, 3>() = -mass * C;
    M.bottomRightCorner<3, 3>() = mass * Mat3::Identity();
    return M;
  }
};

/// Inertia of two bodies rigidly joined, both expressed in the same frame
/// (parallel-axis theorem about the common centre of mass).
inline Inertia operator+(const Inertia& a, const Inertia& b) {
  Inertia r;
  r.mass = a.mass + b.mass;
  if (r.mass <= 0.0) return r;
  r.com = (a.mass * a.com + b.mass * b.com) / r.mass;
  const Vec3 da = a.com - r.com, db = b.com - r.com;
  const Mat3 Sa = skew(da), Sb = skew(db);
  r.I_com = a.I_com + b.I_com - a.mass * Sa * Sa - b.mass * Sb * Sb;
  return r;
}

/// Pose A_X_B of frame B in frame A (see the file comment).
struct Transform {
  Mat3 R = Mat3::Identity();  ///< A_R_B: B axes → A axes
  Vec3 p = Vec3::Zero();      ///< origin of B in A [m]

  static Transform Identity() { return Transform{}; }

  /// Motion in B coordinates → A coordinates.
  Motion apply(const Motion& m_B) const {
    const Vec3 w = R * m_B.angular;
    return Motion{w, R * m_B.linear + p.cross(w)};
  }
  /// Motion in A coordinates → B coordinates.
  Motion apply_inverse(const Motion& m_A) const {
    return Motion{R.transpose() * m_A.angular, R.transpose() * (m_A.linear - p.cross(m_A.angular))};
  }
  /// Force in B coordinates → A coordinates (moment now about A's origin).
  Force apply(const Force& f_B) const {
    const Vec3 f = R * f_B.linear;
    return Force{R * f_B.angular + p.cross(f), f};
  }
  /// Force in A coordinates → B coordinates (moment now about B's origin).
  Force apply_inverse(const Force& f_A) const {
    return Force{R.transpose() * (f_A.angular - p.cross(f_A.linear)), R.transpose() * f_A.linear};
  }
  /// Inertia in B coordinates → A coordinates.
  Inertia apply(const Inertia& I_B) const {
    return Inertia{I_B.mass, R * I_B.com + p, R * I_B.I_com * R.transpose()};
  }
  /// Point in B coordinates → A coordinates [m].
  Vec3 apply_point(const Vec3& r_B) const { return R * r_B + p; }

  /// B_X_A.
  Transform inverse() const { return Transform{R.transpose(), -(R.transpose() * p)}; }

  /// 6×6 matrix acting on Featherstone motion vectors: [[R, 0], [[p] R, R]].
  Mat6 motion_matrix() const {
    Mat6 X;
    X.topLeftCorner<3, 3>() = R;
    X.topRightCorner<3, 3>().setZero();
    X.bottomLeftCorner<3, 3>() = skew(p) * R;
    X.bottomRightCorner<3, 3>() = R;
    return X;
  }
  /// 6×6 matrix acting on Featherstone force vectors: [[R, [p] R], [0, R]].
  Mat6 force_matrix() const {
    Mat6 X;
    X.topLeftCorner<3, 3>() = R;
    X.topRightCorner<3, 3>() = skew(p) * R;
    X.bottomLeftCorner<3, 3>().setZero();
    X.bottomRightCorner<3, 3>() = R;
    return X;
  }
};

/// Composition A_X_C = A_X_B * B_X_C.
inline Transform operator*(const Transform& A_X_B, const Transform& B_X_C) {
  return Transform{A_X_B.R * B_X_C.R, A_X_B.p + A_X_B.R * B_X_C.p};
}

}  // namespace hexdyn
