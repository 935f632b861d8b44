// Cantilever (clamped-free) beam eigenfunctions used as assumed modes (docs/model.md §2).
//
//   S_i(ξ) = cosh r_iξ − cos r_iξ − σ_i (sinh r_iξ − sin r_iξ),  ξ = s/L ∈ [0, 1],
//   σ_i = (sinh r_i − sin r_i)/(cosh r_i + cos r_i),  cos r_i cosh r_i = −1.
//
// The textbook form cancels catastrophically for large r_i (cosh r_iξ ≈ σ_i sinh r_iξ ≈ e^{r_i}/2).
// Here the growing exponentials are combined analytically:
//   cosh rξ − σ sinh rξ = α e^{−r(1−ξ)} + ½(1+σ) e^{−rξ},
//   α = ½ e^{r} (1 − σ) = (e^{−r} + cos r + sin r)/(1 + 2 e^{−r} cos r + e^{−2r}),
// so every term is bounded by O(1) for all ξ ∈ [0, 1] and every r.
// The normalisation is the classical one: ∫₀¹ S_i S_j dξ = δ_ij, ∫₀¹ S_i'' S_j'' dξ = r_i⁴ δ_ij.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace rotbeam {

/// Largest number of assumed modes of the quadratic-foreshortening model (its precomputed ξ-integrals
/// grow as n⁴).
inline constexpr int kMaxModes = 40;
/// Largest number of assumed modes of the elastica (elastica_beam.hpp), whose cost grows as n² times
/// its quadrature nodes, and of a ModalBasis.
inline constexpr int kMaxElasticaModes = 80;

/// The i-th positive root (i = 1, 2, …) of cos r cosh r = −1, found by Newton's method on
/// f(r) = cos r + 1/cosh r from the asymptotic guess (2i − 1)π/2. Accurate to ~1 ulp.
double cantilever_root(int i);

/// Coefficients of the first n cantilever modes and their evaluation. Immutable after construction.
class ModalBasis {
public:
  explicit ModalBasis(int n);

  int size() const { return static_cast<int>(root_.size()); }
  /// r_i (dimensionless), i = 0 … n−1 (mode i+1).
  double root(int i) const { return root_[i]; }
  /// σ_i of docs/model.md §2.
  double sigma(int i) const { return sigma_[i]; }

  /// Derivative order k = 0…4 of S_i with respect to ξ at ξ ∈ [0, 1].
  double shape(int i, double xi, int derivative = 0) const;

  /// S(ξ), S'(ξ), S''(ξ) for all modes at once (vectors of length n; pass nullptr to skip one).
  void evaluate(double xi, double* s, double* ds, double* d2s) const;

private:
  std::vector<double> root_, sigma_, alpha_, beta_;  // beta = ½(1 + σ)
};

}  // namespace rotbeam
