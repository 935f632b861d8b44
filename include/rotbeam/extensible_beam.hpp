// The extensible filament (beam.axial = "extensible", docs/model.md §12): either beam theory with the
// wire's own axial compliance EA. One more generalised coordinate, the tip's stretch a [m], with the
// strain uniform along the filament (ε = a/L, the static shape of a rod loaded at its tip: it gives
// the exact static stiffness EA/L and Rayleigh's effective mass m/3 along the filament):
//
//   quadratic (beam.theory = "foreshortening"):  x(ξ) = r_h + ξ(L + a) − (L/2)∫₀^ξ φ² dη,  y(ξ) = S(ξ)ᵀq,
//   exact (beam.theory = "elastica"):             r(ξ) = (r_h, 0) + (1 + ε) L ∫₀^ξ (cos φ, sin φ) dη,
//
// φ = S'ᵀq/L, with U = U_b(q) + ½(EA/L)a² (U_b the theory's bending energy: the thesis's quartic form
// for the quadratic geometry, ½EI∫φ'² for the exact one) and T = ½ρA∫|ṙ + ω × r|² ds. At a = 0 each
// reduces to its inextensible theory term by term (tests/test_extensible.cpp checks M and Ψ there).
// The equations of motion follow from virtual work at the quadrature nodes, as for the elastica
// (elastica_beam.hpp): with J = ∂r/∂(q, a),
//   M = ρA∫JᵀJ ds,  Ψ = ρA∫Jᵀ[a_q + 2ω k × ṙ − ω² r] ds + ∇U (+ C q̇ when damped).
// The coordinates are (q_1 … q_n, a): modes() is n + 1.
#pragma once

#include "rotbeam/beam_model.hpp"
#include "rotbeam/beam_parameters.hpp"
#include "rotbeam/elastica_beam.hpp"

#include <Eigen/Core>
#include <memory>

namespace rotbeam {

/// The extensible filament's scratch space: the filament at every quadrature node after the last
/// evaluation.
struct ExtensibleWorkspace : BeamWorkspace {
  ExtensibleWorkspace(int coordinates, int n, int nodes);
  Eigen::VectorXd phi, phid;        // φ [rad], φ̇ [rad/s]
  Eigen::VectorXd cos_phi, sin_phi; // (exact geometry)
  Eigen::VectorXd x, y, xd, yd;     // position [m] and velocity [m/s] relative to the hub frame
  Eigen::VectorXd ax, ay;           // a_q: relative acceleration without the q̈ terms [m/s²]
  Eigen::VectorXd fx, fy;           // the weighted inertial acceleration less J q̈ [m/s²]
  Eigen::MatrixXd jx, jy;           // ∂x/∂(q, a), ∂y/∂(q, a) at the nodes (nodes × (n + 1))
  Eigen::MatrixXd weighted;         // a Jacobian times the quadrature weights
  Eigen::MatrixXd integrand, integral, rate_integrand, rate_integral;  // running integrals' columns
  Eigen::RowVectorXd start;
  Eigen::VectorXd bend;             // ∇U_b (size n + 1, last entry 0)
  Eigen::VectorXd curvature;        // y'' at the nodes [m] (quadratic geometry)
};

class ExtensibleBeam final : public BeamModel, public BeamConstants {
public:
  BeamTheory theory = BeamTheory::foreshortening;  // quadratic (foreshortening) or exact (elastica) geometry
  double axial_stiffness = 0;       // EA/L [N/m]
  double rest_stretch = 0;          // a of the straight filament turning steadily (centrifugal stretch) [m]
  ElasticaBeam grid;                // the quadrature nodes, the modes' slopes and the running integrals
  std::shared_ptr<const BeamModel> inextensible;  // the same theory without the stretch (shape, bending)
  Eigen::MatrixXd shape_nodes, curvature_nodes;   // S(ξ_m), S''(ξ_m) (nodes × n)
  Eigen::VectorXd s_tip;                          // S(1)
  Eigen::MatrixXd damping;          // C [kg/s] ((n + 1)², 0×0 when undamped)
  Linearization linear;             // about q = 0, a = 0: block-diagonal (bending; axial m/3, EA/L − mω²/3)

  int modes() const override { return n + 1; }
  HubMotion hub_motion() const override { return {omega, theta0}; }
  /// r_h + L + the rest stretch [m].
  double tip_radius() const override { return hub_radius + length + rest_stretch; }
  double beam_length() const override { return length; }
  bool geometrically_exact() const override { return theory == BeamTheory::elastica; }
  std::unique_ptr<BeamWorkspace> make_workspace() const override;
  void evaluate_mass(const Eigen::Ref<const Eigen::VectorXd>& q, BeamWorkspace& ws) const override;
  void evaluate_dynamics(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                         BeamWorkspace& ws) const override;
  void tip(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
           HubFrameTip& out) const override;
  Eigen::Vector2d tip_position(const Eigen::Ref<const Eigen::VectorXd>& q) const override;
  /// The inextensible theory's centreline, stretched: + (ξa, 0) (quadratic) or scaled by 1 + ε about
  /// the clamp (exact).
  void shape(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& xi,
             Eigen::Ref<Eigen::MatrixXd> positions) const override;
  double tip_deflection(const Eigen::Ref<const Eigen::VectorXd>& q) const override;
  /// As the elastica's (node sums), with U = U_b + ½(EA/L)a².
  EnergyTerms energy(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                     BeamWorkspace& ws) const override;
  double angular_momentum_rate(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                               const Eigen::Ref<const Eigen::VectorXd>& qdd, BeamWorkspace& ws) const override;
  double dissipation(const Eigen::Ref<const Eigen::VectorXd>& qd) const override;
  bool damped() const override { return damping.size() > 0; }
  Linearization linearization() const override { return linear; }
  /// None (+inf): the stretch exchanges energy with the bending, and no bound is derived for it.
  double tip_excursion_bound(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                             BeamWorkspace& ws) const override;
  /// (0, …, 0, rest_stretch).
  void rest_state(Eigen::Ref<Eigen::VectorXd> q) const override;
};

/// Builds the extensible filament of `p` (its theory chooses the geometry; p.axial is not read); θ0
/// as for make_beam. Throws std::invalid_argument on non-physical values, and when the hub spins so
/// fast that the centrifugal load overcomes the axial stiffness (mω²/3 ≥ EA/L).
ExtensibleBeam make_extensible(const BeamParameters& p, double theta0_rad = kDefaultStartAngleDeg * M_PI / 180.0);

}  // namespace rotbeam
