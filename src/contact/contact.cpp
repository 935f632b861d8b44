#include "rotbeam/contact.hpp"

#include <cmath>

namespace rotbeam {

MultiplierSolution solve_multiplier(double a, double b, double c) {
  // Contact (λ ≤ 0, friction active): (a − b) λ = c. Separation (λ > 0, no friction): a λ = c.
  MultiplierSolution s;
  const bool contact_ok = (a - b != 0.0) ? (c / (a - b) <= 0.0) : (c == 0.0);
  const bool separation_ok = c / a > 0.0;
  if (contact_ok && separation_ok) {
    s.status = MultiplierSolution::Status::non_unique;
    s.lambda = c / (a - b);
  } else if (contact_ok) {
    s.status = MultiplierSolution::Status::unique;
    s.lambda = (a - b != 0.0) ? c / (a - b) : 0.0;
  } else if (separation_ok) {
    s.status = MultiplierSolution::Status::unique;
    s.lambda = c / a;
  } else {
    s.status = MultiplierSolution::Status::inconsistent;
    s.lambda = 0.0;
  }
  return s;
}

double stick_speed_threshold(const Model& model) {
  return 1e-9 * std::max(model.omega * (model.hub_radius + model.length), 1e-3);
}

double effective_friction(const FrictionModel& friction, const TipKinematics& tip) {
  return friction.thesis_forces ? friction.mu * tip.grad_gap.norm() : friction.mu;
}

double reported_normal_force(const FrictionModel& friction, const TipKinematics& tip, double lambda) {
  return friction.thesis_forces ? std::abs(lambda) * tip.grad_gap.norm() : -lambda;
}

void friction_direction(const FrictionModel& friction, const TipKinematics& tip, double slip_direction,
                        Eigen::Ref<Eigen::VectorXd> out) {
  out = (-effective_friction(friction, tip) * slip_direction) * tip.grad_y;
}

SlipDecision decide_slip(const Model& model, const FrictionModel& friction, const TipKinematics& tip,
                         Workspace& ws) {
  SlipDecision d;
  if (std::abs(tip.VY) > stick_speed_threshold(model)) {
    d.kind = SlipDecision::Kind::slip;
    d.direction = tip.VY > 0 ? 1.0 : -1.0;
    return d;
  }
  return decide_slip_at_rest(model, friction, tip, ws);
}

SlipDecision decide_slip_at_rest(const Model& model, const FrictionModel& friction, const TipKinematics& tip,
                                 Workspace& ws) {
  (void)model;
  SlipDecision d;
  d.from_velocity = false;
  // Two constraints: C̈ = ∇Cᵀq̈ + γ = 0 and Ÿ = gᵀq̈ + γ_Y = 0 with M q̈ = −Ψ + λ∇C + λ_t g, g = ∂Y/∂q.
  Eigen::VectorXd& minv_grad = ws.scratch;
  Eigen::VectorXd& minv_g = ws.scratch2;
  minv_grad = tip.grad_gap;
  ws.mass_llt.solveInPlace(minv_grad);
  minv_g = tip.grad_y;
  ws.mass_llt.solveInPlace(minv_g);
  const double ann = tip.grad_gap.dot(minv_grad), ant = tip.grad_gap.dot(minv_g), att = tip.grad_y.dot(minv_g);
  // ∇CᵀM⁻¹Ψ and gᵀM⁻¹Ψ via the symmetric solves already made.
  const double cn = minv_grad.dot(ws.psi) - tip.gamma, ct = minv_g.dot(ws.psi) - tip.gamma_y;
  const double det = ann * att - ant * ant;
  if (det <= 1e-12 * ann * att) {
    // ∇C ∥ ∂Y/∂q (e.g. the straight beam, where the tip can only move along the beam's local y):
    // holding X_t also holds Y_t, friction does no work, and the frictionless λ = c/a decides.
    d.stick_normal = cn / ann;
    d.stick_tangential = 0.0;
    d.kind = d.stick_normal > 0.0 ? SlipDecision::Kind::separate : SlipDecision::Kind::stick;
    return d;
  }
  const double lambda = (cn * att - ct * ant) / det;
  const double tangential = (ann * ct - ant * cn) / det;
  d.stick_normal = lambda;
  d.stick_tangential = tangential;
  if (lambda > 0.0) {
    d.kind = SlipDecision::Kind::separate;
    d.direction = 0.0;
  } else if (std::abs(tangential) <= effective_friction(friction, tip) * std::abs(lambda)) {
    d.kind = SlipDecision::Kind::stick;
    d.direction = 0.0;
  } else {
    d.kind = SlipDecision::Kind::slip;
    d.direction = tangential > 0 ? -1.0 : 1.0;
  }
  return d;
}

AccelerationMultiplier acceleration_multiplier(const Model& model, const FrictionModel& friction, double t,
                                               const Eigen::Ref<const Eigen::VectorXd>& q,
                                               const Eigen::Ref<const Eigen::VectorXd>& qd, double slip_direction,
                                               Workspace& ws, TipKinematics& tip) {
  evaluate_dynamics(model, q, qd, ws);
  tip_kinematics(model, t, q, qd, tip);
  Eigen::VectorXd& minv_grad = ws.scratch;
  minv_grad = tip.grad_gap;
  ws.mass_llt.solveInPlace(minv_grad);
  AccelerationMultiplier m;
  m.a = tip.grad_gap.dot(minv_grad);
  // b = ∇CᵀM⁻¹Q* = (M⁻¹∇C)ᵀQ* with Q* = −μ_eff s_t g.
  m.b = -effective_friction(friction, tip) * slip_direction * minv_grad.dot(tip.grad_y);
  m.c = minv_grad.dot(ws.psi) - tip.gamma;
  m.solution = solve_multiplier(m.a, m.b, m.c);
  return m;
}

}  // namespace rotbeam
