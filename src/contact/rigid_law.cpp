// The rigid contact law (SPEC §4, §5; thesis §4.4–4.5): a unilateral constraint C = 0 whose multiplier
// λ ≤ 0 is the normal force, Coulomb friction F_t = −μ_eff|λ| s_t, and momentum-balance impacts with
// a coefficient of restitution. Its one contact phase slides (s_t = ±1) and is a constraint; its
// roots are λ = 0 (separation) and V_t = 0 (the slip stops: stick, lift-off or reversal, decided by
// the locked-tip analysis). A stick, and a λ + b|λ| = c with no or two admissible solutions
// (Painlevé's paradox), stop the pass with a diagnostic. Episode: parameter[0] = λ0, the
// acceleration-level multiplier at the contact's start (the thesis scheme's first prediction).
#include "laws.hpp"

#include "rotbeam/rigid_contact.hpp"
#include "rotbeam/detail/diagnostics.hpp"

#include <algorithm>
#include <array>

namespace rotbeam {

namespace {

using detail::short_number;

constexpr std::array<ContactRoot, 2> kSlidingRoots = {{
    {"λ = 0", true, "λ reached 0"},
    {"V_t = 0", false, ""},
}};

class RigidLaw final : public ContactLaw {
public:
  using ContactLaw::ContactLaw;

  const char* name() const override { return "rigid"; }
  bool has_thesis_scheme() const override { return true; }
  PhaseKind kind(Phase) const override { return PhaseKind::constraint; }
  std::span<const ContactRoot> roots(Phase) const override { return kSlidingRoots; }

  ContactEvaluation evaluate(const System& system, const ContactEpisode& episode, double t,
                             const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                             BeamWorkspace& ws, TipKinematics& tip,
                             Eigen::Ref<Eigen::VectorXd> generalized_force) const override {
    const AccelerationMultiplier am =
        acceleration_multiplier(system.beam, system.surface, friction(), t, q, qd, episode.slip, ws, tip);
    ContactEvaluation e;
    e.admissible = am.solution.status == MultiplierSolution::Status::unique;
    e.a = am.a, e.b = am.b, e.c = am.c;
    // Past a separation (λ > 0) the contact force is zero; a step is cut at λ = 0 anyway.
    e.load = contact_load(friction(), tip, qd, std::min(am.solution.lambda, 0.0), episode.slip, generalized_force);
    return e;
  }

  ContactSample sample(const System& system, const ContactEpisode& episode, double t,
                       const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                       BeamWorkspace& ws, TipKinematics& tip) const override {
    const double lambda =
        acceleration_multiplier(system.beam, system.surface, friction(), t, q, qd, episode.slip, ws, tip).solution.lambda;
    return {lambda, reported_normal_force(friction(), tip, std::min(lambda, 0.0))};
  }

  // 0: λ crosses 0 upward. 1: s_t V_t crosses 0 downward, −s_t V_t upward.
  double root_value(Phase, int k, const System& system, const ContactEpisode& episode, double t,
                    const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                    BeamWorkspace& ws, TipKinematics& tip) const override {
    if (k == 0)
      return acceleration_multiplier(system.beam, system.surface, friction(), t, q, qd, episode.slip, ws, tip)
          .solution.lambda;
    tip_kinematics(system.beam, system.surface, t, q, qd, tip);
    return -(episode.slip * tip.slip_speed);
  }

  std::string failure_message(const ContactEvaluation& e) const override {
    return detail::painleve_message(e.a, e.b, e.c);
  }

  void touch(PhaseControl& control) const override {
    const System& sys = control.system();
    FilamentState& s = control.state();
    tip_kinematics(sys.beam, sys.surface, s.t, s.q, s.qd, control.tip());
    if (control.tip().gap_rate > 0.0)
      impact(control);
    else
      begin_contact(control, "touch without approach speed");
  }

  // V_t = 0 in contact: the velocity has no sign to give; the locked-tip analysis decides (SPEC §4).
  void root(PhaseControl& control, int) const override {
    const System& sys = control.system();
    FilamentState& s = control.state();
    TipKinematics& tip = control.tip();
    sys.beam.evaluate_dynamics(s.q, s.qd, control.workspace());
    tip_kinematics(sys.beam, sys.surface, s.t, s.q, s.qd, tip);
    const SlipDecision d = decide_slip_at_rest(friction(), tip, control.workspace());
    if (d.kind == SlipDecision::Kind::stick)
      return control.fail(FailureKind::stick, detail::stick_message(d, effective_friction(friction(), tip)),
                          Phase::stick);
    if (d.kind == SlipDecision::Kind::separate) return control.end_contact("the tip stopped sliding and lifts off");
    if (d.direction != s.episode.slip)
      control.event(EventKind::slip_reversal, detail::slip_reversal_message(d.direction));
    s.episode.slip = d.direction;
  }

