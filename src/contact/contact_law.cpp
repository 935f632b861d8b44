#include "rotbeam/contact_law.hpp"

#include <cmath>

namespace rotbeam {

double effective_friction(const FrictionModel& friction, const TipKinematics& tip) {
  return friction.thesis_forces ? friction.mu * tip.grad_gap.norm() : friction.mu;
}

double reported_normal_force(const FrictionModel& friction, const TipKinematics& tip, double lambda) {
  return friction.thesis_forces ? std::abs(lambda) * tip.grad_gap.norm() : -lambda;
}

void friction_direction(const FrictionModel& friction, const TipKinematics& tip, double slip_direction,
                        Eigen::Ref<Eigen::VectorXd> out) {
  out = (-effective_friction(friction, tip) * slip_direction) * tip.grad_tangent;
}

ContactLoad contact_load(const FrictionModel& friction, const TipKinematics& tip,
                         const Eigen::Ref<const Eigen::VectorXd>& qd, double lambda, double slip_direction,
                         Eigen::Ref<Eigen::VectorXd> generalized_force) {
  ContactLoad l;
  if (lambda == 0.0) {
    generalized_force.setZero();
    return l;
  }
  l.lambda = lambda;
  l.slip = slip_direction;
  l.normal_force = reported_normal_force(friction, tip, lambda);
  l.friction_force = -effective_friction(friction, tip) * std::abs(lambda) * slip_direction;
  generalized_force = lambda * tip.grad_gap + l.friction_force * tip.grad_tangent;
  l.force_x = lambda * tip.normal_x + l.friction_force * tip.tangent_x;
  l.force_y = lambda * tip.normal_y + l.friction_force * tip.tangent_y;
  l.moment = tip.X * l.force_y - tip.Y * l.force_x;
  l.power = qd.dot(generalized_force);
  l.slip_power = l.friction_force * tip.slip_speed;
  l.surface_power = l.friction_force * (tip.surface_vx * tip.tangent_x + tip.surface_vy * tip.tangent_y);
  return l;
}

}  // namespace rotbeam
