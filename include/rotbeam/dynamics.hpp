// Equations of motion of the spinning filament in free flight (SPEC §3, thesis eqns 4-60…4-82):
//
//   M(q) q̈ + Ψ(q, q̇) = Q,   Ψ = 2ω G(q) q̇ + D(q, q̇) q̇ + K_ω(q) q + K_b(q) q.
//
// Units: q in metres, q̇ in m/s, forces (Ψ, Q) in newtons (generalised), M in kg.
// Every function here works on a caller-owned Workspace and allocates nothing.
#pragma once

#include "rotbeam/model.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <vector>

namespace rotbeam {

/// Scratch space for the dynamics of one model size (n). Reused across calls; not thread-shared.
struct Workspace {
  explicit Workspace(int n);
  int n;
  // Results of the last evaluate_* call.
  Eigen::MatrixXd mass;           // M(q) [kg]
  Eigen::LLT<Eigen::MatrixXd> mass_llt;  // Cholesky factor of M(q)
  Eigen::VectorXd gyroscopic;     // 2ω G(q) q̇ [N]
  Eigen::VectorXd foreshortening; // D(q, q̇) q̇ [N]
  Eigen::VectorXd centrifugal;    // K_ω(q) q [N]
  Eigen::VectorXd bending;        // K_b(q) q [N]
  Eigen::VectorXd psi;            // Ψ = sum of the four above [N]
  // Contractions shared by the terms (see dynamics.cpp).
  std::vector<double> z;          // Z[i][(j,l)] = Σ_k q_k ∫ISP_ik ISP_jl
  Eigen::VectorXd q_pairs, v_pairs, p_contract, isp_cubic, scratch, scratch2;
};

/// Fills ws.mass = M(q) and the contraction ws.z (q only). O(n⁴) with packed symmetry.
void evaluate_mass(const Model& model, const Eigen::Ref<const Eigen::VectorXd>& q, Workspace& ws);

/// Fills M(q), every term of Ψ(q, q̇), and the Cholesky factor of M.
void evaluate_dynamics(const Model& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                       const Eigen::Ref<const Eigen::VectorXd>& qd, Workspace& ws);

/// q̈ = M⁻¹(Q − Ψ) for a given generalised force Q (pass nullptr for Q = 0, free flight).
/// Calls evaluate_dynamics. Result written to qdd (size n, preallocated).
void acceleration(const Model& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                  const Eigen::Ref<const Eigen::VectorXd>& qd, const Eigen::VectorXd* generalized_force,
                  Workspace& ws, Eigen::Ref<Eigen::VectorXd> qdd);

/// Stiffness of the system linearised about q = 0 (K_ω(0) + K_b(0)) [N/m]; M(0) = m·1, G(0) = D = 0.
Eigen::MatrixXd linear_stiffness(const Model& model);

}  // namespace rotbeam
