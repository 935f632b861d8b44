// Pseudo-arclength continuation of the fixed points of a parametrised map, z = P^M(z; p), with their
// multipliers and the special points a branch passes (docs/continuation.md): the algorithm alone,
// over any map (the section map of a filament's revolutions is one, orbit_continuation.hpp; the tests
// use maps with known bifurcations).
//
// Unknowns y = (ẑ, u): the state scaled by a fixed z_scale (ẑ = z / z_scale) and the parameter
// scaled to the range (u = (p − from) / (to − from): 0 at `from`, 1 at `to`). A branch is followed by
// steps of arclength h in y: a tangent predictor, then a corrector on [P(z) − z; tᵀ(y − y_pred)] = 0
// (Newton's chord with Broyden updates, started from the last point's Jacobian). The Jacobian ∂P/∂z
// and ∂P/∂p are central differences of the map; their columns are evaluated in parallel.
#pragma once

#include "rotbeam/pass.hpp"
#include "rotbeam/stop_token.hpp"

#include <Eigen/Dense>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rotbeam {

/// What one period of an orbit did (the metrics of branch.csv). NaN where the map gives none.
struct OrbitMetrics {
  int impacts = 0;                   // over the period
  int contact_episodes = 0;          // over the period
  double normal_impulse_n_s = 0;     // ∫F_n dt + Σ|P| over the period [N s]
  double peak_normal_force_n = 0;    // [N]
  double mean_hub_torque_n_m = NAN;  // hub work / (ω · period) [N m]
  double mean_hub_power_w = NAN;     // hub work / period [W]
  double max_tip_deflection_ratio = NAN;  // max |y_t| / L [-]
};

/// One evaluation of the map: P^M(z; p), or why it could not be had.
struct MapValue {
  Eigen::VectorXd z;  // empty when the evaluation did not complete
  // ∂P^M/∂z where the map was asked for it (a ParametrisedJacobian) and could give it; empty otherwise,
  // and then why in jacobian_fallback.
  Eigen::MatrixXd jacobian;
  std::string jacobian_fallback;
  OrbitMetrics metrics;
  std::optional<NumericalFailure> failure;
  bool complete() const { return z.size() > 0; }
};

/// P^M(z; p): the map after `period` applications at parameter p. Called from several threads at
/// once (the Jacobian's columns): it must be safe to do so.
using ParametrisedMap = std::function<MapValue(const Eigen::VectorXd& z, double p, int period)>;
/// P^M(z; p) with its Jacobian ∂P^M/∂z (MapValue::jacobian) from one evaluation (the variational
/// equations); where it gives none, the columns are central differences of the map.
using ParametrisedJacobian = std::function<MapValue(const Eigen::VectorXd& z, double p, int period)>;

/// Settings of the continuation; the step lengths are in the scaled unknowns (a step of 0.02 with
/// the state at rest moves the parameter by 2 % of |to − from|).
struct ContinuationSettings {
  double tolerance = 1e-8;         // a point is converged when ‖P(z) − z‖ / ‖z‖ is below this
  double initial_step = 0.02;
  double min_step = 1e-4;          // below this the branch is given up (the note says where)
  double max_step = 0.1;
  int max_points = 400;            // points per branch
  int max_corrector_iterations = 8;
  double jacobian_step = 1e-5;     // δ = jacobian_step · max(‖z‖, 1e-6) for ∂P/∂z; the same fraction of |to − from| for ∂P/∂p
  bool switch_period_doubling = true;  // follow the doubled branch from each period doubling
  int max_branches = 4;            // doubled branches followed at most
  double restart_jump = 0.01;      // after a stall, the orbit is sought again this far on (in u) …
  int max_restarts = 100;          // … at most this many times, and never past the range (only with a reseed function)
  int threads = 1;                 // for the Jacobian's columns
  const StopToken* stop = nullptr;
};

