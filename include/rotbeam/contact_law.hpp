// The contact-law seam (SPEC §4, §5): what the surface pushes on the tip with, as forces on the
// tip and as the generalised force on the modal coordinates, computed in one place
// (contact_load) for every scheme and output. Two laws: the thesis's rigid unilateral constraint
// whose multiplier λ is the normal force (rigid_contact.hpp), Coulomb friction, and
// momentum-balance impacts with a restitution law (impact.hpp); and a compliant law (SPEC §11,
// "Compliant contact"): Hertz sphere-on-flat with Hunt–Crossley damping, whose λ = −F_n comes from
// the penetration δ = C > 0 and its rate δ̇ = Ċ (hertz_normal_force) and goes through the same
// contact_load, with a regularised Coulomb friction (regularized_slip).
//
// Force conventions: because ∂C/∂R_tip is the unit normal n, λ ≤ 0 is the physical normal force:
// F_n = −λ [N]; friction on the tip acts along the tangent t, F_t = −μ F_n s_t with s_t = sign(V_t).
// With compat.thesis_forces the thesis's convention is used instead: F_n = |λ|·|∇C| and
// μ_eff = μ|∇C| (|∇C| being the norm of the modal-coordinate gradient, SPEC §4).
#pragma once

#include "rotbeam/impact.hpp"
#include "rotbeam/kinematics.hpp"

#include <cmath>

namespace rotbeam {

struct FrictionModel {
  double mu = 0.4;             // μ (surface.friction)
  bool thesis_forces = false;  // compat.thesis_forces
};

enum class ContactModel { rigid, hertz };

/// Hertz sphere-on-flat contact of the filament's rounded tip with the surface (SPEC §11):
/// F_n = k δ^{3/2}(1 + c δ̇), k = (4/3) E* √R, 1/E* = (1 − ν_w²)/E_w + (1 − ν_s²)/E_s.
struct HertzContact {
  double tip_radius_m = 0.0;                  // R (contact.tip_radius_m); 0: the wire's radius D/2
  double surface_youngs_modulus_pa = 2.0e11;  // E_s (surface.youngs_modulus_pa)
  double surface_poisson = 0.3;               // ν_s (surface.poisson)
  double wire_poisson = 0.3;                  // ν_w (beam.poisson)
  double friction_regularization_m_s = 1e-3;  // v_ε of regularized_slip (contact.friction_regularization_m_s)
  double stiffness_factor = 1.0;              // multiplies E* (contact.stiffness_factor): the rigid limit's studies
  double stiffness = 0.0;                     // k [N/m^{3/2}], set by hertz_stiffness from the wire (build_case)
};

/// The contact law of a case: friction, the impact law, and the normal law (rigid or Hertz).
struct ContactLaw {
  FrictionModel friction;
  ImpactLaw impact;
  ContactModel model = ContactModel::rigid;  // contact.model
  HertzContact hertz;                        // used when model == hertz
};

/// k = (4/3) E* √R × stiffness_factor [N/m^{3/2}] for a wire of modulus `wire_youngs_pa` [Pa] and diameter
/// `wire_diameter_m` [m] (R = hertz.tip_radius_m, or D/2 when that is 0). SPEC §11.
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

/// The smallest restitution the compliant law reproduces (hunt_crossley_product).
inline constexpr double kMinCompliantRestitution = 0.05;

/// The damping c [s/m] of a compliant contact that starts with normal approach speed v0 = Ċ [m/s]
/// and full tip speed `full_speed` [m/s]: e from law.impact (a constant, or Yigit's e(v) capped,
/// without the plastic floor, and at least kMinCompliantRestitution), c = hunt_crossley_product(e) /
/// max(v0, impact.plastic_below_m_s, 1e-3 m/s). The speed floor bounds c for grazing touches (their
/// restitution is then above e). SPEC §11.
double hertz_damping(const ContactLaw& law, double v0, double full_speed);

/// The Hertz normal force F_n = max(0, k δ^{3/2}(1 + c δ̇)) [N] at penetration δ [m] (0 for δ ≤ 0)
/// and its rate δ̇ [m/s]: the force never pulls (clipped at 0 where the damping term would make it
/// negative, on a fast exit).
double hertz_normal_force(const HertzContact& hertz, double damping, double delta, double delta_rate);

/// The elastic energy stored in the Hertz contact, (2/5) k δ^{5/2} [J] (0 for δ ≤ 0).
double hertz_elastic_energy(const HertzContact& hertz, double delta);

/// The rate at which the compliant contact dissipates energy [W] (≤ 0, signed as energy given to
/// the filament): −(F_n − k δ^{3/2}) δ̇, i.e. −k c δ^{3/2} δ̇² unclipped and k δ^{3/2} δ̇ (δ̇ < 0) clipped.
double hertz_dissipation_rate(const HertzContact& hertz, double normal_force, double delta, double delta_rate);

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
  double moment = 0;          // its moment about the hub axis, X_t F_Y − Y_t F_X [N m]
  double power = 0;           // q̇ᵀQ_contact [W], the rate of change of the Jacobi integral
  double slip_power = 0;      // F_t V_t [W] (≤ 0)
  double surface_power = 0;   // F_t (V_s·t) [W]: a moving surface's power on the tip through friction (0 at rest)
  double slip = 0;            // slip direction s_t used
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
/// q̇): Q = λ∇C + F_t ∂V_t/∂q̇ into `generalized_force` (size n), and the forces, powers and the
/// force on the tip. Allocates nothing. λ = 0 gives the zero load.
ContactLoad contact_load(const FrictionModel& friction, const TipKinematics& tip,
                         const Eigen::Ref<const Eigen::VectorXd>& qd, double lambda, double slip_direction,
                         Eigen::Ref<Eigen::VectorXd> generalized_force);

}  // namespace rotbeam
