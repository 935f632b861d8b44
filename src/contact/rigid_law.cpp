// The rigid contact law (docs/model.md §4, §5; thesis §4.4–4.5): a unilateral constraint C = 0 whose multiplier
// λ ≤ 0 is the normal force, Coulomb friction F_t = −μ_eff|λ| s_t, and momentum-balance impacts with
// a coefficient of restitution. Two contact phases (docs/contact.md, "Stick"):
//   contact (sliding, s_t = ±1), a constraint: roots λ = 0 (separation), V_t = 0 (the slip stops:
//           stick, lift-off or reversal, decided by the locked-tip analysis) and a − b = 0 (a dynamic
//           jam: the tangential impact);
//   stick   (V_t = 0 held), two constraints whose multipliers are λ and the tangential force F_t:
//           roots λ = 0 (separation) and |F_t| = μ_eff|λ| (the tip slides against F_t).
// A stepper that does not hold a stick (StepperTraits::holds_stick: the thesis scheme) stops there
// with a diagnostic; a λ + b|λ| = c with no or two admissible solutions (Painlevé's paradox) is
// resolved by the rules of docs/contact.md or stops the pass with a message that says why.
// Episode: parameter[0] = λ0, the acceleration-level multiplier at the contact's start (the thesis
// scheme's first prediction); parameter[kStuck] = 1 while the tip sticks.
#include "laws.hpp"

#include "rotbeam/impact.hpp"
#include "rotbeam/rigid_contact.hpp"
#include "rotbeam/detail/diagnostics.hpp"

#include <algorithm>
#include <array>

namespace rotbeam {

namespace {

using detail::short_number;

constexpr std::array<ContactRoot, 3> kSlidingRoots = {{
    {"λ = 0", true, "λ reached 0"},
    {"V_t = 0", false, ""},
    {"a − b = 0", false, ""},
}};
constexpr int kJamRoot = 2;  // the sliding phase's root a − b = 0
constexpr std::array<ContactRoot, 2> kStickRoots = {{
    {"λ = 0", true, "λ reached 0 while the tip stuck"},
    {"|F_t| = μ F_n", false, ""},
}};
constexpr std::size_t kStuck = 1;  // the episode's parameter that marks a stick (evaluate has no phase)

bool stuck(const ContactEpisode& episode) { return episode.parameter[kStuck] != 0.0; }

class RigidLaw final : public ContactLaw {
public:
  using ContactLaw::ContactLaw;

  const char* name() const override { return "rigid"; }
  bool has_thesis_scheme() const override { return true; }
  PhaseKind kind(Phase phase) const override {
    return phase == Phase::stick ? PhaseKind::locked : PhaseKind::constraint;
  }
  std::span<const ContactRoot> roots(Phase phase) const override {
    return phase == Phase::stick ? std::span<const ContactRoot>(kStickRoots) : std::span<const ContactRoot>(kSlidingRoots);
  }

  ContactEvaluation evaluate(const System& system, const ContactEpisode& episode, double t,
                             const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                             BeamWorkspace& ws, TipKinematics& tip,
                             Eigen::Ref<Eigen::VectorXd> generalized_force) const override {
    if (stuck(episode)) {
      // The tip held: λ and F_t from the two constraints. Past the phase's roots (a trial step beyond
      // λ = 0 or |F_t| = μ_eff|λ|, which the stepper cuts there) the force is kept admissible: no pull,
      // and F_t within the cone.
      const LockedTipForces f = locked(system, t, q, qd, ws, tip);
      const double lambda = std::min(f.lambda, 0.0);
      const double cone = effective_friction(friction(), tip) * std::abs(lambda);
      ContactEvaluation e;
      e.load = contact_load_with_friction(friction(), tip, qd, lambda, std::clamp(f.tangential, -cone, cone), 0.0,
                                          generalized_force);
      return e;
    }
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
        stuck(episode)
            ? locked(system, t, q, qd, ws, tip).lambda
            : acceleration_multiplier(system.beam, system.surface, friction(), t, q, qd, episode.slip, ws, tip)
                  .solution.lambda;
    return {lambda, reported_normal_force(friction(), tip, std::min(lambda, 0.0))};
  }

