// The record of the tip's state that the kinematics (kinematics.hpp), the surface (surface.hpp)
// and the contact algorithms share: the motion in the global frame, filled by tip_kinematics, and
// the contact geometry, filled by the surface (docs/model.md §2, §4).
#pragma once

#include "rotbeam/beam_model.hpp"

#include <Eigen/Core>

namespace rotbeam {

struct TipKinematics {
  explicit TipKinematics(int n) : hub(n), grad_x(n), grad_y(n), grad_gap(n), grad_tangent(n) {}
  // The motion (filled by tip_kinematics).
  double t = 0;              // time [s]
  double theta = 0;          // beam angle [rad]
  HubFrameTip hub;           // the tip in the hub frame (x, y, rates, Jacobians)
  double X = 0, Y = 0;       // tip in the global frame [m]
  double VX = 0, VY = 0;     // inertial tip velocity [m/s]
  double frame_vx = 0, frame_vy = 0;  // ω × R: velocity of the hub-frame point at the tip [m/s]
  double bias_ax = 0, bias_ay = 0;    // A − (∂R/∂q) q̈ [m/s²]
  Eigen::VectorXd grad_x, grad_y;     // ∂X/∂q, ∂Y/∂q (dimensionless)
  // The contact geometry (filled by the surface).
  double gap = 0;               // C [m] (≤ 0 clear, 0 in contact)
  double gap_rate = 0;          // Ċ [m/s] (= V_X for the plane)
  double gap_time_partial = 0;  // ∂C/∂t at fixed q [m/s] (= −ωY_t for the plane)
  double gamma = 0;             // γ: C̈ = ∇Cᵀq̈ + γ [m/s²]
  Eigen::VectorXd grad_gap;     // ∇C = ∂C/∂q (dimensionless)
  double normal_x = 1, normal_y = 0;    // unit normal at the contact point, pointing into the surface
  double tangent_x = 0, tangent_y = 1;  // unit tangent, the normal turned +90° (the sense of rotation)
  double surface_vx = 0, surface_vy = 0;  // the surface's own velocity at the contact point [m/s]
  double slip_speed = 0;        // V_t: tangential tip velocity relative to the surface [m/s]
  Eigen::VectorXd grad_tangent; // ∂V_t/∂q̇ = (∂R/∂q)ᵀ t, the direction of friction's generalised force
  double gamma_tangent = 0;     // V̇_t = grad_tangentᵀ q̈ + γ_t [m/s²]
};

}  // namespace rotbeam
