#include "rotbeam/integrating_factor.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

namespace rotbeam {

IntegratingFactor::IntegratingFactor(const Linearization& lin) {
  const Eigen::Index n = lin.mass.rows();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(lin.stiffness, lin.mass);
  if (solver.info() != Eigen::Success)
    throw std::invalid_argument("integrating factor: the linearised mass matrix is not positive definite");
  const double mean_mass = lin.mass.trace() / static_cast<double>(n);
  shapes_ = solver.eigenvectors() * std::sqrt(mean_mass);  // Vᵀ M0 V = m̄·1
  projection_ = shapes_.transpose() * lin.mass / mean_mass;
  omega2_ = solver.eigenvalues();
  const Eigen::MatrixXd modal_damping = shapes_.transpose() * lin.damping * shapes_ / mean_mass;
  sigma_ = 0.5 * modal_damping.diagonal();
  for (Eigen::Index j = 0; j < n; ++j) highest_ = std::max(highest_, std::sqrt(std::max(omega2_[j], 0.0)));
  for (Eigen::VectorXd* v : {&e11_, &e12_, &e21_, &e22_, &grow_, &c_, &s_, &eta_, &etad_, &rho_}) v->setZero(n);
}

void IntegratingFactor::at(double tau) {
  for (Eigen::Index j = 0; j < omega2_.size(); ++j) {
    const double sigma = sigma_[j], d2 = omega2_[j] - sigma * sigma;
    double c, s;
    if (d2 > 0.0) {
      const double d = std::sqrt(d2);
      c = std::cos(d * tau);
      s = std::sin(d * tau) / d;
    } else if (d2 < 0.0) {
      const double d = std::sqrt(-d2);
      c = std::cosh(d * tau);
      s = std::sinh(d * tau) / d;
    } else {
      c = 1.0;
      s = tau;
    }
    const double decay = std::exp(-sigma * tau);
    c_[j] = c;  // c is even in τ, s odd: E(−τ) uses the same c, −s and e^{+στ}
    s_[j] = s;
    grow_[j] = 1.0 / decay;
    e11_[j] = decay * (c + sigma * s);
    e12_[j] = decay * s;
    e21_[j] = -decay * omega2_[j] * s;
    e22_[j] = decay * (c - sigma * s);
  }
}

void IntegratingFactor::to_physical(const double* v, double* q, double* qd) {
  const Eigen::Index n = omega2_.size();
  const Eigen::Map<const Eigen::VectorXd> ve(v, n), vd(v + n, n);
  eta_ = e11_.cwiseProduct(ve) + e12_.cwiseProduct(vd);
  etad_ = e21_.cwiseProduct(ve) + e22_.cwiseProduct(vd);
  Eigen::Map<Eigen::VectorXd>(q, n).noalias() = shapes_ * eta_;
  Eigen::Map<Eigen::VectorXd>(qd, n).noalias() = shapes_ * etad_;
}

void IntegratingFactor::to_integration(const double* q, const double* qd, double* v) const {
  const Eigen::Index n = omega2_.size();
  Eigen::Map<Eigen::VectorXd>(v, n).noalias() = projection_ * Eigen::Map<const Eigen::VectorXd>(q, n);
  Eigen::Map<Eigen::VectorXd>(v + n, n).noalias() = projection_ * Eigen::Map<const Eigen::VectorXd>(qd, n);
}

void IntegratingFactor::derivative(const double* qdd, double* dv) {
  const Eigen::Index n = omega2_.size();
  rho_.noalias() = projection_ * Eigen::Map<const Eigen::VectorXd>(qdd, n);
  rho_ += omega2_.cwiseProduct(eta_) + 2.0 * sigma_.cwiseProduct(etad_);
  // E(−τ)(0, ρ) = e^{στ} (−s ρ, (c + σ s) ρ).
  for (Eigen::Index j = 0; j < n; ++j) {
    dv[j] = -grow_[j] * s_[j] * rho_[j];
    dv[n + j] = grow_[j] * (c_[j] + sigma_[j] * s_[j]) * rho_[j];
  }
}

}  // namespace rotbeam
