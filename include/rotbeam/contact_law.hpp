// The contact-law seam (docs/model.md §4, §5, §11): what the surface pushes on the tip with, and what happens
// when the tip touches it. A contact law is an object (ContactLaw) made once per case by
// make_contact_law (contact_laws.hpp) from the case's ContactSettings, immutable and shared by any
// number of passes and threads. It
//   - names the phases its contacts pass through, how a stepper integrates each (a constraint
//     projected at every step, or a smooth force) and the root functions each needs;
//   - computes the contact's load at a state: the forces on the tip, the generalised force Q on the
//     modal coordinates and the rates of the ledger's terms (ledger.hpp), its dissipation included;
//   - decides the transitions (a touch, a root of its phase) through PhaseControl, which the pass
//     driver implements: impacts, contact starts and ends, lift-offs, failures;
//   - reports the energy it stores (a compliant contact's elastic energy).
// The driver, the steppers and the recorder never ask which law it is.
//
// Two laws today: the thesis's rigid unilateral constraint whose multiplier λ is the normal force
// (rigid_contact.hpp), Coulomb friction and momentum-balance impacts (impact.hpp); and a compliant
// law: Hertz sphere-on-flat with Hunt–Crossley damping, λ = −F_n from the penetration δ = C > 0 and
// its rate δ̇ = Ċ, with a regularised Coulomb friction. Both compute their load through contact_load.
//
// Force conventions: because ∂C/∂R_tip is the unit normal n, λ ≤ 0 is the physical normal force:
// F_n = −λ [N]; friction on the tip acts along the tangent t, F_t = −μ F_n s_t with s_t = sign(V_t).
// With compat.thesis_forces the thesis's convention is used instead: F_n = |λ|·|∇C| and
// μ_eff = μ|∇C| (|∇C| being the norm of the modal-coordinate gradient, docs/model.md §4).
#pragma once

#include "rotbeam/impact.hpp"
#include "rotbeam/kinematics.hpp"
#include "rotbeam/ledger.hpp"
#include "rotbeam/outcome.hpp"
#include "rotbeam/state.hpp"

#include <cmath>
#include <span>
#include <string>

