#include "rotbeam/rigid_contact.hpp"

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

double stick_speed_threshold(const BeamModel& beam) {
  return 1e-9 * std::max(beam.hub_motion().omega * beam.tip_radius(), 1e-3);
}

SlipDecision decide_slip(const BeamModel& beam, const FrictionModel& friction, const TipKinematics& tip,
                         BeamWorkspace& ws) {
  SlipDecision d;
  if (std::abs(tip.slip_speed) > stick_speed_threshold(beam)) {
    d.kind = SlipDecision::Kind::slip;
    d.direction = tip.slip_speed > 0 ? 1.0 : -1.0;
    return d;
  }
  return decide_slip_at_rest(friction, tip, ws);
}

ContactMobility contact_mobility(const TipKinematics& tip, BeamWorkspace& ws) {
  Eigen::VectorXd& minv_grad = ws.scratch;
  Eigen::VectorXd& minv_g = ws.scratch2;
  minv_grad = tip.grad_gap;
  ws.mass_llt.solveInPlace(minv_grad);
  minv_g = tip.grad_tangent;
  ws.mass_llt.solveInPlace(minv_g);
  return {tip.grad_gap.dot(minv_grad), tip.grad_gap.dot(minv_g), tip.grad_tangent.dot(minv_g)};
}

LockedTipForces locked_tip_forces(const TipKinematics& tip, BeamWorkspace& ws) {
  // Two constraints: C̈ = ∇Cᵀq̈ + γ = 0 and V̇_t = gᵀq̈ + γ_t = 0 with M q̈ = −Ψ + λ∇C + λ_t g,
  // g = ∂V_t/∂q̇.
  const ContactMobility m = contact_mobility(tip, ws);
  const Eigen::VectorXd& minv_grad = ws.scratch;
  const Eigen::VectorXd& minv_g = ws.scratch2;
  const double ann = m.nn, ant = m.nt, att = m.tt;
  // ∇CᵀM⁻¹Ψ and gᵀM⁻¹Ψ via the symmetric solves already made.
  const double cn = minv_grad.dot(ws.psi) - tip.gamma, ct = minv_g.dot(ws.psi) - tip.gamma_tangent;
  const double det = ann * att - ant * ant;
  LockedTipForces f;
  if (det <= 1e-12 * ann * att) {
    // ∇C ∥ g (e.g. the straight beam on the plane, where the tip can only move along the beam's local
    // y): holding the gap also holds the slip, friction does no work, and the frictionless λ = c/a decides.
    f.dependent = true;
    f.lambda = cn / ann;
    return f;
  }
  f.lambda = (cn * att - ct * ant) / det;
  f.tangential = (ann * ct - ant * cn) / det;
  return f;
}

SlipDecision decide_slip_at_rest(const FrictionModel& friction, const TipKinematics& tip, BeamWorkspace& ws) {
  SlipDecision d;
  d.from_velocity = false;
  const LockedTipForces f = locked_tip_forces(tip, ws);
  if (f.dependent) {
    d.stick_normal = f.lambda;
    d.stick_tangential = 0.0;
    d.kind = d.stick_normal > 0.0 ? SlipDecision::Kind::separate : SlipDecision::Kind::stick;
    return d;
  }
  const double lambda = f.lambda;
  const double tangential = f.tangential;
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

AccelerationMultiplier acceleration_multiplier(const BeamModel& beam, const Surface& surface,
                                               const FrictionModel& friction, double t,
                                               const Eigen::Ref<const Eigen::VectorXd>& q,
                                               const Eigen::Ref<const Eigen::VectorXd>& qd, double slip_direction,
                                               BeamWorkspace& ws, TipKinematics& tip) {
  beam.evaluate_dynamics(q, qd, ws);
  tip_kinematics(beam, surface, t, q, qd, tip);
  Eigen::VectorXd& minv_grad = ws.scratch;
  minv_grad = tip.grad_gap;
  ws.mass_llt.solveInPlace(minv_grad);
  AccelerationMultiplier m;
  m.a = tip.grad_gap.dot(minv_grad);
  // b = ∇CᵀM⁻¹Q* = (M⁻¹∇C)ᵀQ* with Q* = −μ_eff s_t g.
  m.b = -effective_friction(friction, tip) * slip_direction * minv_grad.dot(tip.grad_tangent);
  m.c = minv_grad.dot(ws.psi) - tip.gamma;
  m.solution = solve_multiplier(m.a, m.b, m.c);
  return m;
}

}  // namespace rotbeam