/// A converged point of a branch.
struct BranchPoint {
  int branch = 0;                  // 0: the branch started at `from`; 1, 2, …: restarted or doubled branches
  int period = 1;                  // M
  double parameter = 0;            // p
  Eigen::VectorXd z;               // the fixed point
  Eigen::VectorXd image;           // P^M(z) as evaluated there (z to the tolerance)
  std::vector<Multiplier> multipliers;  // eigenvalues of ∂P^M/∂z, largest magnitude first
  bool stable = false;             // every |μ| < 1
  double arclength = 0;            // along its branch, in the scaled unknowns
  double tangent_parameter = 0;    // du/ds at the point: its sign changes at a fold
  int corrector_iterations = 0;
  int jacobian_event_changes = 0;  // central-difference evaluations whose impacts or episodes differed
  OrbitMetrics metrics;
  // Kept to find and locate special points and to switch branches.
  Eigen::MatrixXd jacobian;        // ∂P^M/∂z
  Eigen::VectorXd parameter_derivative;  // ∂P^M/∂p
};

enum class SpecialKind {
  fold,              // the branch turns back in the parameter (a multiplier through +1)
  branch_point,      // a real multiplier through +1 while the branch goes on (a pitchfork)
  period_doubling,   // a real multiplier through −1
  neimark_sacker,    // a complex pair through the unit circle
  grazing,           // the impacts or episodes of one period change along the branch
};
const char* special_kind_name(SpecialKind kind);

/// A special point, located between points `before` and `before + 1` of branch `branch` (indices into
/// Continuation::points).
struct SpecialPoint {
  SpecialKind kind = SpecialKind::fold;
  int branch = 0;
  int before = 0;
  double parameter = 0;        // located by interpolation over the segment (see docs/continuation.md)
  Eigen::VectorXd z;
  Multiplier multiplier;       // the crossing multiplier where one crosses (interpolated)
  int doubled_branch = -1;     // period doubling: the branch followed from it (−1: none)
  std::string note;            // in words
};

struct BranchSummary {
  int branch = 0, period = 1;
  int points = 0;
  std::string start;           // how the branch began, in words
  std::string end;             // how it ended
};

/// An orbit found at p by other means than the continuation (a brute-force or shooting search from a
/// state near it), to restart from where a branch stalled.
struct Reseed {
  Eigen::VectorXd z;
  int period = 1;
  std::string note;  // how it was found
};
using ReseedFunction = std::function<std::optional<Reseed>(double p, const Eigen::VectorXd& z_near)>;

struct ContinuationResult {
  std::vector<BranchPoint> points;   // every branch's, in order
  std::vector<SpecialPoint> special;
  std::vector<BranchSummary> branches;
  int map_evaluations = 0;
  int revolutions = 0;               // applications of the one-revolution map in all
  int variational_jacobians = 0;     // Jacobians from a ParametrisedJacobian
  int difference_jacobians = 0;      // Jacobians by central differences of the map
  std::string jacobian_fallback;     // why the last ParametrisedJacobian gave none ("" when it always did)
  bool stopped = false;              // a stop request ended it
  std::optional<NumericalFailure> failure;  // the first evaluation that failed where no smaller step got round it
};

/// Progress after each converged point.
struct ContinuationProgress {
  int branch = 0, points = 0, map_evaluations = 0;
  double parameter = 0, u = 0;  // u: the scaled parameter, 0 at from, 1 at to
  bool stable = false;
};

/// Continues the fixed points of `map` from (z0, from) toward `to`, with period M = `period`. z0 need
/// not be converged: it is corrected at p = from first (when that fails, the result has no point and
/// its first branch's `end` says why). Where a branch stalls (no step down to min_step converges:
/// the map is not smooth there, or an evaluation fails) and `reseed` is given, the orbit is sought
/// again by it restart_jump further on and a new branch follows from there. Throws
/// std::invalid_argument for from == to or a non-finite bound, an empty z0 or a period < 1.
ContinuationResult continue_fixed_points(const ParametrisedMap& map, const Eigen::VectorXd& z0, double from, double to,
                                         int period, const ContinuationSettings& settings,
                                         const std::function<void(const ContinuationProgress&)>& on_point = {},
                                         const ReseedFunction& reseed = {},
                                         const ParametrisedJacobian& jacobian = {});

}  // namespace rotbeam
