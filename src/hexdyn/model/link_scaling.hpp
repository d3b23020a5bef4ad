#pragma once
/// \file link_scaling.hpp
/// How a YAML robot's link mass, centre of mass and inertia follow its length
/// (robot.links_follow_length, docs/theory/model.md#links-that-follow-their-length).
///
/// uniform_density: the link's stated mass, COM and inertia belong to its reference length
/// L_ref (robot.<link>.reference_length); a link of length L is that link stretched along its
/// axis by r = L / L_ref, with its cross-section and its density unchanged (the paper's
/// links keep their mass per metre). Link frame as in RobotParams: x along the link from its
/// joint, the stated moments principal along the frame axes, about the COM.
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// Rule of robot.links_follow_length.
enum class LinkLengthRule {
  kNone,            ///< mass, COM and inertia as stated, whatever the length (the default)
  kUniformDensity,  ///< stretched from the reference length (file comment)
};

/// The link `ref` (stated for its reference length) stretched along its x axis by
/// `ratio` = L / L_ref > 0:
///   mass            m' = r m
///   COM             c' = (r c_x, c_y, c_z)            (the stretch is about the joint, x = 0)
///   second moments  Σ_xx = ∫x² dm → r³ Σ_xx;  Σ_yy, Σ_zz → r Σ_yy, r Σ_zz  (about the COM)
///   inertia         I_xx' = r I_xx,  I_yy' = r³ Σ_xx + r Σ_zz,  I_zz' = r³ Σ_xx + r Σ_yy,
/// with Σ_xx = (I_yy + I_zz − I_xx)/2, Σ_yy = (I_xx + I_zz − I_yy)/2,
/// Σ_zz = (I_xx + I_yy − I_zz)/2 (each ≥ 0 when the moments satisfy the triangle inequality,
/// as load_scene checks). For a slender link (Σ_yy, Σ_zz ≪ Σ_xx) the transverse moments grow
/// as m L², r³, and the axial one as m, r. ratio == 1 returns `ref` unchanged.
BodyParams stretch_link(const BodyParams& ref, double ratio);

}  // namespace hexdyn
