// Bookkeeping of a pass shared by the schemes: history sampling at a fixed interval plus every
// event, contact episodes, running metrics and the energy audit (SPEC §7).
#pragma once

#include "rotbeam/energy.hpp"
#include "rotbeam/pass.hpp"

#include <chrono>

namespace rotbeam {

/// The contact force state on an accepted point (zero in free flight).
struct ContactLoad {
  double lambda = 0;          // multiplier [N]
  double normal_force = 0;    // reported F_n [N]
  double friction_force = 0;  // F_t on the tip along Y [N]
  double power = 0;           // q̇ᵀQ_contact [W], rate of change of h
  double slip_power = 0;      // F_t V_t [W]
  double slip = 0;            // slip direction s_t used
};

/// Contact integrals over a step when the scheme integrates them itself (adaptive scheme).
struct StepIntegrals {
  double work = 0;            // ∫ q̇ᵀQ_contact dt [J]
  double friction_work = 0;   // ∫ F_t V_t dt [J]
  double normal_impulse = 0;  // ∫ F_n dt [N s]
};

class PassRecorder {
public:
  PassRecorder(const Model& model, const FrictionModel& friction, const PassOptions& options, PassResult& result);

  /// Generalised contact force Q = λ∇C + |λ|Q* and the derived quantities at (t, q, q̇).
  ContactLoad load(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double lambda, double slip);

  /// The start of the pass.
  void start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  /// An accepted point reached over a step from the previous accepted point. `load_end` is the
  /// contact load at the new point, `load_begin` at the previous one (trapezoidal integrals).
  void accept(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase, const ContactLoad& load_begin,
              const ContactLoad& load_end, bool force_sample = false);
  /// The same with the step's contact integrals given exactly (no trapezoidal rule).
  void accept_integrated(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase,
                         const ContactLoad& load_end, const StepIntegrals& integrals, bool force_sample = false);
  void impact(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd_before, const Eigen::VectorXd& qd_after,
              const ImpactResult& r);
  void contact_start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const std::string& detail);
  void contact_end(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const std::string& detail);
  void event(double t, const Eigen::VectorXd& q, const std::string& kind, const std::string& detail);
  /// A warning: kept once in the summary and recorded as an event at t.
  void warn(double t, const std::string& message);
  void fail(const std::string& kind, double t, const std::string& message);
  void finish(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase, const ContactLoad& load);

  bool in_episode() const { return in_episode_; }
  /// True when the pass must stop now: an interrupt was requested or the validity limit was
  /// breached with deflection_limit_is_error (the failure is recorded the first time it is seen).
  bool stop_requested(double t);
  /// True (with an `impacts` failure recorded) when the pass already had options.max_impacts impacts.
  bool impacts_exhausted(double t);
  long& steps() { return result_.summary.steps; }
  long& rhs() { return result_.summary.rhs_evaluations; }

private:
  void sample(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase, const ContactLoad& load);
  void track(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  double hub_torque(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const ContactLoad& load);

  const Model& model_;
  const FrictionModel& friction_;
  const PassOptions& options_;
  PassResult& result_;
  Workspace ws_;
  TipKinematics tip_;
  Eigen::VectorXd generalized_force_, qdd_, q_probe_, qd_probe_, qstar_;
  double next_sample_t_ = 0;
  double last_t_ = 0;
  bool in_episode_ = false;
  double episode_t0_ = 0, episode_theta0_ = 0, episode_y0_ = 0;
  double last_contact_load_lambda_ = 0;
  // Energy audit.
  double h_start_ = 0, work_ = 0, impact_jumps_ = 0, energy_scale_ = 0;
  double normal_time_integral_ = 0;
  bool deflection_warned_ = false;
  bool validity_breached_ = false;
  double validity_ratio_ = 0;
};

/// Runs a scheme into a fresh PassResult named `scheme` and records its wall time.
template <class RunScheme>
PassResult timed_pass(const char* scheme, RunScheme&& run) {
  const auto wall0 = std::chrono::steady_clock::now();
  PassResult result;
  result.summary.scheme = scheme;
  run(result);
  result.summary.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return result;
}

}  // namespace rotbeam
