// The pass driver (docs/model.md §4–§6): the phase logic of a pass, written once over the steppers' contract
// (stepper.hpp) and the contact law's (contact_law.hpp). Free flight until the gap closes; then the
// law decides (an impact, a contact phase, a lift-off) and the driver carries it out (PhaseControl);
// a contact phase until one of its roots: the law's end of contact returns to free flight, its other
// roots are the law's to decide. The driver keeps the revolutions' sections, the Zeno floor, the
// chatter guard, the early end and stop requests. The scheme only advances the state of a phase and
// reports the roots it crosses.
#pragma once

#include "pass_recorder.hpp"

#include "rotbeam/detail/progress_clock.hpp"
#include "rotbeam/contact_law.hpp"
#include "rotbeam/pass.hpp"
#include "rotbeam/stepper.hpp"
#include "rotbeam/tangent.hpp"

#include <cmath>
#include <optional>
#include <string>

namespace rotbeam {

/// An event of a pass whose saltation matrix is still to be applied (PassOptions::tangent): the root
/// function that reached zero and the state before it.
struct PendingEvent {
  EventSurface surface;
  EventSide before;
  int impacts = 0;  // impacts the law applied at the event
};

class PassDriver final : public PhaseControl {
public:
  PassDriver(const System& system, const PassOptions& options, Stepper& stepper, PassRecorder& recorder,
             const PassControl& control);
  /// Runs the pass from `initial` to the end angle or a diagnosed failure.
  void run(const InitialConditions& initial);
  /// With PassOptions::tangent: Φ at the end of the run (empty where it was lost), and why it was lost.
  Eigen::MatrixXd final_tangent() const { return tangent_lost_.empty() ? state_.tangent : Eigen::MatrixXd(); }
  const std::string& tangent_lost() const { return tangent_lost_; }

  // PhaseControl: what the contact law's transitions do (contact_law.hpp).
  const System& system() const override { return system_; }
  FilamentState& state() override { return state_; }
  BeamWorkspace& workspace() override { return *ws_; }
  TipKinematics& tip() override { return tip_; }
  Eigen::VectorXd& scratch() override { return scratch_; }
  bool lifts_off_on_positive_multiplier() const override { return traits_.lifts_off_on_positive_multiplier; }
  bool holds_stick() const override { return traits_.holds_stick; }
  bool impacts_exhausted() override;
  void impact(const Eigen::VectorXd& qd_before, const ImpactResult& result) override;
  void rebound() override;
  void enter_contact(const ContactLoad& load, const std::string& why, bool first_touch) override;
  void lift_off(const std::string& why) override;
  void end_contact(const std::string& why) override;
  void event(EventKind kind, const std::string& detail) override;
  void fail(FailureKind kind, const std::string& message, Phase phase) override;

private:
  void loop();
  void free_flight();
  void contact();
  // Free flight from the current state after a separation or lift-off.
  void separate();
  void fail_at(FailureKind kind, double t, const std::string& message, Phase phase);
  void finish(Phase phase);
  void report_progress();
  // The end of the current stepper call: the end of the run or the next revolution's section.
  double stop_time() const { return std::min(t_end_, next_section_); }
  // At a section (state_.t == next_section_): closes the revolution; true when the run must finish
  // (the steady state was reached). In free flight the stepper restarts there (FreeStart::pass_start).
  bool cross_section();
  // simulation.end_when_clear: true when, from the current free-flight state, the tip provably
  // cannot reach the surface before the end angle (checked every kClearCheckDeg of hub angle).
  bool clear_for_the_rest();

  const System system_;
  const PassOptions options_;
  Stepper& stepper_;
  PassRecorder& rec_;
  StepperTraits traits_;
  std::unique_ptr<BeamWorkspace> ws_;
  TipKinematics tip_;
  FilamentState state_;
  Eigen::VectorXd scratch_;
  double t_end_ = 0;
  double period_ = INFINITY;        // one revolution [s] (runs over many)
  double next_section_ = INFINITY;  // the next interior section [s]
  int section_index_ = 0;           // sections crossed
  bool done_ = false;
  int instant_transitions_ = 0;  // phase changes without time advancing (chatter guard)
  std::function<void(const PassProgress&)> on_progress_;
  detail::ProgressClock progress_clock_;
  double flexible_from_t_ = 0.0;  // where the integration of the flexible motion began [s]
  double next_clear_check_t_ = 0.0;  // simulation.end_when_clear: the next check [s]

  // The variational equations (PassOptions::tangent, tangent.hpp): an event opens where a root
  // function reached zero (a touch, a root of a contact phase) with the state before it; the new
  // phase's start applies its saltation matrix to state_.tangent.
  void open_event(const EventSurface& surface);
  void close_event();
  void lose_tangent(const std::string& why);
  bool tracking() const { return options_.tangent && tangent_lost_.empty(); }
  std::optional<TangentWorkspace> tangent_ws_;
  std::optional<PendingEvent> pending_;
  std::string tangent_lost_;
};

}  // namespace rotbeam
