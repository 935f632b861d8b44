// Impact by momentum balance (docs/model.md §5, thesis eqn 4-106):
//   q̇⁺ = q̇⁻ + P M⁻¹∇C,  P = −(1 + e) Ċ⁻ / a,  a = ∇CᵀM⁻¹∇C,  so that Ċ⁺ = −e Ċ⁻.
// Position and time are unchanged; friction during the impact is neglected.
// P is the impulse on the tip along the surface normal [N s] (negative: the surface pushes the tip
// back).
#pragma once

#include "rotbeam/kinematics.hpp"

namespace rotbeam {

class Surface;

enum class RestitutionModel { yigit, constant };
enum class RestitutionSpeed { normal, full };
/// Friction during the impact: none (the thesis: the impulse is normal) or Coulomb's law with
/// Stronge's energetic coefficient of restitution (docs/model.md §11).
enum class ImpactFriction { none, coulomb };

/// How e is chosen at an impact.
struct ImpactLaw {
  RestitutionModel model = RestitutionModel::yigit;
  double constant = 0.5;          // e when model == constant, in [0, 1]
  double cap = 1.0;               // upper bound on e (Yigit's law exceeds 1 below 0.0634 m/s)
  // Normal speeds below this give e = 0. Default: where Yigit's law reaches e = 1 (0.501⁴ ≈ 0.063 m/s);
  // below it the capped law bounces elastically and a bounce sequence could never settle into
  // sustained contact (see docs/configuration.md).
  double plastic_below_m_s = 0.063;
  RestitutionSpeed speed = RestitutionSpeed::normal;  // `full`: Appendix B jump.m (|V_tip|)
  ImpactFriction friction = ImpactFriction::none;     // impact.friction
};

/// e for an impact with normal approach speed v_n = |Ċ⁻| and full tip speed |V| [m/s]:
/// Yigit et al. e = 0.501 v^(−1/4) with v = v_n (or |V| under RestitutionSpeed::full), capped;
/// 0 when v_n < plastic_below_m_s.
double restitution(const ImpactLaw& law, double normal_speed, double full_speed);

struct ImpactResult {
  double vx_before = 0, vx_after = 0;  // normal velocity Ċ before and after (V_X on the plane) [m/s]
  double vy_before = 0, vy_after = 0;  // tangential slip V_t (V_Y on the plane) [m/s]
  double restitution = 0;              // e used
  double impulse = 0;                  // P [N s]
  double effective_inverse_mass = 0;   // a = ∇CᵀM⁻¹∇C [1/kg]
  double relative_energy_loss = 0;     // ½(1 − e²)(Ċ⁻)²/a [J], the drop of T_rel
  double delta_t2 = 0;                 // change of ½q̇ᵀMq̇ [J] = −loss − P ∂C/∂t
  double tangential_impulse = 0;       // P_t along the tangent (Coulomb impacts; |P_t| ≤ μ|P|) [N s]
  double impulse_x = 0, impulse_y = 0; // the impulse on the tip, global frame [N s]
  bool jammed = false;                 // a frictional impact whose normal approach never ends (impact Painlevé)
  bool tangential = false;             // an impact without collision at a Painlevé point (apply_tangential_impact)
  double contact_work = 0;             // work of the contact impulse on the tip [J]: surface_work − (the energy the impact dissipates)
  double surface_work = 0;             // its part P⃗·V_s that a moving surface does (0 at rest, and without friction) [J]
  double frictional_heat = 0;          // −∫V_t dP_t over the impulse, the heat friction makes in it (≥ 0) [J]
  double sliding_load = 0;             // ∫|V_t| dp over the normal impulse, the impact's Archard load–distance [N m]
};

/// ∫|v| dp over [0, p] of a slip v that changes linearly from v0 to v1 as the normal impulse grows
/// from 0 to p ≥ 0 [N m]: p(|v0| + |v1|)/2, or p(v0² + v1²)/(2(|v0| + |v1|)) where v changes sign.
double linear_sliding_load(double p, double v0, double v1);

/// Whether the tip leaves the surface after the impact. The law makes Ċ⁺ = −e Ċ⁻ exactly, so it
/// does iff e > 0 (above 1e-12); after a plastic impact the recomputed Ċ⁺ is zero only to round-off
/// of the tip velocity (~1e-15 ω(r_h + L)), and its sign must not decide.
inline bool rebounds(const ImpactResult& r) { return r.restitution > 1e-12; }

/// Applies the impact law at (t, q) to qd in place. Requires an approaching tip (Ċ⁻ > 0);
/// throws std::domain_error otherwise (a receding tip has no impact, docs/model.md §5). `mu` is Coulomb's
/// coefficient during the impact, used when law.friction is `coulomb`.
///
/// Frictionless (the thesis): q̇⁺ = q̇⁻ + P M⁻¹∇C, P = −(1 + e)Ċ⁻/a. Coulomb (docs/model.md §11, Stronge
/// 2000, ch. 5): the normal impulse p = −P grows from 0; with a_nn = ∇CᵀM⁻¹∇C, a_nt = ∇CᵀM⁻¹g_t,
/// a_tt = g_tᵀM⁻¹g_t (g_t = ∂V_t/∂q̇) the normal and slip velocities are piecewise linear in p:
/// sliding with s = sign(V_t), dP_t = −μ s dp; when V_t reaches 0 the tip sticks (dP_t = a_nt/a_tt dp)
/// if |a_nt| ≤ μ a_tt, else slides back, s = −sign(a_nt). Compression ends at Ċ = 0; restitution ends
/// when the normal impulse's work in it is −e² times its work in compression (e is the law's,
/// as an energetic coefficient), so no impact creates energy and |P_t| ≤ μ p.
ImpactResult apply_impact(const BeamModel& beam, const Surface& surface, const ImpactLaw& law, double t,
                          const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> qd,
                          BeamWorkspace& ws, TipKinematics& tip, double mu = 0.0);

/// The tangential impact ("impact without collision": Génot & Brogliato 1999; Nordmark, Dankowicz &
/// Champneys 2017) at a sliding contact state (C = 0, Ċ ≈ 0) where no contact force is admissible,
/// a − b < 0 and c < 0 in a λ + b|λ| = c (Painlevé's paradox, docs/contact.md): sliding drives the tip
/// into the surface, so an impulse arises with no approach speed. It is the Coulomb impact above
/// from Ċ⁻ = max(Ċ, 0) with e = 0: the normal impulse grows while friction slows the slip until V_t = 0,
/// then the tip sticks in impulse space and compression ends at Ċ = 0. `jammed` where the slip does
/// not slow (|a_nt| > μ a_tt: no impulse resolves it), or where ∇C ∥ g_t or μ = 0 (no paradox there).
/// Applies the impulse to qd in place; restitution 0; `tangential` set.
ImpactResult apply_tangential_impact(const BeamModel& beam, const Surface& surface, double t,
                                     const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> qd,
                                     BeamWorkspace& ws, TipKinematics& tip, double mu);

}  // namespace rotbeam
