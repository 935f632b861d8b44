#include "rotbeam/impact_output.hpp"

#include <cmath>

namespace rotbeam {

nlohmann::json impact_json(const FirstImpactResult& r, const Config& config) {
  const ImpactResult& im = r.impact;
  nlohmann::json j;
  j["t_s"] = r.t;
  j["theta_deg"] = r.theta * 180.0 / M_PI;
  j["x_tip_m"] = r.x_tip;
  j["y_tip_m"] = r.y_tip;
  j["vx_before_m_s"] = im.vx_before;
  j["vx_after_m_s"] = im.vx_after;
  j["delta_vx_m_s"] = im.vx_before - im.vx_after;
  j["restitution"] = -im.vx_after / im.vx_before;
  j["restitution_used"] = im.restitution;
  j["vy_before_m_s"] = im.vy_before;
  j["vy_after_m_s"] = im.vy_after;
  j["impulse_n_s"] = im.impulse;
  j["tangential_impulse_n_s"] = im.tangential_impulse;
  j["energy_loss_j"] = im.relative_energy_loss;
  j["steps"] = r.steps;
  j["rhs_evaluations"] = r.rhs_evaluations;
  j["config"] = config.to_json();
  return j;
}

}  // namespace rotbeam
