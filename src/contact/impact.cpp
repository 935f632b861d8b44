#include "rotbeam/impact.hpp"

#include "rotbeam/detail/quadratic_form.hpp"
#include "rotbeam/surface.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rotbeam {

double restitution(const ImpactLaw& law, double normal_speed, double full_speed) {
  if (normal_speed < law.plastic_below_m_s) return 0.0;
  double e = law.constant;
  if (law.model == RestitutionModel::yigit) {
    const double v = law.speed == RestitutionSpeed::normal ? normal_speed : full_speed;
    e = 0.501 * std::pow(v, -0.25);
  }
  return std::min(e, law.cap);
}

ImpactResult apply_impact(const BeamModel& beam, const Surface& surface, const ImpactLaw& law, double t,
                          const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> qd,
                          BeamWorkspace& ws, TipKinematics& tip) {
  tip_kinematics(beam, surface, t, q, qd, tip);
  const double vx = tip.gap_rate;
  if (!(vx > 0.0))
    throw std::domain_error("impact requested for a tip that is not approaching the surface (V_X = " +
                            std::to_string(vx) + " m/s)");
  ImpactResult r;
  r.vx_before = vx;
  r.vy_before = tip.slip_speed;
  beam.evaluate_mass(q, ws);
  Eigen::VectorXd& minv_grad = ws.scratch;
  minv_grad = tip.grad_gap;
  ws.mass_llt.solveInPlace(minv_grad);
  const double a = tip.grad_gap.dot(minv_grad);
  const double e = restitution(law, vx, std::hypot(tip.VX - tip.surface_vx, tip.VY - tip.surface_vy));
  const double p = -(1.0 + e) * vx / a;
  const double t2_before = 0.5 * detail::quadratic_form(ws.mass, qd);
  qd += p * minv_grad;
  tip_kinematics(beam, surface, t, q, qd, tip);
  r.vx_after = tip.gap_rate;
  r.vy_after = tip.slip_speed;
  r.restitution = e;
  r.impulse = p;
  r.effective_inverse_mass = a;
  r.relative_energy_loss = 0.5 * (1.0 - e * e) * vx * vx / a;
  r.delta_t2 = 0.5 * detail::quadratic_form(ws.mass, qd) - t2_before;
  return r;
}

}  // namespace rotbeam
