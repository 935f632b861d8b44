// Equations of motion of the foreshortening beam in free flight (docs/model.md §3, thesis eqns 4-60…4-82):
//
//   M(q) q̈ + Ψ(q, q̇) = Q,   Ψ = 2ω G(q) q̇ + D(q, q̇) q̇ + K_ω(q) q + K_b(q) q (+ C q̇ when damped, docs/model.md §11).
//
// Units: q in metres, q̇ in m/s, forces (Ψ, Q) in newtons (generalised), M in kg.
// Every function here works on a caller-owned workspace and allocates nothing.
#pragma once

#include "rotbeam/foreshortening_beam.hpp"

#include <vector>

namespace rotbeam {

/// Scratch space of the foreshortening beam for one mode count n, with every term of Ψ kept
/// separately. Reused across calls; not thread-shared.
struct ForeshorteningWorkspace : BeamWorkspace {
  explicit ForeshorteningWorkspace(int n);
  // Results of the last evaluate_dynamics call (their sum is BeamWorkspace::psi).
  Eigen::VectorXd gyroscopic;     // 2ω G(q) q̇ [N]
  Eigen::VectorXd foreshortening; // D(q, q̇) q̇ [N]
  Eigen::VectorXd centrifugal;    // K_ω(q) q [N]
  Eigen::VectorXd bending;        // K_b(q) q [N]
  Eigen::VectorXd damping;        // C q̇ [N] (zero when undamped)
  // Contractions shared by the terms (see dynamics.cpp).
  std::vector<double> z;          // Z[i][(j,l)] = Σ_k q_k ∫ISP_ik ISP_jl
  Eigen::VectorXd q_pairs, v_pairs, p_contract, isp_cubic;
  // Scratch of free_flight_jacobian: ∂Ψ/∂q, ∂Ψ/∂q̇ (n × n), a packed pair vector and an n² vector.
  Eigen::MatrixXd dpsi_dq, dpsi_dv;
  Eigen::VectorXd pair_scratch, square_scratch;
};

/// Fills ws.mass = M(q) and the contraction ws.z (q only; no factorisation). O(n⁴) with packed symmetry.
void evaluate_mass(const ForeshorteningBeam& beam, const Eigen::Ref<const Eigen::VectorXd>& q,
                   ForeshorteningWorkspace& ws);

/// Fills M(q), every term of Ψ(q, q̇), and the Cholesky factor of M.
void evaluate_dynamics(const ForeshorteningBeam& beam, const Eigen::Ref<const Eigen::VectorXd>& q,
                       const Eigen::Ref<const Eigen::VectorXd>& qd, ForeshorteningWorkspace& ws);

/// q̈ = −M⁻¹Ψ into qdd, ∂q̈/∂q into jq and ∂q̈/∂q̇ into jqd (n × n) in closed form:
///   ∂q̈/∂q̇ = −M⁻¹ ∂Ψ/∂q̇,   ∂q̈/∂q = −M⁻¹ (∂Ψ/∂q + (∂M/∂q) q̈),
/// each term of Ψ differentiated from its contraction with the modal integrals (dynamics.cpp); O(n⁴)
/// like Ψ itself. Verified against central differences of q̈ (tests/test_tangent.cpp).
void free_flight_jacobian(const ForeshorteningBeam& beam, const Eigen::Ref<const Eigen::VectorXd>& q,
                          const Eigen::Ref<const Eigen::VectorXd>& qd, ForeshorteningWorkspace& ws,
                          Eigen::Ref<Eigen::VectorXd> qdd, Eigen::Ref<Eigen::MatrixXd> jq, Eigen::Ref<Eigen::MatrixXd> jqd);

/// Stiffness of the system linearised about q = 0 (K_ω(0) + K_b(0)) [N/m]; M(0) = m·1, G(0) = D = 0.
Eigen::MatrixXd linear_stiffness(const ForeshorteningBeam& beam);

}  // namespace rotbeam
