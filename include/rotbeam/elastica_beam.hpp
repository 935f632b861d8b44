// The geometrically exact filament (docs/model.md §11 "Geometrically exact filament"): a planar,
// inextensible, unshearable Euler–Bernoulli beam whose tangent angle is
//
//   φ(s) = Σ q_i ψ_i(s),  ψ_i(s) = S_i'(s/L)/L,
//
// with position r(s) = (r_h + ∫₀ˢ cos φ, ∫₀ˢ sin φ) in the hub frame, kinetic energy
// T = ½ρA∫|ṙ + ω × r|² ds and bending energy U = ½EI∫φ'² ds = ½(EI/L³) Σ r_i⁴ q_i². At small
// amplitude it coincides with the thesis's model (foreshortening_beam.hpp), and q keeps its meaning
// (y ≈ Sᵀq). Nothing of the geometry is truncated: every integral over the filament is evaluated
// afresh at each call by composite Gauss–Legendre quadrature, the running integrals ∫₀ˢ by the
// spectral integration matrix of each panel's Legendre nodes (accurate to ~1e-14; docs/model.md
// "The elastica").
//
// The equations of motion follow from virtual work, exact for a constant ω: with J(s) = ∂r(s)/∂q,
//   M(q) = ρA ∫ JᵀJ ds,
//   Ψ(q, q̇) = ρA ∫ Jᵀ [a_q + 2ω k × ṙ − ω² r] ds + (EI/L³) diag(r⁴) q (+ C q̇ when damped),
// a_q = J̇ q̇ the part of r̈ that does not involve q̈ (model.coriolis = false drops the 2ω term,
// model.centrifugal = false the ω² term).
#pragma once

#include "rotbeam/beam_model.hpp"
#include "rotbeam/beam_parameters.hpp"
#include "rotbeam/modal_basis.hpp"

#include <Eigen/Core>
#include <memory>

namespace rotbeam {

/// The elastica's scratch space: the filament at every quadrature node after the last evaluation.
struct ElasticaWorkspace : BeamWorkspace {
  ElasticaWorkspace(int n, int nodes);
  Eigen::VectorXd phi, phid;        // φ [rad], φ̇ [rad/s]
  Eigen::VectorXd cos_phi, sin_phi;
  Eigen::VectorXd x, y;             // position in the hub frame [m]
  Eigen::VectorXd xd, yd;           // velocity relative to the hub frame [m/s]
  Eigen::VectorXd ax, ay;           // a_q: relative acceleration without q̈ [m/s²]
  Eigen::VectorXd fx, fy;           // inertial acceleration less J q̈, weighted [m/s²]
  // The running integrals of the geometry (columns cos φ, sin φ, then ∂x/∂q and ∂y/∂q) and of the
  // rates, from their integrands; a row of panel starts.
  Eigen::MatrixXd integrand, integral;            // nodes × (2n + 2)
  Eigen::MatrixXd rate_integrand, rate_integral;  // nodes × 4
  Eigen::RowVectorXd start;
  /// ∂x/∂q, ∂y/∂q at the nodes (nodes × n, dimensionless).
  auto jx() { return integral.middleCols(2, n); }
  auto jy() { return integral.middleCols(2 + n, n); }
};

class ElasticaBeam final : public BeamModel, public BeamConstants {
public:
  /// Gauss–Legendre points per panel.
  static constexpr int kPanelPoints = 16;

  std::shared_ptr<const ModalBasis> basis;  // S_i and its derivatives (for the centreline at any ξ)
  Eigen::VectorXd r4;           // r_i⁴
  // The quadrature: `panels` equal panels of kPanelPoints Legendre nodes on ξ ∈ [0, 1].
  int panels = 0;
  Eigen::VectorXd node_xi, node_weight;  // ξ_m and w_m (Σ w_m = 1)
  Eigen::MatrixXd slope;                 // S_i'(ξ_m) (nodes × n)
  // Running integral on a panel: ∫_{-1}^{x_j} f ≈ Σ_m A_jm f(x_m) on the reference [−1, 1].
  Eigen::Matrix<double, kPanelPoints, kPanelPoints> running;
  Eigen::Matrix<double, kPanelPoints, 1> reference_weight;
  Eigen::MatrixXd damping;       // C [kg/s] (0×0 when undamped)
  Linearization linear;          // M0, K, C about q = 0 (from the model's own quadrature)
  // Constants of the excursion bound: μ = λ_max(K_b⁻¹ ISP(1)) [m/N] and V(0) = −T0(0) [J].
  double excursion_mu = 0, excursion_v0 = 0;

