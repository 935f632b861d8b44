// The history rows of a pass (docs/model.md §7, history.csv): one row at the start and at every event, rows
// on the grid of output.interval_s, and, while the tip is within output.near_surface_gap_m of the
// surface, on the finer grid of output.near_surface_interval_s — inside free-flight steps from the
// stepper's dense output, so that a step longer than the interval loses no row.
#pragma once

#include "pass_observer.hpp"

#include <memory>

namespace rotbeam {

class HistorySampler final : public PassObserver {
public:
  explicit HistorySampler(PassContext& context);

  void start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;
  void step(const StepView& v) override;
  /// The rows of an impact: the state before it and after it (around its event).
  void before_impact(const ImpactView& v);
  void after_impact(const ImpactView& v);

  /// A row at (t, q, q̇) in `phase` with `load` (none where the previous row was the same state).
  void sample(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase, const ContactLoad& load);
  /// The rows of a rigid start's turn (q = q̇ = 0) from t_from to t_to, where the tip reaches the
  /// surface: every output.interval_s or every 0.1° of hub angle, whichever is longer (near the
  /// surface, every output.near_surface_interval_s); progress and stop requests are seen.
  void rigid_turn(double t_from, double t_to);
  /// Free flight reached t (state q) over the step `stepper` just took from t_last: the rows strictly
  /// inside the step from the stepper's dense output. A stepper without dense output gives none.
  void free_rows_within(double t_last, double t, const Eigen::VectorXd& q, Stepper& stepper);
  /// The largest |h| and T2 of the rows written [J]: the energy audit's scale.
  double energy_scale() const { return energy_scale_; }
  void note_energy(double jacobi, double t2);

private:
  // True when the tip at (t, q) is within output.near_surface_gap_m of the surface (remembers the gap).
  bool near_surface(double t, const Eigen::VectorXd& q);
  double hub_torque(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const ContactLoad& load);

  PassContext& ctx_;
  std::unique_ptr<BeamWorkspace> ws_;
  TipKinematics tip_;
  HistoryRow row_;
  Eigen::VectorXd generalized_force_, qdd_;
  Eigen::VectorXd iq_, iqd_;            // interpolated or rigid-turn states (scratch)
  double next_sample_t_ = 0;
  double next_near_t_ = 0;              // the next row time on the near-surface grid [s]
  double last_gap_ = -INFINITY;         // the gap at the last point asked about [m]
  double gap_t_ = NAN;                  // … and its time [s]
  double energy_scale_ = 0;
};

}  // namespace rotbeam
