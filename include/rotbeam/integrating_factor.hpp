// The integrating factor of the adaptive scheme (Lawson's method; docs/model.md §6): the linear modal
// oscillation about the straight filament is propagated exactly, and the Runge–Kutta pair
// integrates only what remains.
//
// With the linearisation M0 q̈ + C q̇ + K q = 0 (beam_model.hpp) and modal coordinates q = V η,
// Vᵀ M0 V = m̄·1, Vᵀ K V = m̄·diag(Ω_j²), m̄ = trace(M0)/n (so that for M0 = m·1, V is orthonormal and
// η is in metres like q), every mode obeys
//
//   η̈_j + 2σ_j η̇_j + Ω_j² η_j = ρ_j,    σ_j = (VᵀCV)_jj / (2m̄),   ρ = η̈ + 2σ⊙η̇ + Ω²⊙η,
//
// where η̈ = Vᵀ M0 q̈ / m̄ is the full model's acceleration. Writing y_j = (η_j, η̇_j) and
// y_j(t) = E_j(t − t_b) v_j(t) with E_j(τ) = exp(A_j τ), A_j = [[0, 1], [−Ω_j², −2σ_j]], the
// integration variable v obeys v̇_j = E_j(−τ) (0, ρ_j): smooth where y oscillates at Ω_j, so the
// step is no longer tied to the highest mode's period. In closed form, with d² = Ω² − σ²,
//
//   E(τ) = e^{−στ} [[c + σ s, s], [−Ω² s, c − σ s]],   c = cos dτ, s = sin(dτ)/d
//
// (cosh and sinh(|d|τ)/|d| when d² < 0, c = 1 and s = τ when d = 0), valid for every Ω² and σ.
// Couplings the linearisation leaves out of its diagonal (none for the foreshortening beam's modal
// damping) stay in ρ, so the transformation is exact whatever they are.
#pragma once

#include "rotbeam/beam_model.hpp"

#include <Eigen/Core>

namespace rotbeam {

class IntegratingFactor {
public:
  /// From the linearisation about q = 0. Throws std::invalid_argument when M0 is not positive
  /// definite.
  explicit IntegratingFactor(const Linearization& lin);

  int size() const { return static_cast<int>(omega2_.size()); }
  /// The highest linear modal frequency Ω_max [rad/s].
  double highest_frequency() const { return highest_; }
  /// The largest modal decay rate σ_j [1/s] (0 undamped): E(−τ) grows like e^{σ τ}.
  double largest_decay_rate() const { return sigma_.size() ? sigma_.maxCoeff() : 0.0; }

  /// Sets the trigonometric factors for τ = t − t_b [s]; the calls below use them until the next.
  void at(double tau);
  /// q [m], q̇ [m/s] from the integration variable v (2n: v_η, v_η̇) at the τ of at().
  void to_physical(const double* v, double* q, double* qd);
  /// v at τ = 0 (the base time) from q, q̇: the modal coordinates η = Vᵀ M0 q / m̄, η̇.
  void to_integration(const double* q, const double* qd, double* v) const;
  /// dv/dt (2n) at the τ of at() from the full model's acceleration q̈ [m/s²] at the state last
  /// passed to to_physical.
  void derivative(const double* qdd, double* dv);

private:
  Eigen::MatrixXd shapes_;      // V [-]
  Eigen::MatrixXd projection_;  // Vᵀ M0 / m̄ [-]
  Eigen::VectorXd omega2_, sigma_;
  double highest_ = 0;
  // Per mode at the current τ: E(τ) entries and the scale e^{στ} of E(−τ).
  Eigen::VectorXd e11_, e12_, e21_, e22_, grow_, c_, s_;
  Eigen::VectorXd eta_, etad_, rho_;
};

}  // namespace rotbeam