namespace rotbeam {

struct FrictionModel {
  double mu = 0.4;             // μ (surface.friction)
  bool thesis_forces = false;  // compat.thesis_forces
};

enum class ContactModel { rigid, hertz };

/// Hertz sphere-on-flat contact of the filament's rounded tip with the surface (docs/model.md §11):
/// F_n = k δ^{3/2}(1 + c δ̇), k = (4/3) E* √R, 1/E* = (1 − ν_w²)/E_w + (1 − ν_s²)/E_s.
struct HertzContact {
  double tip_radius_m = 0.0;                  // R (contact.tip_radius_m); 0: the wire's radius D/2
  double surface_youngs_modulus_pa = 2.0e11;  // E_s (surface.youngs_modulus_pa)
  double surface_poisson = 0.3;               // ν_s (surface.poisson)
  double wire_poisson = 0.3;                  // ν_w (beam.poisson)
  double friction_regularization_m_s = 1e-3;  // v_ε of regularized_slip (contact.friction_regularization_m_s)
  double stiffness_factor = 1.0;              // multiplies E* (contact.stiffness_factor): the rigid limit's studies
};

/// What a case says of its contact: friction, the impact law, and the normal law (rigid or Hertz) with
/// its parameters. make_contact_law (contact_laws.hpp) makes the law object from it.
struct ContactSettings {
  FrictionModel friction;
  ImpactLaw impact;
  ContactModel model = ContactModel::rigid;  // contact.model
  HertzContact hertz;                        // used when model == hertz
};

/// "rigid", "hertz": contact.model's values.
const char* contact_model_name(ContactModel m);

/// The tip radius R [m]: hertz.tip_radius_m, or the wire's radius D/2 when that is 0.
double hertz_tip_radius(const HertzContact& hertz, double wire_diameter_m);

/// k = (4/3) E* √R × stiffness_factor [N/m^{3/2}] for a wire of modulus `wire_youngs_pa` [Pa] and diameter
/// `wire_diameter_m` [m] (R = hertz.tip_radius_m, or D/2 when that is 0). docs/model.md §11.
double hertz_stiffness(const HertzContact& hertz, double wire_youngs_pa, double wire_diameter_m);

/// The Hunt–Crossley product x = c·v0 that gives the restitution e ∈ (0, 1] to a single mass m
/// striking at v0 with m δ̈ = −k δ^{3/2}(1 + c δ̇). Its phase plane integrates in closed form,
/// m[(u − v0)/c − ln((1 + cu)/(1 + cv0))/c²] = −(2/5) k δ^{5/2} (u = δ̇), so the exit speed u = −e v0 at
/// δ = 0 depends on x alone: ln((1 + x)/(1 − e x)) = (1 + e) x, solved on (0, 1/e) by TOMS 748 to
/// double precision (exact for every e, where Hunt and Crossley's c = 3(1 − e)/(2v0) holds only
/// near e = 1). 0 for e = 1. As e → 0, x → 1/e with 1 − e x ≈ (1 + 1/e) e^{−(1 + e)/e}: below
/// e = kMinCompliantRestitution that gap is under 1e-8 and the exit is lost to rounding, so smaller
/// e throw std::domain_error.
double hunt_crossley_product(double e);

/// Hertz's theory holds for a contact radius a = √(Rδ) small against the tip radius R: up to
/// δ = kHertzValidPenetration·R (a/R ≈ 0.3).
inline constexpr double kHertzValidPenetration = 0.1;

/// The smallest restitution the compliant law reproduces (hunt_crossley_product).
inline constexpr double kMinCompliantRestitution = 0.05;
/// The approach speed [m/s] below which the compliant law's damping is that of this speed.
inline constexpr double kGrazingSpeedFloor = 1e-3;

/// The damping c [s/m] of a compliant contact that starts with normal approach speed v0 = Ċ [m/s]
/// and full tip speed `full_speed` [m/s]: e from law.impact (a constant, or Yigit's e(v) capped,
/// without the rigid law's plastic floor impact.plastic_below_m_s, and at least
/// kMinCompliantRestitution), c = hunt_crossley_product(e) / max(v0, kGrazingSpeedFloor). The speed
/// floor bounds c for grazing touches (their restitution is then above e). docs/contact.md.
double hertz_damping(const ContactSettings& law, double v0, double full_speed);

/// The Hertz normal force F_n = max(0, k δ^{3/2}(1 + c δ̇)) [N] for the stiffness k [N/m^{3/2}] at
/// penetration δ [m] (0 for δ ≤ 0) and its rate δ̇ [m/s]: the force never pulls (clipped at 0 where the
/// damping term would make it negative, on a fast exit).
double hertz_normal_force(double stiffness, double damping, double delta, double delta_rate);

/// The elastic energy stored in the Hertz contact of stiffness k, (2/5) k δ^{5/2} [J] (0 for δ ≤ 0).
double hertz_elastic_energy(double stiffness, double delta);

/// The rate at which the compliant contact dissipates energy [W] (≤ 0, signed as energy given to
/// the filament): −(F_n − k δ^{3/2}) δ̇, i.e. −k c δ^{3/2} δ̇² unclipped and k δ^{3/2} δ̇ (δ̇ < 0) clipped.
double hertz_dissipation_rate(double stiffness, double normal_force, double delta, double delta_rate);

/// The regularised slip direction s = V_t / √(V_t² + v_ε²) ∈ (−1, 1) of the compliant law's Coulomb
/// friction F_t = −μ F_n s: Coulomb's law to a relative 1/2 (v_ε/V_t)² when sliding, a steep viscous
/// law (slope μ F_n / v_ε) through V_t = 0, so stick is a micro-slip below v_ε.
inline double regularized_slip(double slip_speed, double v_eps) {
  return slip_speed / std::sqrt(slip_speed * slip_speed + v_eps * v_eps);
}

/// The contact force state at a point of a pass (all zero in free flight).
struct ContactLoad {
  double lambda = 0;          // multiplier [N] (≤ 0 in contact)
  double normal_force = 0;    // reported F_n [N]
  double friction_force = 0;  // F_t on the tip along the tangent [N]
  double force_x = 0, force_y = 0;  // the surface's force on the tip, global frame [N]
  double slip = 0;            // slip direction s_t used
  // The rates of the ledger's terms (ledger.hpp) per second: contact_work q̇ᵀQ [W] (the rate of change
  // of the Jacobi integral), friction_work F_t V_t [W] (≤ 0), surface_work F_t (V_s·t) [W] (a moving
  // surface's power through friction), normal_impulse F_n [N], tangential_impulse F_t [N],
  // contact_moment X_t F_Y − Y_t F_X [N m], frictional_heat −F_t V_t = |F_t||V_t| [W], sliding_load F_n|V_t|
  // [N m/s], and a compliant contact's contact_dissipation [W].
  LedgerValues rate;
};

/// μ_eff, the friction coefficient applied to |λ| (μ, or μ|∇C| under thesis_forces).
double effective_friction(const FrictionModel& friction, const TipKinematics& tip);

/// Reported normal force for a multiplier λ: −λ (physical) or |λ|·|∇C| (thesis_forces) [N].
double reported_normal_force(const FrictionModel& friction, const TipKinematics& tip, double lambda);

/// Generalised friction direction per unit |λ|: Q* = −μ_eff s_t ∂V_t/∂q̇ into `out` (size n),
/// so that friction's generalised force is |λ| Q* (the b of a λ + b|λ| = c).
void friction_direction(const FrictionModel& friction, const TipKinematics& tip, double slip_direction,
                        Eigen::Ref<Eigen::VectorXd> out);

/// The contact load for multiplier λ and slip direction s_t at the state of `tip` (with velocity
/// q̇): Q = λ∇C + F_t ∂V_t/∂q̇ into `generalized_force` (size n), and the forces, the rates and the
/// force on the tip. Allocates nothing. λ = 0 gives the zero load (with s_t kept).
ContactLoad contact_load(const FrictionModel& friction, const TipKinematics& tip,
                         const Eigen::Ref<const Eigen::VectorXd>& qd, double lambda, double slip_direction,
                         Eigen::Ref<Eigen::VectorXd> generalized_force);

/// The same for a tangential force F_t [N] on the tip along the tangent given directly (a stuck tip's,
/// solved with λ from the two constraints) instead of Coulomb's −μ_eff|λ| s_t. λ = 0 and F_t = 0 give
/// the zero load.
ContactLoad contact_load_with_friction(const FrictionModel& friction, const TipKinematics& tip,
                                       const Eigen::Ref<const Eigen::VectorXd>& qd, double lambda,
                                       double friction_force, double slip_direction,
                                       Eigen::Ref<Eigen::VectorXd> generalized_force);

// ---- the law as an object ------------------------------------------------------------------------

/// How a stepper integrates a contact phase.
enum class PhaseKind {
  constraint,  // a constraint holds (C = 0): q and q̇ are projected onto it (mass-weighted) before and
               // after every step, and every step starts the error control afresh
  force,       // a smooth force of the state: ordinary error-controlled steps
  locked,      // two constraints hold (C = 0 and V_t = 0: the tip sticks): q is projected onto C = 0 and
               // q̇ onto Ċ = 0, V_t = 0 before and after every step, which starts the error control afresh
};

/// A root function of a contact phase. Every root function is oriented so that its event is a
/// crossing from below zero to zero or above; a step looks for it when its value at the step's start
/// (sample_at_start for the first) is below zero.
struct ContactRoot {
  const char* name;          // in words, for messages ("λ = 0")
  bool ends_contact;         // the phase ends there and the tip is free (a separation)
  const char* end_detail;    // the contact_end event's detail where it ends the contact
};

/// What a law computes at a state of its contact phase.
struct ContactEvaluation {
  ContactLoad load;            // forces and the ledger's rates
  bool admissible = true;      // false: no force satisfies the law here (Painlevé's paradox)
  double a = 0, b = 0, c = 0;  // a rigid contact's a λ + b|λ| = c, for the message of a failure
};

/// The first root function's value and the reported normal force at a state: what a stepper samples
/// on its dense output to find the phase's end and the step's largest force.
struct ContactSample {
  double root = 0;
  double normal_force = 0;  // [N]
};

/// What the pass driver does for a law at a transition (a touch, a root of a contact phase): the
/// law decides, the driver carries out and records.
class PhaseControl {
public:
  virtual ~PhaseControl() = default;
  virtual const System& system() const = 0;
  /// The filament now (its phase and episode are the law's to set before enter_contact).
  virtual FilamentState& state() = 0;
  /// Scratch: a workspace of the beam model, the tip's kinematics, a vector of size n.
  virtual BeamWorkspace& workspace() = 0;
  virtual TipKinematics& tip() = 0;
  virtual Eigen::VectorXd& scratch() = 0;
  /// Whether the stepper integrates a stick phase (a PhaseKind::locked phase with its roots located);
  /// false: a stick stops the pass with its diagnostic (the thesis scheme).
  virtual bool holds_stick() const = 0;
  /// The stepper's choice at a contact start whose acceleration-level multiplier is positive: true,
  /// the tip lifts off at once; false, its own contact step decides (the thesis's corrector).
  virtual bool lifts_off_on_positive_multiplier() const = 0;
  /// True (the pass then ends, with an `impacts` failure) when no further impact may happen.
  virtual bool impacts_exhausted() = 0;
  /// An impact happened at the current state: q̇ jumped from qd_before to state().qd.
  virtual void impact(const Eigen::VectorXd& qd_before, const ImpactResult& result) = 0;
  /// Free flight after an impact that bounces.
  virtual void rebound() = 0;
  /// The tip enters state().phase (a contact phase) with the episode the law set and the load at
  /// its start; `first_touch`: a touch without an impact (a compliant contact), which the summary's
  /// first touch angle counts.
  virtual void enter_contact(const ContactLoad& load, const std::string& why, bool first_touch) = 0;
  /// The tip leaves the surface at a touch (a lift_off event; free flight).
  virtual void lift_off(const std::string& why) = 0;
  /// A contact episode ends (a contact_end event; free flight).
  virtual void end_contact(const std::string& why) = 0;
  virtual void event(EventKind kind, const std::string& detail) = 0;
  /// The pass stops on a numerical failure in `phase` at the current time.
  virtual void fail(FailureKind kind, const std::string& message, Phase phase) = 0;
};

class ContactLaw {
public:
  explicit ContactLaw(const ContactSettings& settings) : settings_(settings) {}
  virtual ~ContactLaw() = default;
  ContactLaw(const ContactLaw&) = delete;
  ContactLaw& operator=(const ContactLaw&) = delete;

