// The ξ-integrals of docs/model.md §3, computed once per mode count and shared (read-only) by every model.
//
// With ISP(ξ) = ∫₀^ξ S'S'ᵀ dη and P(ξ) = S''S'ᵀ + S'S''ᵀ, the equations of motion, the energies and
// the hub angular momentum need only these constant arrays (all dimensionless, ξ ∈ [0, 1]):
//   isp_tip   = ISP(1)                     s_tip  = S(1)
//   isp_mean  = ∫ ISP dξ                   s_mean = ∫ S dξ
//   isp_xi    = ∫ ξ ISP dξ                 s_xi   = ∫ ξ S dξ
//   r4        = diag ∫ S''S''ᵀ dξ = r_i⁴ (exact for the cantilever basis; verified in tests)
//   isp_isp   [i][k][(j,l)] = ∫ ISP_ik ISP_jl dξ      (j ≤ l packed: n² × n(n+1)/2)
//   p_p       [(i,j)][(k,l)] = ∫ P_ij P_kl dξ          (packed pairs: n(n+1)/2 × n(n+1)/2)
//   isp_s     [i][k][j]      = ∫ ISP_ik S_j dξ         (n³)
// They are integrated with a composite Gauss–Legendre rule whose panel count grows with r_n, so the
// integrand's highest frequency (≈ 4 r_n) is resolved; the nested ISP(ξ) at each node is itself
// integrated with the same rule on [panel start, ξ]. tests/test_modal_integrals.cpp shows the
// convergence (doubling the panels changes no entry by more than ~1e-13 of the largest).
#pragma once

#include "rotbeam/modal_basis.hpp"

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace rotbeam {

struct ModalIntegrals {
  int n = 0;
  int pairs = 0;  // n(n+1)/2
  int quadrature_panels = 0;
  int quadrature_points = 0;
  ModalBasis basis;

  Eigen::MatrixXd isp_tip, isp_mean, isp_xi;
  Eigen::VectorXd s_tip, s_mean, s_xi, r4;
  std::vector<double> isp_isp;  // size n*n*pairs, index (i*n + k)*pairs + pair(j,l)
  std::vector<double> p_p;      // size pairs*pairs, index pair(i,j)*pairs + pair(k,l)
  std::vector<double> isp_s;    // size n*n*n, index (i*n + k)*n + j
  std::vector<int> pair_index;  // size n*n, pair_index[j*n + l] = packed index of {j, l}
  std::vector<int> pair_first, pair_second;  // inverse map, first <= second

  explicit ModalIntegrals(int modes) : basis(modes) {}
  int pair(int j, int l) const { return pair_index[j * n + l]; }
};

/// Computes the integrals for n modes with a chosen composite rule (for convergence studies).
ModalIntegrals compute_modal_integrals(int n, int panels, int points_per_panel);

/// Default panel count for n modes (resolves frequencies up to 4 r_n with 20-point panels).
int default_quadrature_panels(int n);

/// The integrals for n modes with the default rule, computed on first use and cached for the
/// life of the process (thread-safe).
std::shared_ptr<const ModalIntegrals> modal_integrals(int n);

}  // namespace rotbeam
