#include "rotbeam/modal_analysis.hpp"

#include "rotbeam/dynamics.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

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
    f.row(static_cast<Eigen::Index>(s)) = modal_analysis(make_beam(p)).frequencies_hz.transpose();
  }
  return f;
}

}  // namespace rotbeam
