#include "rotbeam/modal_analysis.hpp"

#include "rotbeam/beam_factory.hpp"
#include "rotbeam/dynamics.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rotbeam {

ModalAnalysis modal_analysis(const ForeshorteningBeam& model) {
  const Eigen::MatrixXd k = linear_stiffness(model) / model.mass;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(k);
  ModalAnalysis out;
  out.frequencies_hz.resize(model.n);
  for (int i = 0; i < model.n; ++i) {
    const double lambda = solver.eigenvalues()[i];
    out.frequencies_hz[i] = lambda >= 0.0 ? std::sqrt(lambda) / (2.0 * M_PI) : std::numeric_limits<double>::quiet_NaN();
  }
  out.shapes = solver.eigenvectors();
  return out;
}

Eigen::VectorXd natural_frequencies_hz(const BeamModel& beam) {
  const Linearization l = beam.linearization();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(l.stiffness, l.mass, Eigen::EigenvaluesOnly);
  Eigen::VectorXd f(l.mass.rows());
  for (Eigen::Index i = 0; i < f.size(); ++i) {
    const double lambda = solver.eigenvalues()[i];
    f[i] = lambda >= 0.0 ? std::sqrt(lambda) / (2.0 * M_PI) : std::numeric_limits<double>::quiet_NaN();
  }
  return f;
}

Eigen::MatrixXd modal_damping_matrix(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& stiffness,
                                     const std::vector<double>& zeta) {
  const int n = static_cast<int>(mass.rows());
  if (zeta.empty() || std::all_of(zeta.begin(), zeta.end(), [](double z) { return z == 0.0; }))
    return Eigen::MatrixXd();
  if (zeta.size() != 1 && static_cast<int>(zeta.size()) != n)
    throw std::invalid_argument("damping ratio must have 1 or " + std::to_string(n) + " values, got " +
                                std::to_string(zeta.size()));
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(stiffness, mass);
  Eigen::VectorXd rate(n);  // 2ζ_iΩ_i [1/s]
  for (int i = 0; i < n; ++i) {
    const double z = zeta.size() == 1 ? zeta[0] : zeta[static_cast<std::size_t>(i)];
    if (!(z >= 0.0) || !std::isfinite(z))
      throw std::invalid_argument("damping ratio must be >= 0 and finite, got " + std::to_string(z));
    const double lambda = modes.eigenvalues()[i];
    if (z > 0.0 && !(lambda > 0.0))
      throw std::invalid_argument("mode " + std::to_string(i + 1) +
                                  " has no positive frequency at this speed, so it cannot be given a damping ratio");
    rate[i] = z > 0.0 ? 2.0 * z * std::sqrt(lambda) : 0.0;
  }
  const Eigen::MatrixXd mphi = mass * modes.eigenvectors();  // M0 Φ
  Eigen::MatrixXd c = mphi * rate.asDiagonal() * mphi.transpose();
  return 0.5 * (c + c.transpose());
}

std::vector<double> default_mode_speeds_rpm(double case_speed_rpm) {
  std::vector<double> speeds = {0.0, 550.0, 1000.0, 2000.0, 3000.0, case_speed_rpm};
  std::sort(speeds.begin(), speeds.end());
  speeds.erase(std::unique(speeds.begin(), speeds.end()), speeds.end());
  return speeds;
}

Eigen::MatrixXd frequencies_versus_speed(const BeamParameters& base, const std::vector<double>& speeds_rpm,
                                         const StopToken* stop) {
  Eigen::MatrixXd f = Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(speeds_rpm.size()), base.modes, NAN);
  BeamParameters p = base;
  for (std::size_t s = 0; s < speeds_rpm.size(); ++s) {
    if (stop && stop->stop_requested()) break;
    p.speed_rpm = speeds_rpm[s];
    f.row(static_cast<Eigen::Index>(s)) = natural_frequencies_hz(*make_beam_model(p)).transpose();
  }
  return f;
}

}  // namespace rotbeam