  // The thesis's Appendix B checks the slip direction from V_t before every contact step.
  bool before_step(PhaseControl& control) const override {
    const System& sys = control.system();
    FilamentState& s = control.state();
    TipKinematics& tip = control.tip();
    sys.beam.evaluate_dynamics(s.q, s.qd, control.workspace());
    tip_kinematics(sys.beam, sys.surface, s.t, s.q, s.qd, tip);
    const SlipDecision slip = decide_slip(sys.beam, friction(), tip, control.workspace());
    if (slip.kind == SlipDecision::Kind::stick) {
      control.fail(FailureKind::stick, detail::stick_message(slip, effective_friction(friction(), tip)), Phase::stick);
      return false;
    }
    if (slip.kind == SlipDecision::Kind::slip) {
      if (s.episode.slip != 0.0 && slip.direction != s.episode.slip)
        control.event(EventKind::slip_reversal, detail::slip_reversal_message(slip.direction));
      s.episode.slip = slip.direction;
    }
    return true;
  }

private:
  // Momentum-balance impact at the current state; then a bounce or sustained contact.
  void impact(PhaseControl& control) const {
    if (control.impacts_exhausted()) return;
    const System& sys = control.system();
    FilamentState& s = control.state();
    Eigen::VectorXd& before = control.scratch();
    before = s.qd;
    const ImpactResult r = apply_impact(sys.beam, sys.surface, impact_law(), s.t, s.q, s.qd, control.workspace(),
                                        control.tip(), friction().mu);
    if (r.jammed)
      return control.fail(FailureKind::painleve,
                          "the frictional impact jams: sliding drives the tip into the surface and the normal "
                          "approach never ends (Painlevé's paradox of impacts; impact.friction = \"none\" keeps the "
                          "thesis's frictionless impact)",
                          Phase::free);
    control.impact(before, r);
    if (rebounds(r)) return control.rebound();
    begin_contact(control, r.restitution == 0.0 ? "after a plastic impact" : "after an impact");
  }

  // Sustained contact at the current state (C = Ċ = 0) if the slip analysis allows it.
  void begin_contact(PhaseControl& control, const std::string& why) const {
    const System& sys = control.system();
    FilamentState& s = control.state();
    TipKinematics& tip = control.tip();
    BeamWorkspace& ws = control.workspace();
    sys.beam.evaluate_dynamics(s.q, s.qd, ws);
    tip_kinematics(sys.beam, sys.surface, s.t, s.q, s.qd, tip);
    const SlipDecision slip = decide_slip(sys.beam, friction(), tip, ws);
    if (slip.kind == SlipDecision::Kind::stick)
      return control.fail(FailureKind::stick, detail::stick_message(slip, effective_friction(friction(), tip)),
                          Phase::stick);
    if (slip.kind == SlipDecision::Kind::separate) return control.lift_off(detail::lift_off_message(slip.stick_normal));
    s.episode.slip = slip.direction;
    const AccelerationMultiplier am =
        acceleration_multiplier(sys.beam, sys.surface, friction(), s.t, s.q, s.qd, s.episode.slip, ws, tip);
    if (am.solution.status != MultiplierSolution::Status::unique)
      return control.fail(FailureKind::painleve, detail::painleve_message(am.a, am.b, am.c), Phase::contact);
    if (am.solution.lambda > 0.0 && control.lifts_off_on_positive_multiplier())
      return control.lift_off("λ = " + short_number(am.solution.lambda) + " N > 0 at the touch: no sustained contact");
    s.episode.parameter[0] = am.solution.lambda;
    const ContactLoad load =
        contact_load(friction(), tip, s.qd, std::min(am.solution.lambda, 0.0), s.episode.slip, control.scratch());
    s.phase = Phase::contact;
    control.enter_contact(load, why, false);
  }
};

}  // namespace

std::shared_ptr<const ContactLaw> make_rigid_law(const ContactSettings& settings) {
  return std::make_shared<RigidLaw>(settings);
}

}  // namespace rotbeam
