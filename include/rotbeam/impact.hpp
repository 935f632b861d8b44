// Impact by momentum balance (SPEC §5, thesis eqn 4-106):
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
};

/// Whether the tip leaves the surface after the impact. The law makes Ċ⁺ = −e Ċ⁻ exactly, so it
/// does iff e > 0 (above 1e-12); after a plastic impact the recomputed Ċ⁺ is zero only to round-off
/// of the tip velocity (~1e-15 ω(r_h + L)), and its sign must not decide.
inline bool rebounds(const ImpactResult& r) { return r.restitution > 1e-12; }

/// Applies the impact law at (t, q) to qd in place. Requires an approaching tip (Ċ⁻ > 0);
/// throws std::domain_error otherwise (a receding tip has no impact, SPEC §5).
ImpactResult apply_impact(const BeamModel& beam, const Surface& surface, const ImpactLaw& law, double t,
                          const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> qd,
                          BeamWorkspace& ws, TipKinematics& tip);

}  // namespace rotbeam
