#include "history_sampler.hpp"

#include "rotbeam/sample_grid.hpp"
#include "rotbeam/surface.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace rotbeam {

namespace {
// Rows written between two looks at the stop request in the loops that write many rows per step.
constexpr long kRowsPerStopCheck = 1024;
}  // namespace

HistorySampler::HistorySampler(PassContext& context)
    : ctx_(context),
      ws_(context.system.beam.make_workspace()),
      tip_(context.system.beam.modes()),
      generalized_force_(context.system.beam.modes()),
      qdd_(context.system.beam.modes()),
      iq_(Eigen::VectorXd::Zero(context.system.beam.modes())),
      iqd_(Eigen::VectorXd::Zero(context.system.beam.modes())) {
  row_.q.resize(context.system.beam.modes());
  row_.qd.resize(context.system.beam.modes());
  row_.t = NAN;  // no row written yet
}

void HistorySampler::note_energy(double jacobi, double t2) {
  energy_scale_ = std::max({energy_scale_, std::abs(jacobi), t2});
}

double HistorySampler::hub_torque(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const ContactLoad& load) {
  // τ = dH_z/dt − (X_t F_Y − Y_t F_X): the hub's torque is the rate of the filament's angular momentum
  // less the moment of the contact force (docs/model.md §7); dH_z/dt in closed form from q̈ = M⁻¹(Q − Ψ).
  // `tip_` holds the kinematics at (t, q, q̇).
  const System& sys = ctx_.system;
  const ContactLoad l = contact_load(sys.law.friction(), tip_, qd, load.lambda, load.slip, generalized_force_);
  acceleration(sys.beam, q, qd, l.lambda != 0.0 ? &generalized_force_ : nullptr, *ws_, qdd_);
  const double dh = sys.beam.angular_momentum_rate(q, qd, qdd_, *ws_);
  return dh - (tip_.X * l.force_y - tip_.Y * l.force_x);
}

void HistorySampler::sample(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase,
                            const ContactLoad& load) {
  const System& sys = ctx_.system;
  const PassOptions& o = ctx_.options;
  // The grids move past t whether or not a row is written here.
  next_near_t_ = o.near_surface_interval_s > 0.0 ? next_grid_time(t, o.near_surface_interval_s) : t;
  if (o.output_interval_s > 0.0) next_sample_t_ = next_grid_time(t, o.output_interval_s);
  // One row per state: an event that forces a row where one was just written (the pre-impact state,
  // the pass's last state) gives no second, identical row.
  if (t == row_.t && phase == row_.phase && q == row_.q && qd == row_.qd && load.normal_force == row_.normal_force &&
      load.friction_force == row_.friction_force && load.lambda == row_.lambda)
    return;
  tip_kinematics(sys.beam, sys.surface, t, q, qd, tip_);
  row_.t = t;
  row_.theta = tip_.theta;
  row_.phase = phase;
  row_.x_tip = tip_.X;
  row_.y_tip = tip_.Y;
  row_.gap = tip_.gap;
  row_.vx = tip_.VX;
  row_.vy = tip_.VY;
  row_.normal_force = load.normal_force;
  row_.friction_force = load.friction_force;
  row_.lambda = load.lambda;
  row_.q = q;
  row_.qd = qd;
  const EnergyTerms e = sys.beam.energy(q, qd, *ws_);
  row_.jacobi = e.jacobi;
  note_energy(e.jacobi, e.t2);
  row_.hub_torque = hub_torque(q, qd, load);
  ctx_.sink.row(row_);
}

bool HistorySampler::near_surface(double t, const Eigen::VectorXd& q) {
  if (!(ctx_.options.near_surface_gap_m > 0.0)) return false;
  // free_rows_within and step ask at the same point of free flight: the gap is computed once.
  if (t != gap_t_) {
    last_gap_ = gap(ctx_.system.beam, ctx_.system.surface, t, q);
    gap_t_ = t;
  }
  return last_gap_ > -ctx_.options.near_surface_gap_m;
}

void HistorySampler::start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  next_sample_t_ = t;
  energy_scale_ = std::abs(ctx_.system.beam.energy(q, qd, *ws_).jacobi);
  sample(t, q, qd, Phase::free, ContactLoad{});
}

