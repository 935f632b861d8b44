// Bookkeeping of a pass for the driver (SPEC §7): history rows at a fixed interval plus every
// event, contact episodes, the running metrics and the energy audit. Rows and events go to the
// pass's sink as they are produced (or into PassResult without one); nothing else grows with the
// length of the run but the list of contact intervals.
#pragma once

#include "rotbeam/force_bins.hpp"
#include "rotbeam/impact.hpp"
#include "rotbeam/pass.hpp"
#include "rotbeam/stepper.hpp"
#include "rotbeam/surface.hpp"

#include <memory>

namespace rotbeam {

class PassRecorder {
public:
  PassRecorder(const System& system, const PassOptions& options, const PassControl& control, PassResult& result);

  /// The start of the pass.
  void start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  /// A rigid start's turn (q = q̇ = 0) from the start to t_to, where the tip reaches the surface:
  /// rows before t_to every output.interval_s or every 0.1° of hub angle, whichever is longer
  /// (near the surface, every output.near_surface_interval_s).
  void rigid_turn(double t_to);
  /// Free flight reached t (state q) over the step `stepper` just took: rows strictly inside the
  /// step from the stepper's dense output, on the grid k·output.interval_s and, while the tip is
  /// near the surface (output.near_surface_gap_m), every output.near_surface_interval_s. Call
  /// before accept(t, …). A stepper without dense output (the thesis's) gives none.
  void free_rows_within(double t, const Eigen::VectorXd& q, Stepper& stepper);
  /// An accepted point reached over a step from the previous accepted point, with the contact
  /// load at the new point and the step's contact integrals (from the stepper).
  void accept(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase, const ContactLoad& load,
              const StepIntegrals& integrals, bool force_sample = false);
  void impact(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd_before, const Eigen::VectorXd& qd_after,
              const ImpactResult& r);
  /// Sustained contact begins with the contact load `load` (a history row is written).
  void contact_start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const ContactLoad& load,
                     const std::string& detail);
  /// A compliant (Hertz) contact begins (contact_start with `detail`): the pass's and the
  /// revolution's first touch angle is set here, since the compliant law has no impacts.
  void compliant_touch(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const ContactLoad& load,
                       const std::string& detail);
  void contact_end(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const std::string& detail);
  void event(EventKind kind, double t, const Eigen::VectorXd& q, const std::string& detail);
  /// The pass ends early at t: the tip cannot reach the surface again (simulation.end_when_clear).
  void ended_clear(double t) { result_.summary.ended_clear_deg = system_.beam.theta(t) * 180.0 / M_PI; }
  /// A warning: kept once in the summary and recorded as an event at t.
  void warn(double t, const Eigen::VectorXd& q, const std::string& message);
  void fail(FailureKind kind, double t, const std::string& message);
  /// The end of the pass (after a failure too): closes an open episode, the last row, the summary.
  void finish(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase,
              const StepperStatistics& statistics);

  /// A revolution's section at t (runs over many revolutions; the driver calls it at every interior
  /// boundary, after accepting the boundary point): closes the revolution's record and, unless that
  /// reached the steady state (then it returns true and the run should finish), opens the next.
  bool end_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  /// The revolution under way (1, 2, …; 0 in a run of one pass).
  int revolution() const { return revolution_; }
  /// The last complete revolution's section distance (NaN before one).
  double section_distance() const { return last_distance_; }

  bool in_episode() const { return in_episode_; }
  bool failed() const { return result_.failure.has_value(); }
  /// True when the pass must stop now: a stop was requested, or the validity limit was breached
  /// with deflection_limit_is_error (the failure is recorded the first time it is seen).
  bool stop_requested(double t);
  /// True (with an `impacts` failure recorded) when the pass (or, over many revolutions, the
  /// revolution) already had options.max_impacts impacts.
  bool impacts_exhausted(double t);

private:
  // Ledger totals and counters at a revolution's start, whose differences make its record.
  struct RevolutionMark {
    double t = 0, energy = 0, momentum = 0, contact_time = 0;
    LedgerValues ledger;
    int impacts = 0, episodes = 0;
    std::size_t history_rows = 0, events = 0;  // in-memory sizes (runs without a sink)
  };
  void open_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  // Closes the open revolution at t; true when it reached the steady state.
  bool close_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, bool complete);
  // Keeps the in-memory history, events and contact intervals of the last output.history_revolutions.
  void drop_old_revolutions();
  double relative_angle_deg(double t) const;
  void note_force(double normal_force);
  // True when the tip at (t, q) is within output.near_surface_gap_m of the surface (remembers the gap).
  bool near_surface(double t, const Eigen::VectorXd& q);
  void sample(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase, const ContactLoad& load);
  void track(double t, const Eigen::VectorXd& q);
  double hub_torque(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const ContactLoad& load);
  void emit(const PassEvent& e);
  double tip_y(double t, const Eigen::VectorXd& q) const;
  // The elastic energy stored in a compliant contact at (t, q) [J] (0 under the rigid law).
  double contact_energy(double t, const Eigen::VectorXd& q) const;

  const System system_;
  const PassOptions options_;
  PassControl control_;
  PassResult& result_;
  std::unique_ptr<BeamWorkspace> ws_;
  TipKinematics tip_;
  HistoryRow row_;
  Eigen::VectorXd generalized_force_, qdd_;
  double next_sample_t_ = 0;
  double next_near_t_ = 0;              // the next row time on the near-surface grid [s]
  double last_gap_ = -INFINITY;         // the gap at the last point asked about [m]
  double gap_t_ = NAN;                  // … and its time [s]
  Eigen::VectorXd iq_, iqd_;            // interpolated or rigid-turn states (scratch)
  ForceBins bins_;                      // of the pass, or of the revolution under way
  std::vector<ForceBin> complete_bins_;  // the last complete revolution's (runs over many)
  BinnedForcePeaks complete_peaks_;
  bool deliveries_ = false;             // the sink wants each step's MomentumDelivery
  double last_h_ = 0;                   // H_z at the last accepted point (deliveries) [kg m² /s]
  double last_t_ = 0;
  bool in_episode_ = false;
  bool touched_ = false;  // a compliant contact has begun in this pass
  double episode_t0_ = 0, episode_theta0_ = 0, episode_y0_ = 0;
  // Energy audit (rotating frame) and the inertial ledger.
  double h_start_ = 0, impact_jumps_ = 0, energy_scale_ = 0;
  double energy_start_ = 0, momentum_start_ = 0;  // E = T + U and H_z at the start
  double normal_time_integral_ = 0;               // ∫ F_n dt over sustained contact [N s]
  bool deflection_warned_ = false;
  bool geometry_warned_ = false;
  bool validity_breached_ = false;
  double validity_ratio_ = 0;
  // Revolutions (options.revolutions > 0).
  double t_start_ = 0;         // the run's start [s]
  int revolution_ = 0;         // the latest revolution opened (0: none)
  bool revolution_open_ = false;
  RevolutionMark mark_;
  std::vector<RevolutionMark> kept_marks_;  // starts of the revolutions kept in memory
  double rev_first_impact_deg_ = NAN, rev_last_separation_deg_ = NAN, rev_peak_force_ = 0, rev_max_ratio_ = 0;
  Eigen::VectorXd section_prev_, section_;  // z = (q/L, q̇/(ωL)) at the open revolution's start, and scratch
  std::vector<Eigen::VectorXd> older_sections_;  // the sections before section_prev_, oldest first
  double last_distance_ = NAN;
  RevolutionRecord last_complete_;
  bool have_complete_ = false;
};

}  // namespace rotbeam
