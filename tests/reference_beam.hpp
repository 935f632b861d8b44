// An independent route to the filament's energies for the tests: x(ξ), y(ξ) and their rates are
// evaluated pointwise on a fine quadrature grid (Boost's 30-point Gauss–Legendre, composite),
// with ISP(ξ) integrated afresh at each node, and the energies are summed directly from
// SPEC §3's definitions. Nothing here uses the library's precomputed tensors or contractions.
#pragma once

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

/// A deterministic random state with tip deflection |y_t| = `tip_deflection_m` and modal
/// velocities of order `speed` m/s, with a decaying spectrum over the modes.
void random_state(const ForeshorteningBeam& model, unsigned seed, double tip_deflection_m, double speed, Eigen::VectorXd& q,
                  Eigen::VectorXd& v);

}  // namespace rotbeam::testing
