// The contact-law seam (SPEC §4, §5): what the surface pushes on the tip with, as forces on the
// tip and as the generalised force on the modal coordinates, computed in one place
// (contact_load) for every scheme and output. Today's law is the thesis's: a rigid unilateral
// constraint whose multiplier λ is the normal force (rigid_contact.hpp), Coulomb friction, and
// momentum-balance impacts with a restitution law (impact.hpp). A compliant law computes λ from
// the penetration and its rate instead and goes through the same contact_load.
//
// Force conventions: because ∂C/∂R_tip is the unit normal n, λ ≤ 0 is the physical normal force:
// F_n = −λ [N]; friction on the tip acts along the tangent t, F_t = −μ F_n s_t with s_t = sign(V_t).
// With compat.thesis_forces the thesis's convention is used instead: F_n = |λ|·|∇C| and
// μ_eff = μ|∇C| (|∇C| being the norm of the modal-coordinate gradient, SPEC §4).
#pragma once

#include "rotbeam/impact.hpp"
#include "rotbeam/kinematics.hpp"

namespace rotbeam {

struct FrictionModel {
  double mu = 0.4;             // μ (surface.friction)
  bool thesis_forces = false;  // compat.thesis_forces
};

/// The contact law of a case: friction and the impact law.
struct ContactLaw {
  FrictionModel friction;
  ImpactLaw impact;
};

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
