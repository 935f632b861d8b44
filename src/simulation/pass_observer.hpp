// The recorder's observers (internal to the simulation layer; pass_recorder.hpp composes them):
// each keeps one account of a pass — its history rows, its contact metrics, its energy ledger, its
// force on the surface by hub angle, its momentum deliveries, its validity, its revolutions — from
// the same hooks, called by the recorder in the order the pass produces them.
#pragma once

#include "rotbeam/impact.hpp"
#include "rotbeam/pass.hpp"
#include "rotbeam/stepper.hpp"

#include <string>

namespace rotbeam {

/// What every observer of a pass shares: the system, the settings, where the rows go and the result
/// being made, and the revolution under way.
struct PassContext {
  PassContext(const System& s, const PassOptions& o, const PassControl& c, PassResult& r, PassSink& k)
      : system(s), options(o), control(c), result(r), sink(k) {}
  const System system;
  const PassOptions& options;
  const PassControl& control;
  PassResult& result;
  PassSink& sink;       // the caller's, or the in-memory one (memory_sink.hpp)
  int revolution = 0;   // the revolution under way (1, 2, …; 0 in a run of one pass)

  /// ω [rad/s].
  double omega() const;
  /// The hub angle at t relative to the revolution, in (−180°, 180°], 0° at the surface's deepest point.
  double relative_angle_deg(double t) const;
  /// The tip's Y in the global frame at (t, q) [m].
  double tip_y(double t, const Eigen::VectorXd& q) const;
};

/// An accepted point reached over a step from the previous accepted point at t0.
struct StepView {
  double t0, t;
  const Eigen::VectorXd& q;
  const Eigen::VectorXd& qd;
  Phase phase;
  const ContactLoad& load;        // at t
  const StepIntegrals& integrals; // over the step
  bool force_row;                 // the history must have a row here (an event, a section)
};

/// An impact at (t, q): q̇ jumped from qd_before to qd_after; with what the recorder derived once.
struct ImpactView {
  double t;
  const Eigen::VectorXd& q;
  const Eigen::VectorXd& qd_before;
  const Eigen::VectorXd& qd_after;
  const ImpactResult& result;
  double impulse_moment;  // X P_Y − Y P_X, the contact impulse's moment about the hub [N m s]
  double momentum_after;  // H_z after the impact [kg m²/s]
  double hub_work;        // ω (ΔH_z − impulse_moment), the hub's work during the impact [J]
};

/// Where observers write what a pass must be told (a warning: kept once in the summary and recorded
/// as an event).
class PassJournal {
public:
  virtual ~PassJournal() = default;
  virtual void warn(double t, const Eigen::VectorXd& q, const std::string& message) = 0;
};

/// One account of a pass. Every hook is optional.
class PassObserver {
public:
  virtual ~PassObserver() = default;
  /// The pass starts at (t, q, q̇).
  virtual void start(double, const Eigen::VectorXd&, const Eigen::VectorXd&) {}
  virtual void step(const StepView&) {}
  virtual void impact(const ImpactView&) {}
  /// A contact episode begins with `load`; `first_touch`: a touch without an impact.
  virtual void contact_start(double, const Eigen::VectorXd&, const ContactLoad&, bool) {}
  virtual void contact_end(double, const Eigen::VectorXd&) {}
  /// A revolution opens at (t, q, q̇) (runs over many revolutions).
  virtual void open_revolution(double, const Eigen::VectorXd&, const Eigen::VectorXd&) {}
  /// The open revolution closes at (t, q, q̇): the observer writes its part of the record.
  virtual void close_revolution(double, const Eigen::VectorXd&, const Eigen::VectorXd&, RevolutionRecord&) {}
  /// The pass ends at (t, q, q̇): the observer writes its part of the summary.
  virtual void finish(double, const Eigen::VectorXd&, const Eigen::VectorXd&) {}
};

}  // namespace rotbeam
