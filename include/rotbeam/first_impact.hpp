// The first impact of a pass (thesis Table 5-3): free flight from the start to the first
// C = 0 crossing (or, for a rigid start, a jump to the geometric impact time with q = q̇ = 0,
// thesis §4.6 Step 1), then the impact law of SPEC §5.
#pragma once

#include "rotbeam/free_flight.hpp"
#include "rotbeam/impact.hpp"

namespace rotbeam {

struct InitialConditions {
  bool rigid_start = true;          // q = q̇ = 0 at the geometric impact time
  Eigen::VectorXd q0, qd0;          // q(0) [m], q̇(0) [m/s] at θ0 (flexible start)
};

struct FirstImpactResult {
  bool found = false;               // false: no contact up to the end angle
  double t = 0, theta = 0;          // impact time [s] and beam angle [rad]
  double x_tip = 0, y_tip = 0;      // global X_t, Y_t at impact [m]
  ImpactResult impact;
  Eigen::VectorXd q, qd_before, qd_after;
  double min_gap = 0;               // closest approach when not found [m]
  long steps = 0, rhs_evaluations = 0;
};

/// Runs to the first impact and applies the impact law.
FirstImpactResult first_impact(const Model& model, const ImpactLaw& law, const InitialConditions& initial,
                               double end_angle_rad, double step_s);

}  // namespace rotbeam
