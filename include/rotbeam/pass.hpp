// A whole pass through contact (docs/model.md §6, §7): the initial conditions, the outputs as they are
// produced (a PassSink) or kept in memory (PassResult), and the entry point that runs the pass
// driver over the configured scheme's stepper.
#pragma once

#include "rotbeam/force_record.hpp"
#include "rotbeam/wear_record.hpp"
#include "rotbeam/ledger.hpp"
#include "rotbeam/outcome.hpp"
#include "rotbeam/pass_options.hpp"
#include "rotbeam/state.hpp"
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

/// One row of the time history (docs/model.md §7). Forces in N, positions in m, velocities in m/s.
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
  double tangential_impulse = NAN;  // impacts: P_t along the surface's tangent [N s] (0 without friction)
  double hub_work = NAN;  // impacts: the work the hub does during the impact [J]
  double impact_loss = NAN;   // impacts: the impulses' work on the tip less a moving surface's part (≤ 0) [J]
  double surface_work = NAN;  // impacts: a moving surface's work through the impact's friction [J]
  double frictional_heat = NAN;  // impacts: the heat its friction makes, −∫V_t dP_t (≥ 0) [J]
  double sliding_load = NAN;     // impacts: its Archard load–distance ∫|V_t| dp [N m]
  std::string detail;
};

struct ContactInterval {
  double t_start = 0, t_end = 0, theta_start = 0, theta_end = 0, y_start = 0, y_end = 0;
  int revolution = 1;  // the revolution it began in (docs/model.md §11: revolution k spans [θ0 + 360°(k − 1), θ0 + 360°k))
};

/// One revolution of a run over many (docs/model.md §11, revolutions.csv). Its ledger's energy terms sum to
/// its energy change (ledger.hpp; the residual is the difference). Angles are relative to the
/// revolution, in (−180°, 180°], 0° where the undeformed filament points at the surface's deepest point.
struct RevolutionRecord {
  int revolution = 0;     // 1, 2, …
  bool complete = false;  // false for a revolution cut short by the end angle, a failure or a stop
  double t_start = 0, t_end = 0;  // [s]
  int impacts = 0;
  int contact_episodes = 0;             // episodes that ended in this revolution
  double first_impact_deg = NAN;        // NaN: no impact
  double last_separation_deg = NAN;     // the last impact or contact end; NaN: none
  Ledger ledger;                        // the revolution's terms and energy change
  double mean_hub_torque_n_m = 0;       // hub work / Δθ
  double mean_hub_power_w = 0;          // hub work / Δt
  double max_tip_deflection_ratio = 0;
  double contact_time_s = 0;
  double stick_time_s = 0;  // the part of contact_time_s in which the tip stuck [s]
  double peak_normal_force_n = 0;
  // The relative change of the section state z = (q/L, q̇/(ωL)) at the revolution's end from the
  // previous section: ‖Δz‖ / max(‖z_k‖, ‖z_(k−1)‖) (0 when both are 0); NaN for an incomplete one.
  double section_distance = NAN;
  Eigen::VectorXd q, qd;  // the state at the revolution's end [m], [m/s]
};

/// The section state z = (q/L, q̇/(ωL)) (dimensionless) of the modal state q [m], q̇ [m/s] (docs/model.md §11),
/// written into z (resized to 2n) or returned.
void section_state(const BeamModel& beam, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Eigen::VectorXd& z);
Eigen::VectorXd section_state(const BeamModel& beam, const Eigen::VectorXd& q, const Eigen::VectorXd& qd);

/// The relative distance ‖a − b‖ / max(‖a‖, ‖b‖) between two section states (0 when both are 0):
/// the measure of simulation.steady_tolerance and of revolutions.csv's section_distance.
double section_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b);

/// A Floquet multiplier of the one-revolution map (an eigenvalue of its Jacobian at the section).
struct Multiplier {
  double re = 0, im = 0;
  double magnitude() const { return std::hypot(re, im); }
};

/// The search for the periodic steady state (simulation.until_steady, docs/model.md §11).
struct SteadyState {
  bool sought = false;                 // simulation.until_steady
  bool reached = false;
  int after_revolutions = 0;           // revolutions run when it was reached (0: not reached)
  int period_revolutions = 0;          // the orbit repeats every this many revolutions (1 … 4; 0: not reached)
  double tolerance = 0;
  SteadyMethod method = SteadyMethod::brute_force;
  std::vector<Multiplier> multipliers; // largest magnitude first; empty when not computed
  double final_distance = NAN;         // the section distance when the search ended
  int newton_iterations = 0;           // shooting
  int map_evaluations = 0;             // one-revolution runs of the shooting and the multipliers
  int event_sequence_changes = 0;      // evaluations whose impacts or episodes differed from the orbit's
  // How the map's Jacobians were computed: "variational", "differences" (simulation.jacobian, or where
  // the variational equations could not be carried through a run: the note says why), "" when none was.
  std::string jacobian;
  std::string note;                    // how the search ended, in words
};