  const ContactSettings& settings() const { return settings_; }
  const FrictionModel& friction() const { return settings_.friction; }
  const ImpactLaw& impact_law() const { return settings_.impact; }
  /// contact.model's value.
  virtual const char* name() const = 0;
  /// Whether the thesis's fixed-step scheme (simulation.scheme = "thesis") integrates this law.
  virtual bool has_thesis_scheme() const = 0;

  // ---- the dynamics of a contact phase (the steppers) -------------------------------------------
  virtual PhaseKind kind(Phase phase) const = 0;
  /// The phase's root functions; the first is sampled with the normal force (sample).
  virtual std::span<const ContactRoot> roots(Phase phase) const = 0;
  /// The load at (t, q, q̇) of `episode`, with Q into `generalized_force` (size n). Evaluates the beam's
  /// dynamics (ws.mass, ws.mass_llt, ws.psi at q, q̇) and the tip's kinematics into `tip`, so that
  /// q̈ = M⁻¹(Q − Ψ) follows. Allocates nothing.
  virtual ContactEvaluation evaluate(const System& system, const ContactEpisode& episode, double t,
                                     const Eigen::Ref<const Eigen::VectorXd>& q,
                                     const Eigen::Ref<const Eigen::VectorXd>& qd, BeamWorkspace& ws, TipKinematics& tip,
                                     Eigen::Ref<Eigen::VectorXd> generalized_force) const = 0;
  /// The first root function and the normal force at (t, q, q̇), sampled inside a step (overwrites ws
  /// and tip).
  virtual ContactSample sample(const System& system, const ContactEpisode& episode, double t,
                               const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                               BeamWorkspace& ws, TipKinematics& tip) const = 0;
  /// The same at a step's start, where the first root is looked for in the step when its value is
  /// below zero (sample by default).
  virtual ContactSample sample_at_start(const System& system, const ContactEpisode& episode, double t,
                                        const Eigen::Ref<const Eigen::VectorXd>& q,
                                        const Eigen::Ref<const Eigen::VectorXd>& qd, BeamWorkspace& ws,
                                        TipKinematics& tip) const;
  /// Root function k of `phase` at (t, q, q̇), as a root finder refines it (overwrites ws and tip).
  virtual double root_value(Phase phase, int k, const System& system, const ContactEpisode& episode, double t,
                            const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                            BeamWorkspace& ws, TipKinematics& tip) const = 0;
  /// The energy the contact stores at (t, q), part of the ledger's energy [J] (0 for a rigid contact).
  virtual double stored_energy(const System& system, double t, const Eigen::Ref<const Eigen::VectorXd>& q) const;
  /// The penetration δ [m] up to which the law's theory holds; 0 for a law without penetration (the
  /// rigid law). The pass warns and marks its validity "edge" where δ goes beyond it.
  virtual double largest_valid_penetration() const { return 0.0; }
  /// The impact the law applies at a touch with approach speed (Ċ⁻ > 0): q̇⁻ → q̇⁺ in place at (t, q).
  /// The variational equations differentiate it (tangent.hpp). Throws std::logic_error for a law
  /// without impacts (the default), std::domain_error where the tip does not approach.
  virtual ImpactResult momentum_jump(const System& system, double t, const Eigen::Ref<const Eigen::VectorXd>& q,
                                     Eigen::Ref<Eigen::VectorXd> qd, BeamWorkspace& ws, TipKinematics& tip) const;
  /// The episode's parameters a touch at (t, q, q̇) sets as continuous functions of the state (the
  /// compliant law's damping from the approach speed) into `episode`; false (the default) where the
  /// law's episodes carry nothing the state sets continuously. The variational equations
  /// differentiate it (tangent.hpp). Overwrites tip.
  virtual bool episode_at_touch(const System& system, double t, const Eigen::Ref<const Eigen::VectorXd>& q,
                                const Eigen::Ref<const Eigen::VectorXd>& qd, ContactEpisode& episode,
                                TipKinematics& tip) const {
    (void)system, (void)t, (void)q, (void)qd, (void)episode, (void)tip;
    return false;
  }
  /// The failure an inadmissible evaluation means, and its message.
  virtual FailureKind failure_kind(const ContactEvaluation& e) const;
  virtual std::string failure_message(const ContactEvaluation& e) const;

  // ---- the transitions (the pass driver) --------------------------------------------------------
  /// Free flight reached the surface (C = 0, or a rigid start's first contact).
  virtual void touch(PhaseControl& control) const = 0;
  /// Root k of the current contact phase was crossed (one that does not end the contact).
  virtual void root(PhaseControl& control, int k) const;
  /// Before every contact step of a scheme that locates no root but the contact's end
  /// (StepperTraits::locates_contact_roots false); false when the pass stopped.
  virtual bool before_step(PhaseControl& control) const;

private:
  ContactSettings settings_;
};

}  // namespace rotbeam