  int modes() const override { return n; }
  HubMotion hub_motion() const override { return {omega, theta0}; }
  double tip_radius() const override { return hub_radius + length; }
  double beam_length() const override { return length; }
  bool geometrically_exact() const override { return true; }
  std::unique_ptr<BeamWorkspace> make_workspace() const override;
  void evaluate_mass(const Eigen::Ref<const Eigen::VectorXd>& q, BeamWorkspace& ws) const override;
  void evaluate_dynamics(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                         BeamWorkspace& ws) const override;
  /// x_t = r_h + ∫cos φ, y_t = ∫sin φ; ∂x/∂q = −∫sin φ ψ, ∂y/∂q = ∫cos φ ψ;
  /// x_quadratic = −∫cos φ φ̇², y_quadratic = −∫sin φ φ̇² (all over s ∈ [0, L]).
  void tip(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
           HubFrameTip& out) const override;
  Eigen::Vector2d tip_position(const Eigen::Ref<const Eigen::VectorXd>& q) const override;
  /// r(ξL) at each ξ, the running integrals by 16-point Gauss–Legendre on panels of at most the
  /// model's panel width.
  void shape(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& xi,
             Eigen::Ref<Eigen::MatrixXd> positions) const override;
  /// |y_t| = |∫ sin φ ds|.
  double tip_deflection(const Eigen::Ref<const Eigen::VectorXd>& q) const override;
  /// T0 = ½ω²ρA∫|r|², T1 = ωρA∫(xẏ − yẋ), T2 = ½ρA∫|ṙ|² = ½q̇ᵀMq̇, U = ½(EI/L³)Σr_i⁴q_i² (each rotation term
  /// only when kept), h = T2 − T0 + U, H_z = ω J + ∫(xẏ − yẋ)dm with the same switches.
  EnergyTerms energy(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                     BeamWorkspace& ws) const override;
  /// dH_z/dt = 2ωρA∫(xẋ + yẏ) + ρA∫(xÿ − yẍ), ẍ = J_x q̈ + a_q,x (the switches as in energy).
  double angular_momentum_rate(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                               const Eigen::Ref<const Eigen::VectorXd>& qdd, BeamWorkspace& ws) const override;
  double dissipation(const Eigen::Ref<const Eigen::VectorXd>& qd) const override;
  bool damped() const override { return damping.size() > 0; }
  /// M0 = ρA∫J(0)ᵀJ(0) (= m·1), K = (EI/L³)diag(r⁴) + ω²ρA∫[(r_h + s) ∫₀ˢψψᵀ − S Sᵀ] ds, from the
  /// model's own nodes.
  Linearization linearization() const override { return linear; }
  /// |r(s)| ≤ r_h + s for an inextensible filament, so V = U − T0 ≥ U + V(0) and U ≤ h − V(0) for
  /// the rest of a free flight. With ∫φ² ds = qᵀISP(1)q/L ≤ 2μU/L: the tip moves at most
  /// ½∫φ² along x and √(L∫φ²) across; δ = their hypotenuse (at most 2L).
  double tip_excursion_bound(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                             BeamWorkspace& ws) const override;

  /// The node count and its layout.
  int nodes() const { return static_cast<int>(node_xi.size()); }
  /// The running integrals of every column of f (nodes × c) into out (the same shape), with
  /// `start` (at least c long) as scratch: out_m = ∫₀^{ξ_m} f dξ, one panel product for all columns.
  void running_integrals(const Eigen::MatrixXd& f, Eigen::MatrixXd& out, Eigen::RowVectorXd& start) const;
  /// Running integral over ξ of the node values f (nodes long) into out: out_m = ∫₀^{ξ_m} f dξ;
  /// returns ∫₀¹ f dξ.
  double running_integral(const double* f, double* out) const;
};

/// Builds the elastica of `p` (p.theory is not read) with `panels` quadrature panels (0: the
/// default, n + 2, which resolves the highest mode's slope to ~1e-15 on 16-point panels); θ0 as
/// for make_beam. Throws std::invalid_argument on non-physical values.
ElasticaBeam make_elastica(const BeamParameters& p, double theta0_rad = kDefaultStartAngleDeg * M_PI / 180.0,
                           int panels = 0);

}  // namespace rotbeam
