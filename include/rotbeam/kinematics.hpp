// Tip kinematics and the contact constraint (SPEC §2, §4).
//   x_t = r_h + L − qᵀISP(1)q/(2L), y_t = S(1)ᵀq           (beam frame, metres)
//   X_t = x_t cos θ − y_t sin θ,  Y_t = x_t sin θ + y_t cos θ (global frame)
//   gap C(q, t) = X_t − d ≤ 0, contact when C = 0
//   ∇C = −(cos θ/L) ISP(1) q − sin θ S(1),  ∂C/∂t = −ω Y_t,  Ċ = ∇Cᵀq̇ + ∂C/∂t = V_X
//   C̈ = ∇Cᵀq̈ + γ, γ = −(cos θ/L) q̇ᵀISP(1)q̇ + 2ω[(sin θ/L) qᵀISP(1)q̇ − cos θ S(1)ᵀq̇] − ω² X_t
//   ∂Y_t/∂q = −(sin θ/L) ISP(1) q + cos θ S(1)
//   Ÿ_t = (∂Y_t/∂q)ᵀq̈ + γ_Y, γ_Y = −(sin θ/L) q̇ᵀISP(1)q̇ − 2ω[(cos θ/L) qᵀISP(1)q̇ + sin θ S(1)ᵀq̇] − ω² Y_t
#pragma once

#include "rotbeam/model.hpp"

#include <Eigen/Core>

namespace rotbeam {

struct TipKinematics {
  explicit TipKinematics(int n) : grad_gap(n), grad_y(n) {}
  double theta = 0;          // beam angle [rad]
  double x = 0, y = 0;       // tip in the beam frame [m]
  double xd = 0, yd = 0;     // their rates relative to the beam frame [m/s]
  double X = 0, Y = 0;       // tip in the global frame [m]
  double VX = 0, VY = 0;     // inertial tip velocity [m/s]
  double gap = 0;            // C = X_t − d [m]
  double gap_rate = 0;       // Ċ = V_X [m/s]
  double gap_time_partial = 0;  // ∂C/∂t = −ω Y_t [m/s]
  double gamma = 0;          // γ [m/s²]
  double gamma_y = 0;        // γ_Y [m/s²], the tangential counterpart of γ
  Eigen::VectorXd grad_gap;  // ∇C (dimensionless)
  Eigen::VectorXd grad_y;    // ∂Y_t/∂q (dimensionless)
};

/// Gap C(q, t) = X_t − d [m] (cheap: no gradients).
double gap(const Model& model, double t, const Eigen::Ref<const Eigen::VectorXd>& q);

/// Fills every field of `out` at (t, q, q̇). Allocates nothing.
void tip_kinematics(const Model& model, double t, const Eigen::Ref<const Eigen::VectorXd>& q,
                    const Eigen::Ref<const Eigen::VectorXd>& qd, TipKinematics& out);

}  // namespace rotbeam