/// Whether a pass stayed where the model holds (docs/model.md, "Validity"): within it; at the edge of
/// the quadratic foreshortening (max |y_t|/L above simulation.deflection_warning_ratio); or outside
/// its geometry (the tip farther than L from its clamp: the results are not physical). A result,
/// not a failure: the pass runs on (exit 0) unless simulation.deflection_limit_is_error.
enum class Validity { within, edge, outside };

/// Above this |y_t|/L the quadratic foreshortening's tip is 1e-2 L or more from the exact (elastica's)
/// tip for the same q (measured on the first mode's shape: 2.4e-4 L at 0.1, 1.9e-3 L at 0.2, 1.0e-2 L at
/// 0.35, 1.5e-2 L at 0.4; about 0.24 (|y_t|/L)³ L): a pass that bends further is `outside` the model
/// (docs/model.md "Validity of a pass").
inline constexpr double kOutsideDeflectionRatio = 0.35;

/// "within", "edge", "outside": the summary's `validity`.
inline const char* validity_name(Validity v) {
  return v == Validity::within ? "within" : v == Validity::edge ? "edge" : "outside";
}

struct PassSummary {
  int impacts = 0;
  int plastic_impacts = 0;
  int contact_episodes = 0;
  double first_impact_deg = NAN;
  double last_separation_deg = NAN;
  double contact_time_s = 0;
  double stick_time_s = 0;  // the part of contact_time_s in which the tip stuck [s]
  double peak_normal_force_n = 0;
  double mean_normal_force_n = 0;
  // The ledger of the pass in the inertial frame (docs/model.md §7, §11; ledger.hpp): works signed as energy
  // given to the filament, whose energy terms sum to the change of E = T + U (+ a compliant
  // contact's elastic energy (2/5)kδ^{5/2}), and the momenta exchanged with the surface.
  Ledger ledger;
  double hub_impulsive_work_j = 0;  // the part of the hub's work done during the impacts (the constraint moves) [J]
  double max_tip_deflection_ratio = 0;
  Validity validity = Validity::within;
  bool left_geometry = false;  // outside because the tip went farther than 1.01 L from its clamp
  double energy_audit_residual = 0;
  // simulation.end_when_clear: the angle at which the pass ended because the tip could no longer
  // reach the surface before end_angle_deg; NaN when it ran to its end angle.
  double ended_clear_deg = NAN;
  // The case's undamped natural frequencies at its hub speed, linearised about the straight
  // filament (run_case fills them; empty otherwise) [Hz]: where a rub map's engine orders cross.
  Eigen::VectorXd natural_frequencies_hz;
  // Runs over revolutions: the last complete revolution's record (none before the first completes).
  std::optional<RevolutionRecord> last_revolution;
  long steps = 0;
  long rhs_evaluations = 0;
  long corrector_iterations = 0;
  int corrector_iterations_max = 0;
  double wall_time_s = 0;
  Scheme scheme = Scheme::adaptive;
  std::vector<std::string> warnings;
  std::vector<ContactInterval> contact_intervals;  // of the revolutions kept (output.history_revolutions)
  // Many revolutions (simulation.revolutions > 0).
  int revolutions = 0;                   // complete revolutions run
  double mean_hub_torque_n_m = NAN;      // of the last complete revolution
  double mean_hub_power_w = NAN;
  SteadyState steady_state;
  // The force on the surface in hub-angle bins of output.bin_deg, impacts included (force_bins.hpp):
  // over the pass, or over the last complete revolution of a run over many.
  BinnedForcePeaks binned_force;
};

/// Receives the history rows and events of a pass as they are produced, so that memory stays
/// bounded whatever the length of the run (the files writer in pass_output.hpp is one).
class PassSink {
public:
  virtual ~PassSink() = default;
  virtual void row(const HistoryRow& row) = 0;
  virtual void event(const PassEvent& event) = 0;
  /// A revolution ended (its rows and events came before). Runs of one pass never call it.
  virtual void revolution(const RevolutionRecord&) {}
  /// Whether the sink wants delivery() (it costs the angular momentum at every accepted step).
  virtual bool wants_deliveries() const { return false; }
  /// What an accepted step or an impact delivered (force_bins.hpp), in order: those between two
  /// revolution() calls are that revolution's, and ω times their hub angular impulses sums to its
  /// hub_work_j.
  virtual void delivery(const MomentumDelivery&) {}
};

