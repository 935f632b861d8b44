// An independent route to the filament's energies for the tests: x(ξ), y(ξ) and their rates are
// evaluated pointwise on a fine quadrature grid (Boost's 30-point Gauss–Legendre, composite),
// with ISP(ξ) integrated afresh at each node, and the energies are summed directly from
// docs/model.md §3's definitions. Nothing here uses the library's precomputed tensors or contractions.
#pragma once

#include "rotbeam/elastica_beam.hpp"
#include "rotbeam/foreshortening_beam.hpp"

#include <Eigen/Core>
#include <vector>

namespace rotbeam::testing {

class ReferenceBeam {
public:
  ReferenceBeam(const ForeshorteningBeam& model, int panels);
  double t0(const Eigen::VectorXd& q) const;                             // ½ω² ∫ (x² + y²) dm
  double t1(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;   // ω ∫ (x ẏ − y ẋ) dm
  double t2(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;   // ½ ∫ (ẋ² + ẏ²) dm
  double potential(const Eigen::VectorXd& q) const;                      // ½ EI/L³ ∫ (x''² + y''²) dξ
  double lagrangian(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
    return t0(q) + t1(q, v) + t2(q, v) - potential(q);
  }
  double angular_momentum(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;

private:
  const ForeshorteningBeam& model_;
  std::vector<double> w_;                // weights on [0, 1]
  std::vector<double> xi_;               // nodes
  std::vector<Eigen::VectorXd> s_, d2s_; // S, S'' at the nodes
  std::vector<Eigen::MatrixXd> isp_, p_; // ISP(ξ), P(ξ) at the nodes
};

/// The elastica's energies by another route (docs/model.md §11): at each node of a composite 30-point
/// Gauss–Legendre rule the position r(ξ) = (r_h + L∫₀^ξ cos φ, L∫₀^ξ sin φ) and its rate are
/// integrated afresh with a rule of their own on [0, ξ], from the modal basis (not from the model's
/// nodes or running-integral matrix); U = ½(EI/L³)∫(Σ q_i S_i'')² dξ by quadrature (not from r_i⁴).
/// The rotation terms follow the model's switches.
class ReferenceElastica {
public:
  ReferenceElastica(const ElasticaBeam& model, int panels);
  double t0(const Eigen::VectorXd& q) const;                             // ½ω² ∫ (x² + y²) dm (0 when switched off)
  double t1(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;   // ω ∫ (x ẏ − y ẋ) dm (0 when switched off)
  double t2(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;   // ½ ∫ (ẋ² + ẏ²) dm
  double potential(const Eigen::VectorXd& q) const;                      // ½ EI ∫ φ'² ds
  double lagrangian(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
    return t0(q) + t1(q, v) + t2(q, v) - potential(q);
  }
  /// The tip (x, y) in the hub frame [m].
  Eigen::Vector2d tip(const Eigen::VectorXd& q) const;

private:
  // Position and velocity at outer node g.
  void point(std::size_t g, const Eigen::VectorXd& q, const Eigen::VectorXd* v, double& x, double& y, double& xd,
             double& yd) const;
  const ElasticaBeam& model_;
  std::vector<double> w_, xi_;                       // outer rule on [0, 1]
  std::vector<std::vector<double>> inner_w_;         // rule on [0, ξ_g]
  std::vector<std::vector<Eigen::VectorXd>> inner_ds_;  // S' at its nodes
  std::vector<Eigen::VectorXd> d2s_;                 // S'' at the outer nodes
  std::vector<double> tip_w_;                        // rule on [0, 1] for the tip
  std::vector<Eigen::VectorXd> tip_ds_;
};

/// A deterministic random state with tip deflection |y_t| = `tip_deflection_m` and modal
/// velocities of order `speed` m/s, with a decaying spectrum over the modes.
void random_state(const ForeshorteningBeam& model, unsigned seed, double tip_deflection_m, double speed, Eigen::VectorXd& q,
                  Eigen::VectorXd& v);

}  // namespace rotbeam::testing
