// A whole pass through contact: options, results and the scheme entry point (SPEC §6, §7).
#pragma once

#include "rotbeam/contact.hpp"
#include "rotbeam/first_impact.hpp"
#include "rotbeam/impact.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rotbeam {

enum class Phase { free, contact, stick };
const char* phase_name(Phase p);

/// One row of the time history (SPEC §7). Forces in N, positions in m, velocities in m/s.
struct HistoryRow {
  double t = 0, theta = 0;
  Phase phase = Phase::free;
  double x_tip = 0, y_tip = 0, gap = 0, vx = 0, vy = 0;
  double normal_force = 0, friction_force = 0, lambda = 0;
  Eigen::VectorXd q, qd;
  double jacobi = 0;      // h [J]
  double hub_torque = 0;  // τ [N m]
};

/// An event, recorded exactly when it happens.
struct PassEvent {
  double t = 0, theta = 0, y_tip = 0;
  std::string kind;  // impact, contact_start, contact_end, slip_reversal, tip_distance_rule, warning, failure, end
  double vx_before = NAN, vx_after = NAN, restitution = NAN, impulse = NAN;
  std::string detail;
};

struct ContactInterval {
  double t_start = 0, t_end = 0, theta_start = 0, theta_end = 0, y_start = 0, y_end = 0;
};

struct PassSummary {
  int impacts = 0;
  int plastic_impacts = 0;
  int contact_episodes = 0;
  double first_impact_deg = NAN;
  double last_separation_deg = NAN;
  double contact_time_s = 0;
  double peak_normal_force_n = 0;
  double mean_normal_force_n = 0;
  double normal_impulse_n_s = 0;
  double friction_work_j = 0;
  double max_tip_deflection_ratio = 0;
  double energy_audit_residual = 0;
  long steps = 0;
  long rhs_evaluations = 0;
  long corrector_iterations = 0;
  int corrector_iterations_max = 0;
  double wall_time_s = 0;
  std::string scheme;
  std::vector<std::string> warnings;
  std::vector<ContactInterval> contact_intervals;
};

/// A numerical breakdown: what, where and the quantities involved. The partial result is kept.
/// Kinds: painleve, stick, corrector, step_underflow, non_finite, validity, impacts, chatter,
/// initial_state, interrupted.
struct NumericalFailure {
  std::string kind;
  double t = 0, theta = 0;
  std::string message;
};

struct PassResult {
  std::vector<HistoryRow> history;
  std::vector<PassEvent> events;
  PassSummary summary;
  std::optional<NumericalFailure> failure;
};

/// Settings of the `thesis` scheme (thesis §4.6–4.7) and of the recording.
struct PassOptions {
  double end_angle_rad = M_PI / 2;
  double free_step_s = 1e-6;          // RK5 step in free flight
  double contact_step_s = 1e-7;       // predictor–corrector step in contact
  double fine_contact_step_s = 1e-8;  // … while 0 < |λ| < fine_below_n
  double fine_below_n = 1e-4;
  double corrector_tolerance = 1e-5;  // relative change of λ between corrector iterates
  int corrector_max_iterations = 50;
  bool thesis_dcdt = false;           // compat: ∂C/∂t forced to −∇Cᵀu^p (thesis §6.3)
  double output_interval_s = 1e-5;    // history sampling (events always recorded exactly)
  double deflection_warning_ratio = 0.1;
  int max_impacts = 10000;
  bool deflection_limit_is_error = false;  // stop with a `validity` failure past the warning ratio
  // Adaptive scheme (SPEC §6).
  double rtol = 1e-9;
  double atol = 1e-12;
  double max_step_s = 2e-5;           // upper bound on the adaptive step [s]
  double event_tolerance_s = 1e-13;   // events located to this bracket width [s]
};

/// Asks every running pass to stop at its next step with an `interrupted` failure (async-signal-safe:
/// sets an atomic flag; used by the command line's SIGINT/SIGTERM handler).
void request_interrupt() noexcept;
/// Clears the request (before a new run).
void clear_interrupt() noexcept;
bool interrupt_requested() noexcept;

/// Runs one pass with the adaptive event-driven scheme: Dormand–Prince 5(4) with dense output
/// (Boost.Odeint), events (C = 0 in free flight; λ = 0 and V_t = 0 in contact; the end angle)
/// located by root finding on the dense output, projection onto C = 0 and Ċ = 0 after every contact
/// step, and the same impact law, slip/stick analysis and Zeno handling as the thesis scheme.
PassResult run_adaptive_pass(const Model& model, const ImpactLaw& law, const FrictionModel& friction,
                             const InitialConditions& initial, const PassOptions& options);

/// Runs one pass with the thesis's scheme (fixed-step RK5, momentum-balance impacts,
/// predictor–corrector in contact). Never throws for numerical trouble: a failure is returned in
/// PassResult::failure with everything computed up to it.
PassResult run_thesis_pass(const Model& model, const ImpactLaw& law, const FrictionModel& friction,
                           const InitialConditions& initial, const PassOptions& options);

}  // namespace rotbeam
