// The compliant contact law (docs/model.md §11, docs/contact.md): Hertz sphere-on-flat with Hunt–Crossley
// damping, F_n = k δ^{3/2}(1 + c δ̇) from the penetration δ = C > 0 and its rate δ̇ = Ċ, and a
// regularised Coulomb friction F_t = −μ F_n V_t/√(V_t² + v_ε²). Its one contact phase is a smooth
// force integrated by ordinary steps; it ends where the gap opens (C crosses 0 downward). The
// damping c is set at the touch from the approach speed (hertz_damping), so that the contact's
// restitution is the impact law's; the contact's dissipation and stored elastic energy enter the
// ledger. Episode: parameter[0] = c [s/m].
#include "laws.hpp"

#include "rotbeam/detail/diagnostics.hpp"

#include <algorithm>
#include <array>

namespace rotbeam {

namespace {

using detail::short_number;

constexpr std::array<ContactRoot, 1> kCompliantRoots = {{{"δ = 0", true, "the gap opened (δ = 0)"}}};

class HertzLaw final : public ContactLaw {
public:
  HertzLaw(const ContactSettings& settings, double stiffness, double tip_radius)
      : ContactLaw(settings), stiffness_(stiffness), tip_radius_(tip_radius) {}

  const char* name() const override { return "hertz"; }
  bool has_thesis_scheme() const override { return false; }
  PhaseKind kind(Phase) const override { return PhaseKind::force; }
  std::span<const ContactRoot> roots(Phase) const override { return kCompliantRoots; }

  ContactEvaluation evaluate(const System& system, const ContactEpisode& episode, double t,
                             const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                             BeamWorkspace& ws, TipKinematics& tip,
                             Eigen::Ref<Eigen::VectorXd> generalized_force) const override {
    tip_kinematics(system.beam, system.surface, t, q, qd, tip);
    const double fn = hertz_normal_force(stiffness_, episode.parameter[0], tip.gap, tip.gap_rate);
    const double slip = regularized_slip(tip.slip_speed, settings().hertz.friction_regularization_m_s);
    ContactEvaluation e;
    e.load = contact_load(friction(), tip, qd, -fn, slip, generalized_force);
    e.load.rate[LedgerTerm::contact_dissipation] = hertz_dissipation_rate(stiffness_, fn, tip.gap, tip.gap_rate);
    system.beam.evaluate_dynamics(q, qd, ws);
    return e;
  }

  // The gap opens: −C crosses 0 upward.
  ContactSample sample(const System& system, const ContactEpisode& episode, double t,
                       const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                       BeamWorkspace&, TipKinematics& tip) const override {
    tip_kinematics(system.beam, system.surface, t, q, qd, tip);
    return {-tip.gap, hertz_normal_force(stiffness_, episode.parameter[0], tip.gap, tip.gap_rate)};
  }

  // A step inside the contact starts below the surface or on it (the touch): the opening is looked
  // for from there whatever the sign round-off gives the gap.
  ContactSample sample_at_start(const System& system, const ContactEpisode& episode, double t,
                                const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                                BeamWorkspace& ws, TipKinematics& tip) const override {
    const ContactSample s = sample(system, episode, t, q, qd, ws, tip);
    return {std::min(-gap(system.beam, system.surface, t, q), -1e-300), s.normal_force};
  }

  double root_value(Phase, int, const System& system, const ContactEpisode&, double t,
                    const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>&, BeamWorkspace&,
                    TipKinematics&) const override {
    return -gap(system.beam, system.surface, t, q);
  }

  double largest_valid_penetration() const override { return kHertzValidPenetration * tip_radius_; }

  double stored_energy(const System& system, double t, const Eigen::Ref<const Eigen::VectorXd>& q) const override {
    return hertz_elastic_energy(stiffness_, gap(system.beam, system.surface, t, q));
  }

  // A compliant contact begins at C = 0: its damping from the approach speed, then the force phase.
  bool episode_at_touch(const System& system, double t, const Eigen::Ref<const Eigen::VectorXd>& q,
                        const Eigen::Ref<const Eigen::VectorXd>& qd, ContactEpisode& episode,
                        TipKinematics& tip) const override {
    tip_kinematics(system.beam, system.surface, t, q, qd, tip);
    const double full = std::hypot(tip.VX - tip.surface_vx, tip.VY - tip.surface_vy);
    episode.slip = regularized_slip(tip.slip_speed, settings().hertz.friction_regularization_m_s);
    episode.parameter[0] = hertz_damping(settings(), tip.gap_rate, full);
    return true;
  }

  void touch(PhaseControl& control) const override {
    const System& sys = control.system();
    FilamentState& s = control.state();
    TipKinematics& tip = control.tip();
    episode_at_touch(sys, s.t, s.q, s.qd, s.episode, tip);
    const double v0 = tip.gap_rate;
    const double damping = s.episode.parameter[0];
    ContactLoad zero;
    zero.slip = s.episode.slip;
    s.phase = Phase::contact;
    control.enter_contact(zero,
                          "compliant contact: approach speed " + short_number(v0) + " m/s, Hunt–Crossley c = " +
                              short_number(damping) + " s/m",
                          true);
  }

private:
  double stiffness_;   // k [N/m^{3/2}]
  double tip_radius_;  // R [m]
};

}  // namespace

std::shared_ptr<const ContactLaw> make_hertz_law(const ContactSettings& settings, double stiffness, double tip_radius) {
  return std::make_shared<HertzLaw>(settings, stiffness, tip_radius);
}

}  // namespace rotbeam
