#include "rotbeam/contact_law.hpp"

#include <boost/math/tools/toms748_solve.hpp>
#include <algorithm>
#include <cmath>
#include <stdexcept>

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

double hertz_stiffness(const HertzContact& hertz, double wire_youngs_pa, double wire_diameter_m) {
  const double radius = hertz.tip_radius_m > 0.0 ? hertz.tip_radius_m : 0.5 * wire_diameter_m;
  const double inverse = (1.0 - hertz.wire_poisson * hertz.wire_poisson) / wire_youngs_pa +
                         (1.0 - hertz.surface_poisson * hertz.surface_poisson) / hertz.surface_youngs_modulus_pa;
  return hertz.stiffness_factor * 4.0 / 3.0 / inverse * std::sqrt(radius);
}

double hunt_crossley_product(double e) {
  if (!(e >= kMinCompliantRestitution))
    throw std::domain_error("Hunt–Crossley damping: a restitution below 0.05 is not resolved in double precision");
  if (e >= 1.0 - 1e-14) return 0.0;
  // f(x) = ln(1 + x) − ln(1 − e x) − (1 + e) x: f ≈ −(1 − e²)x²/2 + (1 + e³)x³/3 near 0, → +∞ at 1/e.
  const auto f = [e](double x) { return std::log1p(x) - std::log1p(-e * x) - (1.0 + e) * x; };
  const double lo = 0.75 * (1.0 - e * e) / (1.0 + e * e * e);  // half the cubic's root: f < 0 there
  double hi = std::min(2.0 * lo, 1.0 / e);
  while (f(hi) <= 0.0) hi = 0.5 * (hi + 1.0 / e);
  boost::uintmax_t iters = 200;
  const auto r = boost::math::tools::toms748_solve(f, lo, hi, boost::math::tools::eps_tolerance<double>(52), iters);
  return 0.5 * (r.first + r.second);
}

double hertz_damping(const ContactLaw& law, double v0, double full_speed) {
  ImpactLaw impact = law.impact;
  impact.plastic_below_m_s = 0.0;  // a compliant contact resolves slow touches in time
  const double e = std::max(restitution(impact, std::abs(v0), full_speed), kMinCompliantRestitution);
  const double speed = std::max({std::abs(v0), law.impact.plastic_below_m_s, 1e-3});
  return hunt_crossley_product(e) / speed;
}

double hertz_normal_force(const HertzContact& hertz, double damping, double delta, double delta_rate) {
  if (!(delta > 0.0)) return 0.0;
  return std::max(0.0, hertz.stiffness * delta * std::sqrt(delta) * (1.0 + damping * delta_rate));
}

double hertz_elastic_energy(const HertzContact& hertz, double delta) {
  return delta > 0.0 ? 0.4 * hertz.stiffness * delta * delta * std::sqrt(delta) : 0.0;
}

double hertz_dissipation_rate(const HertzContact& hertz, double normal_force, double delta, double delta_rate) {
  if (!(delta > 0.0)) return 0.0;
  return -(normal_force - hertz.stiffness * delta * std::sqrt(delta)) * delta_rate;
}

}  // namespace rotbeam