  // Sliding: 0, λ crosses 0 upward; 1, s_t V_t crosses 0 downward, −s_t V_t upward; 2, (a − b)/a
  // crosses 0 downward, −(a − b)/a upward (a > 0: a dynamic jam).
  // Stick: 0, λ crosses 0 upward; 1, |F_t| − μ_eff|λ| crosses 0 upward.
  double root_value(Phase phase, int k, const System& system, const ContactEpisode& episode, double t,
                    const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                    BeamWorkspace& ws, TipKinematics& tip) const override {
    if (phase == Phase::stick) {
      const LockedTipForces f = locked(system, t, q, qd, ws, tip);
      if (k == 0) return f.lambda;
      return std::abs(f.tangential) - effective_friction(friction(), tip) * std::abs(std::min(f.lambda, 0.0));
    }
    if (k == 0)
      return acceleration_multiplier(system.beam, system.surface, friction(), t, q, qd, episode.slip, ws, tip)
          .solution.lambda;
    if (k == kJamRoot) {
      const AccelerationMultiplier am =
          acceleration_multiplier(system.beam, system.surface, friction(), t, q, qd, episode.slip, ws, tip);
      return -(am.a - am.b) / am.a;
    }
    tip_kinematics(system.beam, system.surface, t, q, qd, tip);
    return -(episode.slip * tip.slip_speed);
  }

  std::string failure_message(const ContactEvaluation& e) const override {
    return detail::painleve_unresolved_message(
        e.a, e.b, e.c, "a − b turned negative while the tip slid (the contact force grows without bound toward it)");
  }

