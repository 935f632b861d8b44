// The first impact of a pass (thesis Table 5-3): free flight from the start with the thesis's
// stepper (fixed-step Butcher RK5, C = 0 located on the RK5 step) to the first touch (or, for a
// rigid start, a jump to the geometric impact time with q = q̇ = 0, thesis §4.6 Step 1), then the
// impact law of docs/model.md §5.
#pragma once

#include "rotbeam/impact.hpp"
#include "rotbeam/pass.hpp"

namespace rotbeam {

struct FirstImpactResult {
  bool found = false;               // false: no contact up to the end angle
  double t = 0, theta = 0;          // impact time [s] and beam angle [rad]
  double x_tip = 0, y_tip = 0;      // global X_t, Y_t at impact [m]
  ImpactResult impact;
  Eigen::VectorXd q, qd_before, qd_after;
  double min_gap = 0;               // closest approach when not found (the largest gap seen) [m]
  long steps = 0, rhs_evaluations = 0;
  std::optional<NumericalFailure> failure;  // the free flight broke down (non-finite state, a step
                                            // that does not advance, a jammed frictional impact)
};

/// Runs to the first impact (up to `end_angle_deg`) with free-flight step `step_s` [s] and applies
/// system.law.impact_law(). Throws std::invalid_argument when the initial shape already touches; a numerical
/// breakdown, or a stop requested on control.stop (checked at every step), is returned in `failure`
/// (found = false; kind `interrupted` for a stop). control.on_progress is called as for a pass
/// (θ from θ0 toward the end angle); control.sink is not used (the search records no history).
FirstImpactResult first_impact(const System& system, const InitialConditions& initial, double end_angle_deg,
                               double step_s, const PassControl& control = {});

}  // namespace rotbeam
