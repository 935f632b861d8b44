// The pass driver (SPEC §4–§6): the phase logic of a pass, written once over the steppers'
// contract (stepper.hpp). free flight → (touch) impact or contact → (λ = 0) separation, with the
// slip decisions (stick, lift-off, slip reversal), Painlevé's paradox, the Zeno floor and the
// chatter guard. The scheme only advances the state of a phase and reports the roots it crosses.
#pragma once

#include "pass_recorder.hpp"

#include "rotbeam/detail/progress_clock.hpp"
#include "rotbeam/pass.hpp"

#include <cmath>

namespace rotbeam {

class PassDriver {
public:
  PassDriver(const System& system, const PassOptions& options, Stepper& stepper, PassRecorder& recorder,
             const PassControl& control);
  /// Runs the pass from `initial` to the end angle or a diagnosed failure.
  void run(const InitialConditions& initial);

private:
  void loop();
  void free_flight();
  void contact();
  // A touch at the current state: an impact for an approaching tip, else a grazing contact start.
  void touch();
  // Momentum-balance impact at the current state; chooses the next phase.
  void impact();
  // Enters sustained contact at the current state (C = Ċ = 0) if the slip analysis allows it.
  void begin_contact(const std::string& why);
  // A compliant (Hertz) contact begins at the current state (C = 0): its damping from the approach
  // speed, a contact_start event, then the stepper's compliant phase (SPEC §11).
  void compliant_contact();
  // Free flight from the current state after a separation or lift-off.
  void separate();
  void fail(FailureKind kind, double t, const std::string& message, Phase phase);
  void finish(Phase phase);
  bool check_slip();
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
  Eigen::VectorXd qd_before_, force_;
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
  const bool compliant_ = system_.law.model == ContactModel::hertz;  // contact.model = "hertz"
};

}  // namespace rotbeam
