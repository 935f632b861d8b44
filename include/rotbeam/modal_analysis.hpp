// Linearised modal analysis about the straight beam (q = 0) at a given hub speed (docs/model.md §3):
//   m q̈ + (K_ω(0) + K_b(0)) q = 0  (G(0) = 0 and D = 0, so the in-plane modes decouple).
// Frequencies Ω_k/2π of the lead-lag modes of the spinning cantilever; the mode shapes are the
// eigenvectors in modal coordinates (normalised to unit length), w_k(ξ) = S(ξ)ᵀ φ_k.
#pragma once

#include "rotbeam/stop_token.hpp"

#include "rotbeam/foreshortening_beam.hpp"

#include <Eigen/Core>
#include <vector>

namespace rotbeam {

struct ModalAnalysis {
  Eigen::VectorXd frequencies_hz;  // ascending, n values (negative stiffness → NaN)
  Eigen::MatrixXd shapes;          // column k = modal coordinates of mode k
};

/// Modes of `model` (its own ω).
ModalAnalysis modal_analysis(const ForeshorteningBeam& model);

/// The undamped natural frequencies [Hz] of any beam model's linearisation about q = 0 at its own hub
/// speed (K φ = Ω² M0 φ, BeamModel::linearization), ascending; NaN where K makes a mode unstable.
Eigen::VectorXd natural_frequencies_hz(const BeamModel& beam);

/// The modal damping matrix of docs/model.md §11, C = M0 Φ diag(2ζ_iΩ_i) Φᵀ M0 [kg/s], with Ω_i and Φ the
/// M0-normalised modes of K φ = Ω² M0 φ (ascending Ω), for the ratios ζ (empty or all zero: an empty
/// 0×0 matrix, no damping; one value for every mode; or n values). Throws std::invalid_argument on a
/// ratio that is negative or not finite, a count other than 1 or n, and a damped mode without a
/// positive frequency.
Eigen::MatrixXd modal_damping_matrix(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& stiffness,
                                     const std::vector<double>& zeta);

/// The default speeds of `rotbeam modes` [rpm]: 0, the Table 5-2 speeds and the case's own, ascending.
std::vector<double> default_mode_speeds_rpm(double case_speed_rpm);

/// Modes at each speed [rpm] for the beam of `base` (its theory and rotation switches) (rows: speeds, columns: modes) [Hz]. A stop
/// requested on `stop` (checked at every speed) ends it early: the rows not reached are NaN.
Eigen::MatrixXd frequencies_versus_speed(const BeamParameters& base, const std::vector<double>& speeds_rpm,
                                         const StopToken* stop = nullptr);

}  // namespace rotbeam
