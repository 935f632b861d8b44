// The thesis's beam theory (docs/model.md §2–§3): an inextensible Euler–Bernoulli filament with n assumed
// cantilever modes and quadratic foreshortening, x(ξ) = r_h + ξL − qᵀISP(ξ)q/(2L), y(ξ) = S(ξ)ᵀq,
// clamped radially to a hub of radius r_h spinning at ω. The first implementation of the
// beam-model seam (beam_model.hpp). Everything here is fixed for a run; the state (t, q, q̇) and
// the scratch space (ForeshorteningWorkspace, dynamics.hpp) live elsewhere.
#pragma once

#include "rotbeam/beam_model.hpp"
#include "rotbeam/beam_parameters.hpp"
#include "rotbeam/modal_integrals.hpp"

#include <memory>
#include <vector>

namespace rotbeam {

// BeamConstants: without model.centrifugal the ω² terms (K_ω, T0) are dropped, without
// model.coriolis the terms linear in ω (2ωG q̇, T1).
class ForeshorteningBeam final : public BeamModel, public BeamConstants {
public:
  std::shared_ptr<const ModalIntegrals> integrals;
  // Modal damping (docs/model.md §11): C = M0 Φ diag(2ζ_iΩ_i) Φᵀ M0 with Φ the mass-normalised linear modes
  // at ω (M0 = m·1); the generalised force is −C q̇. Empty (0×0) when undamped.
  Eigen::MatrixXd damping;       // C [kg/s]
  bool damped() const override { return damping.size() > 0; }

  int modes() const override { return n; }
  HubMotion hub_motion() const override { return {omega, theta0}; }
  double tip_radius() const override { return hub_radius + length; }
  double beam_length() const override { return length; }
  bool geometrically_exact() const override { return false; }
  std::unique_ptr<BeamWorkspace> make_workspace() const override;
  void evaluate_mass(const Eigen::Ref<const Eigen::VectorXd>& q, BeamWorkspace& ws) const override;
  void evaluate_dynamics(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                         BeamWorkspace& ws) const override;
  /// x_t = r_h + L − qᵀISP(1)q/(2L), y_t = S(1)ᵀq; ∂x/∂q = −ISP(1)q/L, ∂y/∂q = S(1);
  /// x_quadratic = −q̇ᵀISP(1)q̇/L, y_quadratic = 0.
  void tip(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
           HubFrameTip& out) const override;
  Eigen::Vector2d tip_position(const Eigen::Ref<const Eigen::VectorXd>& q) const override;
  /// y(ξ) = Σ q_i S_i(ξ), x(ξ) = r_h + ξL − (1/2L)∫₀^ξ (Σ q_i S_i')² dη (docs/model.md §2's foreshortening
  /// at every point; at ξ = 1 the tip), the integral by 8-point Gauss–Legendre on panels of at most
  /// 1/(n + 2).
  void shape(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& xi,
             Eigen::Ref<Eigen::MatrixXd> positions) const override;
  /// |y_t| = |S(1)ᵀq|.
  double tip_deflection(const Eigen::Ref<const Eigen::VectorXd>& q) const override;
  EnergyTerms energy(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                     BeamWorkspace& ws) const override;
  double angular_momentum_rate(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                               const Eigen::Ref<const Eigen::VectorXd>& qdd, BeamWorkspace& ws) const override;
  /// q̇ᵀC q̇ (0 when undamped).
  double dissipation(const Eigen::Ref<const Eigen::VectorXd>& qd) const override;
  /// M0 = m·1, K = K_ω(0) + K_b(0) (linear_stiffness, dynamics.hpp), C = damping.
  Linearization linearization() const override;
  bool free_flight_jacobian(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                            BeamWorkspace& ws, Eigen::Ref<Eigen::VectorXd> qdd, Eigen::Ref<Eigen::MatrixXd> jq,
                            Eigen::Ref<Eigen::MatrixXd> jqd) const override;
  /// With V(q) = U − T0 (T2 ≥ 0, so V ≤ h for the rest of the flight) and E = ½qᵀKq:
  /// V(q) − V(0) ≥ E − βE², β = ω²mμ²/(2L²), μ = λ_max(K⁻¹ ISP(1)) (the quartic bending energy is
  /// ≥ 0 and ∫(qᵀISP q)² ≤ (qᵀISP(1)q)² ≤ (2μE)²). While H = h − V(0) < 1/(4β) and E ≤ 1/(2β), E
  /// stays below E₁ = 2H/(1 + √(1 − 4βH)); then |y_t| ≤ √(2E₁ S(1)ᵀK⁻¹S(1)) and the tip's
  /// foreshortening qᵀISP(1)q/(2L) ≤ μE₁/L. δ = √(y² + x²) of the two; +inf outside that range or
  /// when K is not positive definite.
  double tip_excursion_bound(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                             BeamWorkspace& ws) const override;
  // Constants of the bound, set by make_beam: K [N/m], S(1)ᵀK⁻¹S(1) [m/N], μ [m/N], V(0) [J];
  // excursion_valid is false when K is not positive definite.
  Eigen::MatrixXd linear_stiffness_;
  bool excursion_valid = false;
  double excursion_tip_compliance = 0, excursion_mu = 0, excursion_v0 = 0;
};

/// Builds the model; θ0 = `theta0_rad` (default −π/2). Throws std::invalid_argument on
/// non-physical values (and on damping of a mode without a positive frequency at ω).
ForeshorteningBeam make_beam(const BeamParameters& p, double theta0_rad = kDefaultStartAngleDeg * M_PI / 180.0);

}  // namespace rotbeam