struct PassResult {
  std::vector<HistoryRow> history;  // kept only when the pass ran without a sink
  std::vector<PassEvent> events;    // likewise
  PassSummary summary;
  std::vector<RevolutionRecord> revolutions;  // one per revolution (runs over many)
  std::vector<ForceBin> force_bins;           // the bins of summary.binned_force (force_bins.csv)
  // The contact's load–distance and heat along the surface (docs/wear.md): over the pass, or over the
  // last complete revolution of a run over many (over the pass so far when none completed); and the
  // profiles of the last kWearRevolutionsKept complete revolutions, oldest first (a period-m orbit's
  // mean profile is theirs over its last m, wear.hpp's mean_profile).
  std::vector<WearBin> wear_profile;
  std::vector<std::vector<WearBin>> wear_revolution_profiles;
  Eigen::VectorXd final_q, final_qd;          // the state where the run ended [m], [m/s]
  double final_t = 0;                         // [s]
  // With PassOptions::tangent: Φ = ∂(q, q̇)/∂(q₀, q̇₀) at the end (2n × 2n, tangent.hpp), empty where it
  // could not be carried through the run, and then why (tangent_lost).
  Eigen::MatrixXd final_tangent;
  std::string tangent_lost;
  std::optional<NumericalFailure> failure;
};

/// Where a pass is, for progress reports.
struct PassProgress {
  double theta_deg = 0, start_deg = 0, end_deg = 0;  // current, initial and final beam angle
  double elapsed_s = 0;                              // wall time so far
  long steps = 0;
  int revolution = 0, revolutions = 0;  // the revolution under way (1, 2, …) and the run's number (0: one pass)
  double section_distance = NAN;        // the last complete revolution's section distance
  std::string stage;                    // a steady-state search's stage in words ("" while a run turns)
};

/// Watches the revolutions of a run over many (the steady-state search of steady_state.hpp is one):
/// told of every complete revolution as it closes, it may end the run there; at the run's end it
/// gives its account in the summary.
class RevolutionWatcher {
public:
  virtual ~RevolutionWatcher() = default;
  /// The run starts at (q, q̇) [m], [m/s] (the first revolution's section).
  virtual void start(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) = 0;
  /// A complete revolution closed (with its section distance): true ends the run there.
  virtual bool revolution(const RevolutionRecord& record) = 0;
  /// The run ended in revolution `revolution` (after a failure when `failed`): fills
  /// summary.steady_state; returns a warning for the run ("" for none).
  virtual std::string finish(PassSummary& summary, bool failed, int revolution) = 0;
};

/// How a pass is watched: where its rows and events go (nullptr: into PassResult), the token that
/// stops it (nullptr: none), a progress callback (called a few times a second at most), and a
/// watcher of its revolutions (nullptr: none).
struct PassControl {
  PassSink* sink = nullptr;
  const StopToken* stop = nullptr;
  std::function<void(const PassProgress&)> on_progress;
  RevolutionWatcher* watcher = nullptr;
};

/// A sink that keeps nothing (a run whose summary alone is wanted).
class DiscardSink final : public PassSink {
public:
  void row(const HistoryRow&) override {}
  void event(const PassEvent&) override {}
};

/// Runs one pass of `system` from `initial` with options.scheme's stepper under the pass driver.
/// Never throws for numerical trouble: a failure is returned in PassResult::failure with everything
/// computed up to it. options.until_steady is the watcher's (control.watcher; run_to_steady_state in
/// steady_state.hpp gives one): run_pass itself runs to the end angle or the watcher's word.
PassResult run_pass(const System& system, const InitialConditions& initial, const PassOptions& options,
                    const PassControl& control = {});

class Stepper;
/// run_pass over a stepper the caller made (stepper.hpp's contract): a scheme of the caller's own, or
/// a test's scripted stepper that checks the driver's logic without integrating anything. The stepper
/// must be fresh (no step taken); options.scheme is only reported.
PassResult run_pass_with(const System& system, const InitialConditions& initial, const PassOptions& options,
                         Stepper& stepper, const PassControl& control = {});

}  // namespace rotbeam