  ImpactResult momentum_jump(const System& system, double t, const Eigen::Ref<const Eigen::VectorXd>& q,
                             Eigen::Ref<Eigen::VectorXd> qd, BeamWorkspace& ws, TipKinematics& tip) const override {
    return apply_impact(system.beam, system.surface, impact_law(), t, q, qd, ws, tip, friction().mu);
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

  // Sliding, V_t = 0: the velocity has no sign to give; the locked-tip analysis decides (docs/contact.md).
  // Sliding, a − b = 0: a dynamic jam; the tangential impact stops the slip (docs/contact.md).
  // Stick, |F_t| = μ_eff|λ|: the tip slides against F_t.
  void root(PhaseControl& control, int k) const override {
    const System& sys = control.system();
    FilamentState& s = control.state();
    if (s.phase == Phase::contact && k == kJamRoot)
      return tangential_impact(control, "a − b reached 0 while the tip slid (a dynamic jam)");
    TipKinematics& tip = control.tip();
    sys.beam.evaluate_dynamics(s.q, s.qd, control.workspace());
    tip_kinematics(sys.beam, sys.surface, s.t, s.q, s.qd, tip);
    const SlipDecision d = decide_slip_at_rest(friction(), tip, control.workspace());
    if (s.phase == Phase::stick) return end_stick(control, d);
    if (d.kind == SlipDecision::Kind::stick) return stick(control, d);
    if (d.kind == SlipDecision::Kind::separate) return control.end_contact("the tip stopped sliding and lifts off");
    if (d.direction != s.episode.slip)
      control.event(EventKind::slip_reversal, detail::slip_reversal_message(d.direction));
    s.episode.slip = d.direction;
    if (!control.holds_stick()) return;
    slides_from_rest(control, d.direction,
                     "the slip stopped with more than μF_n needed to hold the tip, and sliding on drives it into the "
                     "surface");
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
  // The locked tip's forces at (t, q, q̇) (evaluates the dynamics and the tip's kinematics).
  LockedTipForces locked(const System& system, double t, const Eigen::Ref<const Eigen::VectorXd>& q,
                         const Eigen::Ref<const Eigen::VectorXd>& qd, BeamWorkspace& ws, TipKinematics& tip) const {
    system.beam.evaluate_dynamics(q, qd, ws);
    tip_kinematics(system.beam, system.surface, t, q, qd, tip);
    return locked_tip_forces(tip, ws);
  }

  // A sliding tip stops sliding and sticks (V_t = 0 located, the tangential force needed inside the
  // cone), or stops the pass where the stepper holds no stick.
  void stick(PhaseControl& control, const SlipDecision& d) const {
    const double mu = effective_friction(friction(), control.tip());
    if (!control.holds_stick()) return control.fail(FailureKind::stick, detail::stick_message(d, mu), Phase::stick);
    FilamentState& s = control.state();
    s.phase = Phase::stick;
    s.episode.parameter[kStuck] = 1.0;
    s.episode.slip = 0.0;
    control.event(EventKind::stick_start, detail::stick_start_message(d, mu));
  }

  // The tangential force the stuck tip needs reached the cone: it slides against that force (the
  // locked-tip analysis gives the direction; at the root itself it may still call it a stick by
  // round-off, and then the direction is the one against F_t), or leaves where λ turned positive.
  void end_stick(PhaseControl& control, const SlipDecision& d) const {
    FilamentState& s = control.state();
    if (d.kind == SlipDecision::Kind::separate) return control.end_contact("the stuck tip lifts off (λ > 0)");
    const double direction = d.kind == SlipDecision::Kind::slip ? d.direction : (d.stick_tangential > 0 ? -1.0 : 1.0);
    if (!slides_from_rest(control, direction,
                          "the stuck tip needs more than μF_n to stay, and sliding against that force drives it into "
                          "the surface"))
      return;
    s.phase = Phase::contact;
    s.episode.parameter[kStuck] = 0.0;
    s.episode.slip = direction;
    control.event(EventKind::stick_end, detail::stick_end_message(d.stick_tangential, direction));
  }

  // Whether the tip at rest tangentially (V_t = 0) can slide in `direction`: a Painlevé point there
  // ends the contact (two admissible multipliers: the separation) or stops the pass (none: `why`,
  // and no impulse can stop a slip that is not there); false in both cases.
  bool slides_from_rest(PhaseControl& control, double direction, const std::string& why) const {
    const System& sys = control.system();
    FilamentState& s = control.state();
    const AccelerationMultiplier am = acceleration_multiplier(sys.beam, sys.surface, friction(), s.t, s.q, s.qd,
                                                              direction, control.workspace(), control.tip());
    if (am.solution.status == MultiplierSolution::Status::unique) return true;
    if (am.solution.status == MultiplierSolution::Status::non_unique)
      control.end_contact(two_solutions_rule(am));
    else
      control.fail(FailureKind::painleve,
                   detail::painleve_unresolved_message(am.a, am.b, am.c,
                                                       why + "; with V_t = 0 no impulse can stop a slip"),
                   Phase::contact);
    return false;
  }

  // Painlevé's paradox with two admissible multipliers (a − b < 0, c > 0: a contact force and a
  // separation both consistent): the rule takes the separation (docs/contact.md).
  static std::string two_solutions_rule(const AccelerationMultiplier& am) {
    return detail::painleve_message(am.a, am.b, am.c) + ": of the two, the rule takes the separation (λ = " +
           short_number(am.c / am.a) + " N > 0): the tip leaves";
  }

  // The tangential impact at a Painlevé point with no admissible force (impact.hpp), then the contact
  // starts again from the state after it (a stick, a slip the other way, or a lift-off).
  void tangential_impact(PhaseControl& control, const std::string& why) const {
    if (control.impacts_exhausted()) return;
    const System& sys = control.system();
    FilamentState& s = control.state();
    Eigen::VectorXd& before = control.scratch();
    before = s.qd;
    const ImpactResult r = apply_tangential_impact(sys.beam, sys.surface, s.t, s.q, s.qd, control.workspace(),
                                                   control.tip(), effective_friction(friction(), control.tip()));
    if (r.jammed) {
      const AccelerationMultiplier am = acceleration_multiplier(sys.beam, sys.surface, friction(), s.t, s.q, s.qd,
                                                                s.episode.slip, control.workspace(), control.tip());
      return control.fail(FailureKind::painleve,
                          detail::painleve_unresolved_message(
                              am.a, am.b, am.c,
                              "sliding drives the tip into the surface and friction cannot stop the slip "
                              "(|a_nt| > μ a_tt), so no tangential impact resolves it"),
                          Phase::contact);
    }
    control.impact(before, r);
    begin_contact(control, why + ", then a tangential impact", true);
  }

  // Momentum-balance impact at the current state; then a bounce or sustained contact.
  void impact(PhaseControl& control) const {
    if (control.impacts_exhausted()) return;
    const System& sys = control.system();
    FilamentState& s = control.state();
    Eigen::VectorXd& before = control.scratch();
    before = s.qd;
    const ImpactResult r = momentum_jump(sys, s.t, s.q, s.qd, control.workspace(), control.tip());
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
  // Sustained contact at the current state; `resolved`: a tangential impact has just been applied here.
  void begin_contact(PhaseControl& control, const std::string& why, bool resolved = false) const {
    const System& sys = control.system();
    FilamentState& s = control.state();
    TipKinematics& tip = control.tip();
    BeamWorkspace& ws = control.workspace();
    sys.beam.evaluate_dynamics(s.q, s.qd, ws);
    tip_kinematics(sys.beam, sys.surface, s.t, s.q, s.qd, tip);
    const SlipDecision slip = decide_slip(sys.beam, friction(), tip, ws);
    if (slip.kind == SlipDecision::Kind::stick && control.holds_stick()) {
      s.episode.parameter[0] = slip.stick_normal;
      s.episode.parameter[kStuck] = 1.0;
      s.episode.slip = 0.0;
      s.phase = Phase::stick;
      const ContactLoad load = contact_load_with_friction(friction(), tip, s.qd, std::min(slip.stick_normal, 0.0),
                                                          slip.stick_tangential, 0.0, control.scratch());
      control.enter_contact(load, why, false);
      control.event(EventKind::stick_start, detail::stick_start_message(slip, effective_friction(friction(), tip)));
      return;
    }
    if (slip.kind == SlipDecision::Kind::stick)
      return control.fail(FailureKind::stick, detail::stick_message(slip, effective_friction(friction(), tip)),
                          Phase::stick);
    if (slip.kind == SlipDecision::Kind::separate) return control.lift_off(detail::lift_off_message(slip.stick_normal));
    s.episode.slip = slip.direction;
    const AccelerationMultiplier am =
        acceleration_multiplier(sys.beam, sys.surface, friction(), s.t, s.q, s.qd, s.episode.slip, ws, tip);
    if (am.solution.status != MultiplierSolution::Status::unique) {
      if (!control.holds_stick())
        return control.fail(FailureKind::painleve, detail::painleve_message(am.a, am.b, am.c), Phase::contact);
      if (am.solution.status == MultiplierSolution::Status::non_unique)
        return control.lift_off(two_solutions_rule(am));
      if (resolved)
        return control.fail(FailureKind::painleve,
                            detail::painleve_unresolved_message(am.a, am.b, am.c,
                                                                "after a tangential impact the tip still slides into "
                                                                "the surface"),
                            Phase::contact);
      return tangential_impact(control, why);
    }
    if (am.solution.lambda > 0.0 && control.lifts_off_on_positive_multiplier())
      return control.lift_off("λ = " + short_number(am.solution.lambda) + " N > 0 at the touch: no sustained contact");
    s.episode.parameter[0] = am.solution.lambda;
    s.episode.parameter[kStuck] = 0.0;
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
