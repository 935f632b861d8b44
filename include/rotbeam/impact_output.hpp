// The first-impact record of `rotbeam impact --json` (docs/model.md §7), shared by the CLI and Python.
#pragma once

#include "rotbeam/config.hpp"
#include "rotbeam/first_impact.hpp"

#include <nlohmann/json.hpp>

namespace rotbeam {

/// {t_s, theta_deg, x_tip_m, y_tip_m, vx_before_m_s, vx_after_m_s, delta_vx_m_s, restitution,
///  vy_before_m_s, vy_after_m_s, impulse_n_s, energy_loss_j, steps, rhs_evaluations, config}.
/// Requires r.found.
nlohmann::json impact_json(const FirstImpactResult& r, const Config& config);

}  // namespace rotbeam
