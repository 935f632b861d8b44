// Energies and hub angular momentum of the foreshortening beam (docs/model.md §3, §7), from the
// precomputed integrals:
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

/// Evaluates every energy term at (q, q̇). Uses (and overwrites) ws.z and ws.mass.
EnergyTerms evaluate_energy(const ForeshorteningBeam& beam, const Eigen::Ref<const Eigen::VectorXd>& q,
                            const Eigen::Ref<const Eigen::VectorXd>& qd, ForeshorteningWorkspace& ws);

/// dH_z/dt [N m] at (q, q̇) with acceleration q̈, in closed form from the same integrals:
///   H_z = ω J(q) + p(q)·q̇,  J = ∫(x² + y²)dm,  p(q)·q̇ = ∫(x ẏ − y ẋ)dm,
///   dH_z/dt = ω ∇J·q̇ + d/dt(p(q)·q̇)  (O(n³); uses ws.z from the last evaluate_mass at q).
double angular_momentum_rate(const ForeshorteningBeam& beam, const Eigen::Ref<const Eigen::VectorXd>& q,
                             const Eigen::Ref<const Eigen::VectorXd>& qd,
                             const Eigen::Ref<const Eigen::VectorXd>& qdd, ForeshorteningWorkspace& ws);

}  // namespace rotbeam
