// The periodic steady state of a run over many revolutions (docs/model.md §11, docs/model.md "Many
// revolutions"): the m-revolution map of the section state, its Jacobian by finite differences,
// the Floquet multipliers, and the two searches (brute force and shooting) behind
// simulation.until_steady.
#pragma once

#include "rotbeam/pass.hpp"

#include <Eigen/Dense>

#include <optional>
#include <vector>

namespace rotbeam {

/// One evaluation of the map: the section state after m revolutions and the contact events met.
struct MapEvaluation {
  Eigen::VectorXd z;         // P^m(z0); empty when the run failed or was stopped
  int impacts = 0;           // impacts over the m revolutions
  int contact_episodes = 0;  // sustained-contact episodes over the m revolutions
  bool complete = false;     // the m revolutions ran to their end
  std::optional<NumericalFailure> failure;
  PassSummary summary;       // the run's summary (its ledger, peak force and deflection over the m revolutions)
  // With the variational equations (SectionMap::operator()'s `tangent`): ∂P^m/∂z at z0, empty where
  // the run could not carry them, and then why (tangent_lost).
  Eigen::MatrixXd jacobian;
  std::string tangent_lost;
};

/// The m-revolution map P^m of the section θ = θ0 (mod 360°): m revolutions run by run_pass from
/// the flexible start z at θ0, with the stepper restarted as at every section, so that P^m applied
/// to a run's section state gives that run's state m revolutions later (Revolutions.
/// OneRevolutionIsAMapOfTheSectionState). Rows and events are discarded.
class SectionMap {
public:
  SectionMap(const System& system, const PassOptions& options, const StopToken* stop);

  /// P^m(z); with `tangent`, also its Jacobian from the variational equations with a saltation
  /// matrix at every event (tangent.hpp): one run instead of the 4n of `jacobian`, and accurate to
  /// the integration's tolerance rather than to the differences' ≈ 1e-4.
  MapEvaluation operator()(const Eigen::VectorXd& z, int m, bool tangent = false) const;

  /// The Jacobian ∂P^m/∂z at z (`base` = P^m(z)) by options.jacobian:
  ///  - variational: one run of the variational equations with saltation matrices (tangent.hpp),
  ///    accurate to the integration's tolerance; where they cannot be carried through the run (a
  ///    grazing event, a tangential impact, the thesis scheme) it falls back to differences and
  ///    fallback() says why;
  ///  - differences: central differences with steps δ_j = kJacobianStep·max(‖z‖, 1e-6) (the map's
  ///    integration noise, ≈ rtol·‖z‖, over δ sets its accuracy: ≈ 1e-4 at rtol 1e-9).
  /// Evaluations whose impacts or episodes differ from `base` (the event sequence changed inside the
  /// stencil, so the map is not smooth there) are counted in *sequence_changes. Empty on a failure.
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& z, int m, const MapEvaluation& base, int* sequence_changes) const;
  /// The Jacobian by central differences (whatever options.jacobian says).
  Eigen::MatrixXd jacobian_by_differences(const Eigen::VectorXd& z, int m, const MapEvaluation& base,
                                          int* sequence_changes) const;

  /// How the last Jacobian was computed ("variational" or "differences"; "" before the first).
  const std::string& last_method() const { return last_method_; }
  /// Why the last variational Jacobian fell back to differences ("" when it did not).
  const std::string& fallback() const { return fallback_; }

  int evaluations() const { return evaluations_; }
  int revolutions_run() const { return revolutions_run_; }
  static constexpr double kJacobianStep = 1e-5;

private:
  const System& system_;
  PassOptions options_;
  const StopToken* stop_;
  mutable int evaluations_ = 0, revolutions_run_ = 0;
  mutable std::string last_method_, fallback_;
};

/// `base` with the flexible start of section state z = (q/L, q̇/(ωL)) (section_state's inverse).
InitialConditions section_start(const BeamModel& beam, const Eigen::VectorXd& z, InitialConditions base = {});

/// The eigenvalues of a map's Jacobian, largest magnitude first.
std::vector<Multiplier> floquet_multipliers(const Eigen::MatrixXd& jacobian);

/// Settings of the shooting search (docs/model.md §11); defaults are the product's.
struct ShootingSettings {
  double warmup_tolerance = 1e-3;  // brute force until the section distance is below this …
  int warmup_revolutions = 30;     // … or this many revolutions, whichever comes first
  int max_newton_iterations = 12;  // per period tried
  int max_step_halvings = 6;       // backtracking when a Newton step does not reduce the residual
};

/// Runs `initial` with options.until_steady set to its periodic steady state and returns the run
/// the user sees, with summary.steady_state filled (reached, period, multipliers, counts, note).
///  - brute force: run_pass revolution after revolution (its rows, events and revolutions go to
///    control.sink), then the multipliers of P^m at the orbit's section state;
///  - shooting: a brute-force warm-up, then Newton on F(z) = P^m(z) − z with the central-difference
///    Jacobian, m the warm-up's period (else 1, 2, 3, 4 in turn); the converged orbit's m
///    revolutions are then run from z* into control.sink, so the files hold the periodic orbit.
/// Never throws for numerical trouble (failures are returned as by run_pass).
PassResult run_to_steady_state(const System& system, const InitialConditions& initial, const PassOptions& options,
                               const PassControl& control, const ShootingSettings& settings = {});

}  // namespace rotbeam
