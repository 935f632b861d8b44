// Bookkeeping of a pass for the driver (SPEC §7): history rows at a fixed interval plus every
// event, contact episodes, the running metrics and the energy audit. Rows and events go to the
// pass's sink as they are produced (or into PassResult without one); nothing else grows with the
// length of the run but the list of contact intervals.
#pragma once

#include "rotbeam/impact.hpp"
#include "rotbeam/pass.hpp"

#include <memory>

namespace rotbeam {

class PassRecorder {
public:
  PassRecorder(const System& system, const PassOptions& options, const PassControl& control, PassResult& result);

  /// The start of the pass.
  void start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  /// An accepted point reached over a step from the previous accepted point, with the contact
  /// load at the new point and the step's contact integrals (from the stepper).
  void accept(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase, const ContactLoad& load,
              const StepIntegrals& integrals, bool force_sample = false);
  void impact(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd_before, const Eigen::VectorXd& qd_after,
              const ImpactResult& r);
  /// Sustained contact begins with the contact load `load` (a history row is written).
  void contact_start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const ContactLoad& load,
                     const std::string& detail);
  void contact_end(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const std::string& detail);
  void event(EventKind kind, double t, const Eigen::VectorXd& q, const std::string& detail);
  /// A warning: kept once in the summary and recorded as an event at t.
  void warn(double t, const Eigen::VectorXd& q, const std::string& message);
  void fail(FailureKind kind, double t, const std::string& message);
  /// The end of the pass (after a failure too): closes an open episode, the last row, the summary.
  void finish(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase,
              const StepperStatistics& statistics);

  bool in_episode() const { return in_episode_; }
  bool failed() const { return result_.failure.has_value(); }
  /// True when the pass must stop now: a stop was requested, or the validity limit was breached
  /// with deflection_limit_is_error (the failure is recorded the first time it is seen).
  bool stop_requested(double t);
  /// True (with an `impacts` failure recorded) when the pass already had options.max_impacts impacts.
  bool impacts_exhausted(double t);

private:
  void sample(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase, const ContactLoad& load);
  void track(double t, const Eigen::VectorXd& q);
  double hub_torque(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const ContactLoad& load);
  void emit(const PassEvent& e);
  double tip_y(double t, const Eigen::VectorXd& q) const;

  const System system_;
  const PassOptions options_;
  PassControl control_;
  PassResult& result_;
  std::unique_ptr<BeamWorkspace> ws_;
  TipKinematics tip_;
  HistoryRow row_;
  Eigen::VectorXd generalized_force_, qdd_;
  double next_sample_t_ = 0;
  double last_t_ = 0;
  bool in_episode_ = false;
  double episode_t0_ = 0, episode_theta0_ = 0, episode_y0_ = 0;
  // Energy audit (rotating frame) and the inertial ledger.
  double h_start_ = 0, work_ = 0, impact_jumps_ = 0, energy_scale_ = 0;
  double energy_start_ = 0, momentum_start_ = 0;  // E = T + U and H_z at the start
  double contact_moment_ = 0;                     // ∫ (X F_Y − Y F_X) dt over sustained contact [N m s]
  double impulse_moment_ = 0;                     // Σ (X P_Y − Y P_X) over the impacts [N m s]
  double normal_time_integral_ = 0;
  bool deflection_warned_ = false;
  bool geometry_warned_ = false;
  bool validity_breached_ = false;
  double validity_ratio_ = 0;
};

}  // namespace rotbeam
