// The contact geometry of a curved rigid surface from its gap field (docs/model.md §4, §11): a surface whose
// gap at a point P of the plane is a smooth function g(P) (its value, gradient ∇g and Hessian H at
// the tip) and whose material moves as a rigid rotation at Ω_s about a centre c fills every
// contact-geometry field of TipKinematics through the chain rule:
//   C = g,  ∇C = (∂R/∂q)ᵀ∇g,  ∂C/∂t = ∇g·(ω × R),  Ċ = ∇g·V,  γ = ∇g·a_bias + VᵀHV,
//   n = ∇g/|∇g|,  t = n turned +90°,  V_s = Ω_s k × (P − c),  V_t = (V − V_s)·t,
//   ∂V_t/∂q̇ = (∂R/∂q)ᵀt,  γ_t = t·a_bias − Ω_s V·n − ((V − V_s)·n)(tᵀHV)/|∇g|,
// the last from ṫ = −n (tᵀHV)/|∇g| and V̇_s·t = Ω_s V·n. A gap field with |∇g| = 1 on g = 0 makes
// ∂C/∂R the unit normal at contact, so the multiplier is the physical normal force (contact_law.hpp).
#pragma once

#include "rotbeam/tip_kinematics.hpp"

#include <Eigen/Core>

namespace rotbeam {

/// A gap field at one point: g [m], ∇g (dimensionless), H [1/m].
struct GapField {
  double value = 0;
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  Eigen::Matrix2d hessian = Eigen::Matrix2d::Zero();
};

/// The surface material's motion: a rigid rotation at `spin` [rad/s] (counter-clockwise > 0) about
/// `centre` [m] in the global frame (spin 0: at rest).
struct SurfaceMotion {
  double spin = 0;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
};

/// Fills the contact-geometry fields of `tip` (gap … gamma_tangent) from the gap field evaluated at
/// the tip's global position and the surface's motion. Allocates nothing.
void fill_contact_geometry(const GapField& field, const SurfaceMotion& motion, TipKinematics& tip);

}  // namespace rotbeam
