// Energies and hub angular momentum of the filament (SPEC §3, §7), from the precomputed integrals.
//   T2 = ½ q̇ᵀ M q̇            kinetic energy of the motion relative to the hub frame
//   T1 = ω ∫ (x ẏ − y ẋ) dm   gyroscopic coupling
//   T0 = ½ ω² ∫ (x² + y²) dm  energy of the rigid spin of the deformed shape
//   U  = ½ (EI/L³) ∫ (x''² + y''²) dξ
//   T  = T0 + T1 + T2 (inertial kinetic energy), h = T2 − T0 + U (Jacobi integral, conserved in
//   free flight), H_z = ∫ (ω(x² + y²) + x ẏ − y ẋ) dm.
// All in joules (H_z in kg m²/s).
#pragma once

#include "rotbeam/dynamics.hpp"

namespace rotbeam {

struct EnergyTerms {
  double t0 = 0, t1 = 0, t2 = 0;   // [J]
  double potential = 0;            // U [J]
  double kinetic = 0;              // T = T0 + T1 + T2 [J]
  double jacobi = 0;               // h = T2 − T0 + U [J]
  double spin_inertia = 0;         // J = ∫ (x² + y²) dm [kg m²]
  double relative_momentum = 0;    // ∫ (x ẏ − y ẋ) dm [kg m²/s]
  double angular_momentum = 0;     // H_z = ω J + ∫ (x ẏ − y ẋ) dm [kg m²/s]
};

/// Evaluates every energy term at (q, q̇). Uses (and overwrites) ws.z and ws.mass.
EnergyTerms evaluate_energy(const Model& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                            const Eigen::Ref<const Eigen::VectorXd>& qd, Workspace& ws);

}  // namespace rotbeam
