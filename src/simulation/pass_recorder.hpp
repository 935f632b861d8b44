// The record of a pass for the driver (docs/model.md §7): its events, and its observers (pass_observer.hpp),
// each keeping one account — the history rows (history_sampler.hpp), the contact metrics
// (contact_metrics.hpp), the energy ledger and its audit (energy_ledger.hpp), the force on the surface
// by hub angle (force_binning.hpp), the load–distance and heat along the surface (wear_profile.hpp),
// the momentum deliveries for a sink that asks (deliveries.hpp), the
// validity (validity_monitor.hpp) and the revolutions (revolution_book.hpp). Rows and events go to
// the pass's sink as they are produced (or into PassResult without one, memory_sink.hpp); nothing else
// grows with the length of the run but the list of contact intervals.
#pragma once

#include "contact_metrics.hpp"
#include "deliveries.hpp"
#include "energy_ledger.hpp"
#include "force_binning.hpp"
#include "wear_profile.hpp"
#include "history_sampler.hpp"
#include "memory_sink.hpp"
#include "revolution_book.hpp"
#include "validity_monitor.hpp"

#include <optional>
#include <vector>

namespace rotbeam {

class PassRecorder final : public PassJournal {
public:
  PassRecorder(const System& system, const PassOptions& options, const PassControl& control, PassResult& result);

  /// The start of the pass.
  void start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  /// A rigid start's turn (q = q̇ = 0) from the start to t_to, where the tip reaches the surface.
  void rigid_turn(double t_to) { sampler_.rigid_turn(last_t_, t_to); }
  /// Free flight reached t (state q) over the step `stepper` just took: rows strictly inside the
  /// step from the stepper's dense output. Call before accept(t, …).
  void free_rows_within(double t, const Eigen::VectorXd& q, Stepper& stepper) {
    sampler_.free_rows_within(last_t_, t, q, stepper);
  }
  /// An accepted point reached over a step from the previous accepted point, with the contact
  /// load at the new point and the step's integrals (from the stepper).
  void accept(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase, const ContactLoad& load,
              const StepIntegrals& integrals, bool force_sample = false);
  void impact(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd_before, const Eigen::VectorXd& qd_after,
              const ImpactResult& r);
  /// A contact episode begins with the contact load `load` (a history row is written);
  /// `first_touch`: a touch without an impact (a compliant contact), which sets the first touch angle.
  void contact_start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const ContactLoad& load,
                     const std::string& detail, bool first_touch);
  void contact_end(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const std::string& detail);
  void event(EventKind kind, double t, const Eigen::VectorXd& q, const std::string& detail);
  /// The pass ends early at t: the tip cannot reach the surface again (simulation.end_when_clear).
  void ended_clear(double t) { ctx_.result.summary.ended_clear_deg = ctx_.system.beam.theta(t) * 180.0 / M_PI; }
  /// A warning: kept once in the summary and recorded as an event at t.
  void warn(double t, const Eigen::VectorXd& q, const std::string& message) override;
  /// The failure that stops the pass at t. `q`: the state at t where it is known (the failure event
  /// then has the tip's y from it, as the history's last row has); nullptr where t lies inside a
  /// step whose state is not known (y_tip NaN).
  void fail(FailureKind kind, double t, const std::string& message, const Eigen::VectorXd* q);
  /// The end of the pass (after a failure too): closes an open episode, the last row, the summary.
  void finish(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase,
              const StepperStatistics& statistics);

  /// A revolution's section at t (runs over many revolutions; the driver calls it at every interior
  /// boundary, after accepting the boundary point): closes the revolution's record and, unless the
  /// watcher (PassControl::watcher) ends the run there (then it returns true), opens the next.
  bool end_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  /// The revolution under way (1, 2, …; 0 in a run of one pass).
  int revolution() const { return ctx_.revolution; }
  /// The last complete revolution's section distance (NaN before one).
  double section_distance() const { return book_.last_distance(); }

  bool in_episode() const { return metrics_.in_episode(); }
  bool failed() const { return ctx_.result.failure.has_value(); }
  /// True when the pass must stop now: a stop was requested, or the validity limit was breached
  /// with deflection_limit_is_error (the failure is recorded the first time it is seen).
  bool stop_requested(double t, const Eigen::VectorXd& q);
  /// True (with an `impacts` failure recorded) when the pass (or, over many revolutions, the
  /// revolution) already had options.max_impacts impacts.
  bool impacts_exhausted(double t, const Eigen::VectorXd& q);

private:
  void open_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  // Closes the open revolution at t; true when the watcher ends the run there.
  bool close_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, bool complete);
  void emit(const PassEvent& e);

  std::optional<MemorySink> memory_;  // without the caller's sink
  PassContext ctx_;
  HistorySampler sampler_;
  ContactMetrics metrics_;
  EnergyLedger ledger_;
  ForceBinning bins_;
  WearProfile wear_;
  std::optional<Deliveries> deliveries_;  // for a sink that wants them
  ValidityMonitor validity_;
  RevolutionBook book_;
  std::vector<PassObserver*> observers_;  // in the order they are told (the book last: it keeps the record)
  double last_t_ = 0;                     // the last accepted point [s]
  bool revolution_open_ = false;
  double revolution_t0_ = 0;              // the open revolution's start [s]
};

}  // namespace rotbeam
