// A whole pass through contact (SPEC §6, §7): the initial conditions, the outputs as they are
// produced (a PassSink) or kept in memory (PassResult), and the entry point that runs the pass
// driver over the configured scheme's stepper.
#pragma once

#include "rotbeam/outcome.hpp"
#include "rotbeam/pass_options.hpp"
#include "rotbeam/stepper.hpp"
#include "rotbeam/stop_token.hpp"

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rotbeam {

struct InitialConditions {
  bool rigid_start = true;  // q = q̇ = 0 at the geometric contact angle (thesis §4.6 Step 1)
  Eigen::VectorXd q0, qd0;  // q(0) [m], q̇(0) [m/s] at θ0 (flexible start)
};

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
  EventKind kind = EventKind::end;
  double vx_before = NAN, vx_after = NAN, restitution = NAN, impulse = NAN;
  double hub_work = NAN;  // impacts: the work the hub does during the impact [J]
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
  double damping_work_j = 0;       // −∫q̇ᵀCq̇ dt ≤ 0, the beam's damping (SPEC §11) [J]
  // The energy ledger in the inertial frame (SPEC §7, §11), works signed as energy given to the
  // filament: hub_work_j + friction_work_j + damping_work_j + impact_loss_j = energy_change_j.
  double hub_work_j = 0;            // ω ∫τ dt including the impulsive part, from the angular-momentum balance [J]
  double hub_impulsive_work_j = 0;  // the hub's work during the impacts (the constraint moves) [J]
  double impact_loss_j = 0;         // the contact impulses' work on the tip, −(energy the impacts dissipate) ≤ 0 [J]
  double energy_change_j = 0;       // E = T + U at the end less at the start [J]
  double max_tip_deflection_ratio = 0;
  double energy_audit_residual = 0;
  long steps = 0;
  long rhs_evaluations = 0;
  long corrector_iterations = 0;
  int corrector_iterations_max = 0;
  double wall_time_s = 0;
  Scheme scheme = Scheme::adaptive;
  std::vector<std::string> warnings;
  std::vector<ContactInterval> contact_intervals;
};

/// Receives the history rows and events of a pass as they are produced, so that memory stays
/// bounded whatever the length of the run (the files writer in pass_output.hpp is one).
class PassSink {
public:
  virtual ~PassSink() = default;
  virtual void row(const HistoryRow& row) = 0;
  virtual void event(const PassEvent& event) = 0;
};

struct PassResult {
  std::vector<HistoryRow> history;  // kept only when the pass ran without a sink
  std::vector<PassEvent> events;    // likewise
  PassSummary summary;
  std::optional<NumericalFailure> failure;
};

/// Where a pass is, for progress reports.
struct PassProgress {
  double theta_deg = 0, start_deg = 0, end_deg = 0;  // current, initial and final beam angle
  double elapsed_s = 0;                              // wall time so far
  long steps = 0;
};

/// How a pass is watched: where its rows and events go (nullptr: into PassResult), the token that
/// stops it (nullptr: none), and a progress callback (called a few times a second at most).
struct PassControl {
  PassSink* sink = nullptr;
  const StopToken* stop = nullptr;
  std::function<void(const PassProgress&)> on_progress;
};

/// Runs one pass of `system` from `initial` with options.scheme's stepper under the pass driver.
/// Never throws for numerical trouble: a failure is returned in PassResult::failure with everything
/// computed up to it.
PassResult run_pass(const System& system, const InitialConditions& initial, const PassOptions& options,
                    const PassControl& control = {});

}  // namespace rotbeam