void HistorySampler::step(const StepView& v) {
  const bool near = near_surface(v.t, v.q);
  if (v.force_row || v.t >= next_sample_t_ || (near && v.t >= next_near_t_)) sample(v.t, v.q, v.qd, v.phase, v.load);
}

void HistorySampler::before_impact(const ImpactView& v) { sample(v.t, v.q, v.qd_before, Phase::free, ContactLoad{}); }

void HistorySampler::after_impact(const ImpactView& v) { sample(v.t, v.q, v.qd_after, Phase::free, ContactLoad{}); }

void HistorySampler::rigid_turn(double t_from, double t_to) {
  const System& sys = ctx_.system;
  const PassOptions& o = ctx_.options;
  sys.beam.rest_state(iq_);
  iqd_.setZero();
  // Nothing moves but the hub: a row every output.interval_s or every 0.1° of hub angle,
  // whichever is longer, draws the approach; near the surface, the near-surface interval.
  // The near-surface rows can be billions (a gap wider than the approach): the loop reports its
  // progress, and on a stop request finishes the approach at the far spacing (at most 900 rows), so
  // the history stays whole; the pass then stops at its first step after the impact.
  const double far = std::max(o.output_interval_s, 0.1 * M_PI / 180.0 / sys.beam.hub_motion().omega);
  const auto started = std::chrono::steady_clock::now();
  auto next_report = started + std::chrono::milliseconds(250);
  bool stopping = false;
  double tk = t_from;
  for (long rows = 1;; ++rows) {
    if (rows % kRowsPerStopCheck == 0 && !stopping) {
      stopping = ctx_.control.stop && ctx_.control.stop->stop_requested();
      const auto now = std::chrono::steady_clock::now();
      if (ctx_.control.on_progress && now >= next_report) {
        next_report = now + std::chrono::milliseconds(250);
        PassProgress p;
        p.theta_deg = sys.beam.theta(tk) * 180.0 / M_PI;
        p.start_deg = sys.beam.theta(0.0) * 180.0 / M_PI;
        p.end_deg = o.end_angle_deg;
        p.elapsed_s = std::chrono::duration<double>(now - started).count();
        p.revolution = ctx_.revolution;
        p.revolutions = o.revolutions;
        ctx_.control.on_progress(p);
      }
    }
    const double h =
        !stopping && near_surface(tk, iq_) && o.near_surface_interval_s > 0.0 ? std::min(far, o.near_surface_interval_s) : far;
    tk = next_grid_time(tk, h);
    if (!(tk < t_to)) break;
    sample(tk, iq_, iqd_, Phase::free, ContactLoad{});
  }
}

void HistorySampler::free_rows_within(double t_last, double t, const Eigen::VectorXd& q, Stepper& stepper) {
  // Rows inside the free step just taken, from the dense output, in time order: on the output grid
  // (k·output.interval_s, whatever the step: a step longer than the interval loses no row), and near
  // the surface on the finer grid of near_surface_interval_s.
  const PassOptions& o = ctx_.options;
  const double h = o.near_surface_interval_s, interval = o.output_interval_s;
  const double gap_before = last_gap_;  // at the step's start (near_surface below moves it to t)
  const bool near_rows = h > 0.0 && o.near_surface_gap_m > 0.0 && (near_surface(t, q) || gap_before > -o.near_surface_gap_m);
  const bool grid_rows = interval > 0.0;
  for (long rows = 1;; ++rows) {
    // Millions of rows can fall inside one step (a fine near-surface grid): a stop request ends them
    // here, and the pass at its next step.
    if (rows % kRowsPerStopCheck == 0 && ctx_.control.stop && ctx_.control.stop->stop_requested()) return;
    const double t_grid =
        grid_rows ? (next_sample_t_ > t_last ? next_sample_t_ : next_grid_time(t_last, interval)) : INFINITY;
    const double t_near = near_rows ? std::max(next_near_t_, next_grid_time(t_last, h)) : INFINITY;
    const double tk = std::min(t_grid, t_near);
    if (!(tk < t) || !(tk > t_last)) return;  // none left inside the step (or below t's resolution)
    if (!stepper.interpolate(tk, iq_, iqd_)) return;
    sample(tk, iq_, iqd_, Phase::free, ContactLoad{});
  }
}

}  // namespace rotbeam
