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
  return contact_load_with_friction(friction, tip, qd, lambda,
                                    -effective_friction(friction, tip) * std::abs(lambda) * slip_direction,
                                    slip_direction, generalized_force);
}

ContactLoad contact_load_with_friction(const FrictionModel& friction, const TipKinematics& tip,
                                       const Eigen::Ref<const Eigen::VectorXd>& qd, double lambda,
                                       double friction_force, double slip_direction,
                                       Eigen::Ref<Eigen::VectorXd> generalized_force) {
  ContactLoad l;
  l.slip = slip_direction;
  if (lambda == 0.0 && friction_force == 0.0) {
    generalized_force.setZero();
    return l;
  }
  l.lambda = lambda;
  l.normal_force = reported_normal_force(friction, tip, lambda);
  l.friction_force = friction_force;
  generalized_force = lambda * tip.grad_gap + l.friction_force * tip.grad_tangent;
  l.force_x = lambda * tip.normal_x + l.friction_force * tip.tangent_x;
  l.force_y = lambda * tip.normal_y + l.friction_force * tip.tangent_y;
  l.rate[LedgerTerm::contact_moment] = tip.X * l.force_y - tip.Y * l.force_x;
  l.rate[LedgerTerm::contact_work] = qd.dot(generalized_force);
  l.rate[LedgerTerm::friction_work] = l.friction_force * tip.slip_speed;
  l.rate[LedgerTerm::surface_work] =
      l.friction_force * (tip.surface_vx * tip.tangent_x + tip.surface_vy * tip.tangent_y);
  l.rate[LedgerTerm::normal_impulse] = l.normal_force;
  l.rate[LedgerTerm::tangential_impulse] = l.friction_force;
  // Friction's dissipation −F_t V_t, which is |F_t||V_t| on every accepted state (both laws make friction
  // oppose the slip) and, unlike it, smooth where a slide ends in a stick, whose root the dense output
  // locates from stages past it.
  l.rate[LedgerTerm::frictional_heat] = -l.friction_force * tip.slip_speed;
  l.rate[LedgerTerm::sliding_load] = l.normal_force * std::abs(tip.slip_speed);
  return l;
}

const char* contact_model_name(ContactModel m) { return m == ContactModel::hertz ? "hertz" : "rigid"; }

double hertz_tip_radius(const HertzContact& hertz, double wire_diameter_m) {
  return hertz.tip_radius_m > 0.0 ? hertz.tip_radius_m : 0.5 * wire_diameter_m;
}

double hertz_stiffness(const HertzContact& hertz, double wire_youngs_pa, double wire_diameter_m) {
  const double radius = hertz_tip_radius(hertz, wire_diameter_m);
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

double hertz_damping(const ContactSettings& law, double v0, double full_speed) {
  ImpactLaw impact = law.impact;
  impact.plastic_below_m_s = 0.0;  // a compliant contact resolves slow touches in time
  const double e = std::max(restitution(impact, std::abs(v0), full_speed), kMinCompliantRestitution);
  const double speed = std::max(std::abs(v0), kGrazingSpeedFloor);
  return hunt_crossley_product(e) / speed;
}

double hertz_normal_force(double stiffness, double damping, double delta, double delta_rate) {
  if (!(delta > 0.0)) return 0.0;
  return std::max(0.0, stiffness * delta * std::sqrt(delta) * (1.0 + damping * delta_rate));
}

double hertz_elastic_energy(double stiffness, double delta) {
  return delta > 0.0 ? 0.4 * stiffness * delta * delta * std::sqrt(delta) : 0.0;
}

double hertz_dissipation_rate(double stiffness, double normal_force, double delta, double delta_rate) {
  if (!(delta > 0.0)) return 0.0;
  return -(normal_force - stiffness * delta * std::sqrt(delta)) * delta_rate;
}

// ---- the law's defaults -----------------------------------------------------------------------------

ContactSample ContactLaw::sample_at_start(const System& system, const ContactEpisode& episode, double t,
                                          const Eigen::Ref<const Eigen::VectorXd>& q,
                                          const Eigen::Ref<const Eigen::VectorXd>& qd, BeamWorkspace& ws,
                                          TipKinematics& tip) const {
  return sample(system, episode, t, q, qd, ws, tip);
}

ImpactResult ContactLaw::momentum_jump(const System&, double, const Eigen::Ref<const Eigen::VectorXd>&,
                                       Eigen::Ref<Eigen::VectorXd>, BeamWorkspace&, TipKinematics&) const {
  throw std::logic_error(std::string("the ") + name() + " contact law has no impacts");
}

double ContactLaw::stored_energy(const System&, double, const Eigen::Ref<const Eigen::VectorXd>&) const { return 0.0; }

FailureKind ContactLaw::failure_kind(const ContactEvaluation&) const { return FailureKind::painleve; }

std::string ContactLaw::failure_message(const ContactEvaluation& e) const {
  return std::string("the ") + name() + " contact law has no admissible force here (a = " + std::to_string(e.a) +
         ", b = " + std::to_string(e.b) + ", c = " + std::to_string(e.c) + ")";
}

void ContactLaw::root(PhaseControl&, int k) const {
  throw std::logic_error(std::string("the ") + name() + " contact law has no root " + std::to_string(k));
}

bool ContactLaw::before_step(PhaseControl&) const { return true; }

}  // namespace rotbeam
