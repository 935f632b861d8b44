// The tip's motion in the global frame and the contact geometry the surface makes of it
// (docs/model.md §2, §4). The beam model gives the tip in the hub frame (beam_model.hpp); the hub's
// rotation R(θ) takes it to the global frame; the surface (surface.hpp) turns that motion into the
// gap C and its derivatives. This file is the one place where the rotation is applied:
//   R = R(θ) r,  V = R(θ)(ṙ + ω J r),  A = (∂R/∂q) q̈ + R(θ)(r_quadratic + 2ω J ṙ − ω² r),  J = [0 −1; 1 0]
// and C̈ = ∇Cᵀq̈ + γ, (tangential slip)˙ = (∂s/∂q)ᵀq̈ + γ_t.
#pragma once

#include "rotbeam/beam_model.hpp"
#include "rotbeam/tip_kinematics.hpp"

#include <Eigen/Core>

namespace rotbeam {

class Surface;

/// Fills every field of `out` at (t, q, q̇). Allocates nothing.
void tip_kinematics(const BeamModel& beam, const Surface& surface, double t, const Eigen::Ref<const Eigen::VectorXd>& q,
                    const Eigen::Ref<const Eigen::VectorXd>& qd, TipKinematics& out);

/// Gap C(q, t) [m] (cheap: no gradients).
double gap(const BeamModel& beam, const Surface& surface, double t, const Eigen::Ref<const Eigen::VectorXd>& q);

/// The tip position in the global frame at (t, q) [m].
Eigen::Vector2d tip_position(const BeamModel& beam, double t, const Eigen::Ref<const Eigen::VectorXd>& q);

}  // namespace rotbeam
