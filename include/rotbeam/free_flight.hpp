// Free flight with the thesis's fixed-step Butcher RK5 and location of the first C = 0 crossing
// (thesis §4.6 Step 1: linear interpolation over the last step; here refined by root finding on
// the RK5 step itself, τ ↦ C(RK5(y_n, τ)), with Boost's TOMS 748 solver).
#pragma once

#include "rotbeam/dynamics.hpp"
#include "rotbeam/rk5.hpp"

#include <functional>

namespace rotbeam {

struct FreeFlightOptions {
  double step_s = 1e-6;        // fixed RK5 step [s]
  double end_time_s = 0.0;     // stop here (exactly) if no contact first
  bool stop_at_contact = true; // locate and stop at the first C = 0 crossing with Ċ > 0
};

enum class FreeFlightEnd { contact, end_time };

struct FreeFlightResult {
  FreeFlightEnd end = FreeFlightEnd::end_time;
  double t = 0;                    // final time [s]
  Eigen::VectorXd q, qd;           // final state
  double linear_estimate_t = 0;    // thesis's linear-interpolation contact time (contact only) [s]
  double min_gap = 0;              // most positive C seen (closest approach; < 0 without contact) [m]
  long steps = 0;
  long rhs_evaluations = 0;
};

/// Called after every accepted step with (t, q, q̇).
using StepObserver = std::function<void(double, const Eigen::VectorXd&, const Eigen::VectorXd&)>;

/// Integrates the free (unconstrained) equations from (t0, q0, q̇0).
FreeFlightResult integrate_free_flight(const Model& model, double t0, const Eigen::VectorXd& q0,
                                       const Eigen::VectorXd& qd0, const FreeFlightOptions& options,
                                       Workspace& ws, const StepObserver& observer = {});

}  // namespace rotbeam
