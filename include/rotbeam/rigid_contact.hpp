// Sustained rigid contact with Coulomb friction (docs/model.md §4, thesis eqns 4-86…4-97, 4-109).
//
// In contact the tip obeys M q̈ = −Ψ + λ∇C + |λ| Q*, with λ ≤ 0 and Q* = −μ_eff s_t ∂V_t/∂q̇, where
// s_t = ±1 is the slip direction (sign of the tangential slip V_t). The forces this implies are
// computed by contact_load (contact_law.hpp).
#pragma once

#include "rotbeam/contact_law.hpp"
#include "rotbeam/surface.hpp"

namespace rotbeam {

/// Solution of a λ + b|λ| = c (a > 0), both signs tried.
struct MultiplierSolution {
  enum class Status { unique, inconsistent, non_unique };
  Status status = Status::unique;
  double lambda = 0.0;  // the admissible root (unique), or the contact root λ ≤ 0 when non-unique
};

/// Solves a λ + b|λ| = c exactly, both signs tried. Contact, λ ≤ 0 with friction acting:
/// λ = c/(a − b), admissible if ≤ 0. Separation, λ > 0: the tip leaves the surface and feels no
/// friction, so λ = c/a, admissible if > 0. With a − b > 0 exactly one is admissible (the sign of
/// λ is the sign of c); with a − b ≤ 0 (Painlevé's paradox) there are two (c > 0) or none (c < 0).
MultiplierSolution solve_multiplier(double a, double b, double c);

/// Slip decision at a contact state.
struct SlipDecision {
  enum class Kind { slip, stick, separate };
  Kind kind = Kind::slip;
  double direction = 0.0;        // s_t ∈ {−1, +1} for slip
  double stick_normal = 0.0;     // λ with the tip locked tangentially [N] (when |V_t| was ~0)
  double stick_tangential = 0.0; // tangential force needed to hold the tip [N]
  bool from_velocity = true;     // false: |V_t| ~ 0, decided from the stick analysis
};

/// Speed below which V_t is treated as zero: 1e-9 ω(r_h + L) (far above round-off, far below any
/// physical slip speed; the sign of V_t is never taken from round-off, docs/model.md §10).
double stick_speed_threshold(const BeamModel& beam);

/// The forces that hold the tip locked (two constraints: C̈ = ∇Cᵀq̈ + γ = 0 and V̇_t = gᵀq̈ + γ_t = 0
/// with M q̈ = −Ψ + λ∇C + F_t g, g = ∂V_t/∂q̇): the multiplier λ [N] (≤ 0 pressing) and the tangential
/// force F_t [N] on the tip along the tangent. Where ∇C ∥ g (the straight filament on the plane, whose
/// tip moves only along its local y) holding the gap holds the slip: `dependent`, λ = c/a and F_t = 0.
/// Requires `tip` filled at (t, q, q̇) and ws.mass_llt/ws.psi evaluated at (q, q̇); uses ws.scratch,
/// ws.scratch2.
/// The contact's inverse masses at the tip: a_nn = ∇CᵀM⁻¹∇C, a_nt = ∇CᵀM⁻¹g, a_tt = gᵀM⁻¹g with
/// g = ∂V_t/∂q̇ [1/kg], leaving M⁻¹∇C in ws.scratch and M⁻¹g in ws.scratch2. Requires `tip` filled
/// and ws.mass_llt evaluated at q.
struct ContactMobility {
  double nn = 0, nt = 0, tt = 0;
};
ContactMobility contact_mobility(const TipKinematics& tip, BeamWorkspace& ws);

struct LockedTipForces {
  double lambda = 0, tangential = 0;
  bool dependent = false;
};
LockedTipForces locked_tip_forces(const TipKinematics& tip, BeamWorkspace& ws);

/// Decides the slip direction at (t, q, q̇). If |V_t| exceeds the threshold, s_t = sign(V_t).
/// Otherwise the tip is locked tangentially (two constraints, C = 0 and V_t = 0) and the normal
/// and tangential forces needed are solved: λ > 0 → separate; |tangential| ≤ μ_eff|λ| → stick;
/// else the tip slides against the force it would need, s_t = −sign(tangential).
/// Requires `tip` filled at (t, q, q̇) and ws.mass_llt/ws.psi evaluated at (q, q̇).
SlipDecision decide_slip(const BeamModel& beam, const FrictionModel& friction, const TipKinematics& tip,
                         BeamWorkspace& ws);

/// The locked-tip analysis of decide_slip, whatever V_t is (used at a located V_t = 0 event).
SlipDecision decide_slip_at_rest(const FrictionModel& friction, const TipKinematics& tip, BeamWorkspace& ws);

/// Result of the acceleration-level multiplier (thesis eqn 4-109, with the complete γ of docs/model.md §4).
struct AccelerationMultiplier {
  MultiplierSolution solution;
  double a = 0, b = 0, c = 0;  // of a λ + b|λ| = c
};

/// λ that keeps C̈ = 0 at (t, q, q̇) with slip direction s_t, from a = ∇CᵀM⁻¹∇C,
/// b = ∇CᵀM⁻¹Q*, c = ∇CᵀM⁻¹Ψ − γ. Evaluates the dynamics at (q, q̇) into ws and fills `tip`.
AccelerationMultiplier acceleration_multiplier(const BeamModel& beam, const Surface& surface,
                                               const FrictionModel& friction, double t,
                                               const Eigen::Ref<const Eigen::VectorXd>& q,
                                               const Eigen::Ref<const Eigen::VectorXd>& qd, double slip_direction,
                                               BeamWorkspace& ws, TipKinematics& tip);

}  // namespace rotbeam
