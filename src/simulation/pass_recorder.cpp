#include "pass_recorder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace rotbeam {

namespace {
// Below this |y_t|/L the model's foreshortening stays close to the exact one (≈ 0.05 L at 0.3 L), so
// the tip is within reach and the distance is not computed.
constexpr double kReachCheckRatio = 0.3;

// The first time of the grid k·h after t [s]. A row written at k·h gives t/h a hair below k at
// times: the guard keeps it from naming t again.
double next_grid_time(double t, double h) { return h * (std::floor(t / h + 1e-9) + 1.0); }
}  // namespace

PassRecorder::PassRecorder(const System& system, const PassOptions& options, const PassControl& control,
                           PassResult& result)
    : system_(system),
      options_(options),
      control_(control),
      result_(result),
      ws_(system.beam.make_workspace()),
      tip_(system.beam.modes()),
      generalized_force_(system.beam.modes()),
      qdd_(system.beam.modes()),
      iq_(Eigen::VectorXd::Zero(system.beam.modes())),
      iqd_(Eigen::VectorXd::Zero(system.beam.modes())),
      bins_(options.bin_deg, system.beam.hub_motion().omega),
      deliveries_(control.sink && control.sink->wants_deliveries()) {
  row_.q.resize(system.beam.modes());
  row_.qd.resize(system.beam.modes());
  row_.t = NAN;  // no row written yet
}

bool PassRecorder::stop_requested(double t) {
  if (result_.failure) return true;
  if (control_.stop && control_.stop->stop_requested()) {
    fail(FailureKind::interrupted, t, "the run was interrupted (SIGINT/SIGTERM or a stop request); results up to here are kept");
    return true;
  }
  if (validity_breached_) {
    std::ostringstream s;
    s << "max |y_t|/L = " << validity_ratio_ << " exceeds simulation.deflection_warning_ratio = "
      << options_.deflection_warning_ratio
      << " (simulation.deflection_limit_is_error = true): beyond the quadratic foreshortening model";
    fail(FailureKind::validity, t, s.str());
    return true;
  }
  return false;
}

double PassRecorder::tip_y(double t, const Eigen::VectorXd& q) const {
  return tip_position(system_.beam, t, q).y();
}

void PassRecorder::emit(const PassEvent& e) {
  if (control_.sink)
    control_.sink->event(e);
  else
    result_.events.push_back(e);
}

double PassRecorder::hub_torque(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const ContactLoad& load) {
  // τ = dH_z/dt − (X_t F_Y − Y_t F_X): the hub's torque is the rate of the filament's angular momentum
  // less the moment of the contact force (SPEC §7); dH_z/dt in closed form from q̈ = M⁻¹(Q − Ψ).
  // `tip_` holds the kinematics at (t, q, q̇).
  const ContactLoad l = contact_load(system_.law.friction(), tip_, qd, load.lambda, load.slip, generalized_force_);
  acceleration(system_.beam, q, qd, l.lambda != 0.0 ? &generalized_force_ : nullptr, *ws_, qdd_);
  const double dh = system_.beam.angular_momentum_rate(q, qd, qdd_, *ws_);
  return dh - (tip_.X * l.force_y - tip_.Y * l.force_x);
}

void PassRecorder::track(double t, const Eigen::VectorXd& q) {
  const double ratio = system_.beam.tip_deflection(q) / system_.beam.beam_length();
  if (ratio > result_.summary.max_tip_deflection_ratio) result_.summary.max_tip_deflection_ratio = ratio;
  rev_max_ratio_ = std::max(rev_max_ratio_, ratio);
  // The deflection warning is the foreshortening model's (SPEC §10): the elastica's geometry is exact.
  const bool limited = !system_.beam.geometrically_exact();
  if (limited && options_.deflection_limit_is_error && ratio > options_.deflection_warning_ratio && !validity_breached_) {
    validity_breached_ = true;
    validity_ratio_ = ratio;
  }
  if (limited && ratio > options_.deflection_warning_ratio && result_.summary.validity == Validity::within)
    result_.summary.validity = Validity::edge;
  if (limited && !deflection_warned_ && ratio > options_.deflection_warning_ratio) {
    deflection_warned_ = true;
    std::ostringstream s;
    s << "tip deflection exceeds " << options_.deflection_warning_ratio
      << " of the length: the quadratic foreshortening model is at the edge of its validity (SPEC §10)";
    warn(t, q, s.str());
  }
  // An inextensible filament's tip cannot be farther than L from its clamp at (r_h, 0); where the
  // model puts it there, it has left its geometry (only possible at large deflection).
  if (!geometry_warned_ && ratio > kReachCheckRatio) {
    const double reach = tip_reach(system_.beam, q);
    if (reach > kReachLimit) {
      result_.summary.validity = Validity::outside;
      geometry_warned_ = true;
      std::ostringstream s;
      s.precision(3);
      s << "the tip is " << reach << " L from its clamp, farther than a filament of length L can reach: the model "
        << "has left its geometry and its results are not physical (SPEC §10)";
      warn(t, q, s.str());
      if (options_.deflection_limit_is_error && !validity_breached_) {
        validity_breached_ = true;
        validity_ratio_ = ratio;
      }
    }
  }
}

void PassRecorder::sample(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase,
                          const ContactLoad& load) {
  // One row per state: an event that forces a row where one was just written (the pre-impact state,
  // the pass's last state) gives no second, identical row.
  if (t == row_.t && phase == row_.phase && q == row_.q && qd == row_.qd && load.normal_force == row_.normal_force &&
      load.friction_force == row_.friction_force && load.lambda == row_.lambda)
    return;
  tip_kinematics(system_.beam, system_.surface, t, q, qd, tip_);
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
  const EnergyTerms e = system_.beam.energy(q, qd, *ws_);
  row_.jacobi = e.jacobi;
  energy_scale_ = std::max({energy_scale_, std::abs(e.jacobi), e.t2});
  row_.hub_torque = hub_torque(q, qd, load);
  if (control_.sink)
    control_.sink->row(row_);
  else
    result_.history.push_back(row_);
  next_near_t_ = options_.near_surface_interval_s > 0.0 ? next_grid_time(t, options_.near_surface_interval_s) : t;
  if (options_.output_interval_s <= 0.0) return;  // every accepted point is sampled
  next_sample_t_ = next_grid_time(t, options_.output_interval_s);
}

bool PassRecorder::near_surface(double t, const Eigen::VectorXd& q) {
  if (!(options_.near_surface_gap_m > 0.0)) return false;
  // free_rows_within and accept ask at the same point of free flight: the gap is computed once.
  if (t != gap_t_) {
    last_gap_ = gap(system_.beam, system_.surface, t, q);
    gap_t_ = t;
  }
  return last_gap_ > -options_.near_surface_gap_m;
}

void PassRecorder::rigid_turn(double t_to) {
  iq_.setZero();
  iqd_.setZero();
  // Nothing moves but the hub: a row every output.interval_s or every 0.1° of hub angle,
  // whichever is longer, draws the approach; near the surface, the near-surface interval.
  // The near-surface rows can be billions (a gap wider than the approach): the loop reports its
  // progress, and on a stop request finishes the approach at the far spacing (at most 900 rows), so
  // the history stays whole; the pass then stops at its first step after the impact.
  const double far = std::max(options_.output_interval_s, 0.1 * M_PI / 180.0 / system_.beam.hub_motion().omega);
  const auto started = std::chrono::steady_clock::now();
  auto next_report = started + std::chrono::milliseconds(250);
  bool stopping = false;
  double tk = last_t_;
  for (long rows = 1;; ++rows) {
    if ((rows & 1023) == 0 && !stopping) {
      stopping = control_.stop && control_.stop->stop_requested();
      const auto now = std::chrono::steady_clock::now();
      if (control_.on_progress && now >= next_report) {
        next_report = now + std::chrono::milliseconds(250);
        PassProgress p;
        p.theta_deg = system_.beam.theta(tk) * 180.0 / M_PI;
        p.start_deg = system_.beam.theta(0.0) * 180.0 / M_PI;
        p.end_deg = options_.end_angle_deg;
        p.elapsed_s = std::chrono::duration<double>(now - started).count();
        p.revolution = revolution_;
        p.revolutions = options_.revolutions;
        control_.on_progress(p);
      }
    }
    const double h = !stopping && near_surface(tk, iq_) && options_.near_surface_interval_s > 0.0
                         ? std::min(far, options_.near_surface_interval_s)
                         : far;
    tk = next_grid_time(tk, h);
    if (!(tk < t_to)) break;
    sample(tk, iq_, iqd_, Phase::free, ContactLoad{});
  }
}

void PassRecorder::free_rows_within(double t, const Eigen::VectorXd& q, Stepper& stepper) {
  // Rows inside the free step just taken, from the dense output, in time order: on the output grid
  // (k·output.interval_s, whatever the step: a step longer than the interval loses no row), and near
  // the surface on the finer grid of near_surface_interval_s.
  const double h = options_.near_surface_interval_s, interval = options_.output_interval_s;
  const double gap_before = last_gap_;  // at the step's start (near_surface below moves it to t)
  const bool near_rows = h > 0.0 && options_.near_surface_gap_m > 0.0 &&
                         (near_surface(t, q) || gap_before > -options_.near_surface_gap_m);
  const bool grid_rows = interval > 0.0;
  for (;;) {
    const double t_grid =
        grid_rows ? (next_sample_t_ > last_t_ ? next_sample_t_ : next_grid_time(last_t_, interval)) : INFINITY;
    const double t_near = near_rows ? std::max(next_near_t_, next_grid_time(last_t_, h)) : INFINITY;
    const double tk = std::min(t_grid, t_near);
    if (!(tk < t) || !(tk > last_t_)) return;  // none left inside the step (or below t's resolution)
    if (!stepper.interpolate(tk, iq_, iqd_)) return;
    sample(tk, iq_, iqd_, Phase::free, ContactLoad{});
  }
}

void section_state(const BeamModel& beam, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Eigen::VectorXd& z) {
  const double L = beam.beam_length(), omega = beam.hub_motion().omega;
  z.resize(q.size() + qd.size());
  z << q / L, qd / (omega * L);
}

Eigen::VectorXd section_state(const BeamModel& beam, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  Eigen::VectorXd z;
  section_state(beam, q, qd, z);
  return z;
}

double section_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const double scale = std::max(a.norm(), b.norm());
  return scale > 0.0 ? (a - b).norm() / scale : 0.0;
}

void PassRecorder::start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  next_sample_t_ = t;
  last_t_ = t;
  t_start_ = t;
  const EnergyTerms e = system_.beam.energy(q, qd, *ws_);
  h_start_ = e.jacobi;
  energy_start_ = e.kinetic + e.potential + contact_energy(t, q);
  momentum_start_ = e.angular_momentum;
  last_h_ = e.angular_momentum;
  energy_scale_ = std::abs(h_start_);
  section_state(system_.beam, q, qd, section_prev_);
  section_.resize(section_prev_.size());
  if (options_.revolutions > 0) open_revolution(t, q, qd);
  track(t, q);
  sample(t, q, qd, Phase::free, ContactLoad{});
}

bool PassRecorder::impacts_exhausted(double t) {
  const int counted = result_.summary.impacts - (revolution_ > 0 ? mark_.impacts : 0);
  if (counted < options_.max_impacts) return false;
  fail(FailureKind::impacts, t,
       "more than " + std::to_string(options_.max_impacts) + (options_.max_impacts == 1 ? " impact" : " impacts") +
           (revolution_ > 0 ? " in one revolution" : " in one pass") + " (simulation.max_impacts = " +
           std::to_string(options_.max_impacts) +
           "): impacts accumulate (raise simulation.max_impacts, or impact.plastic_below_m_s to end a bouncing sequence)");
  return true;
}

double PassRecorder::relative_angle_deg(double t) const {
  // SPEC §11: relative to the revolution, in (−180°, 180°], 0° at the surface's deepest point.
  double a = std::remainder(system_.beam.theta(t) - system_.surface.deepest_angle(), 2.0 * M_PI) * 180.0 / M_PI;
  if (a <= -180.0) a += 360.0;
  return a;
}

void PassRecorder::note_force(double normal_force) {
  result_.summary.peak_normal_force_n = std::max(result_.summary.peak_normal_force_n, normal_force);
  rev_peak_force_ = std::max(rev_peak_force_, normal_force);
}

void PassRecorder::open_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  const PassSummary& s = result_.summary;
  const EnergyTerms e = system_.beam.energy(q, qd, *ws_);
  ++revolution_;
  revolution_open_ = true;
  mark_.t = t;
  mark_.energy = e.kinetic + e.potential + contact_energy(t, q);
  mark_.momentum = e.angular_momentum;
  mark_.ledger = s.ledger;
  mark_.contact_time = s.contact_time_s;
  mark_.impacts = s.impacts;
  mark_.episodes = s.contact_episodes;
  mark_.history_rows = result_.history.size();
  mark_.events = result_.events.size();
  if (!control_.sink) kept_marks_.push_back(mark_);
  bins_.clear();
  rev_first_impact_deg_ = rev_last_separation_deg_ = NAN;
  rev_peak_force_ = 0.0;
  rev_max_ratio_ = system_.beam.tip_deflection(q) / system_.beam.beam_length();
}

bool PassRecorder::close_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, bool complete) {
  const PassSummary& s = result_.summary;
  if (complete) {
    complete_bins_ = bins_.table();
    complete_peaks_ = bins_.peaks();
  }
  const EnergyTerms e = system_.beam.energy(q, qd, *ws_);
  const double omega = system_.beam.hub_motion().omega;
  RevolutionRecord r;
  r.revolution = revolution_;
  r.complete = complete;
  r.t_start = mark_.t;
  r.t_end = t;
  r.impacts = s.impacts - mark_.impacts;
  r.contact_episodes = s.contact_episodes - mark_.episodes;
  r.first_impact_deg = rev_first_impact_deg_;
  r.last_separation_deg = rev_last_separation_deg_;
  static_cast<LedgerValues&>(r.ledger) = s.ledger - mark_.ledger;
  const double moment = s.ledger[LedgerTerm::contact_moment] - mark_.ledger[LedgerTerm::contact_moment];
  r.ledger[LedgerTerm::hub_work] = omega * (e.angular_momentum - mark_.momentum - moment);
  r.ledger.energy_change_j = e.kinetic + e.potential + contact_energy(t, q) - mark_.energy;
  const double dt = t - mark_.t;
  const double hub_work = r.ledger[LedgerTerm::hub_work];
  r.mean_hub_torque_n_m = dt > 0.0 ? hub_work / (omega * dt) : 0.0;
  r.mean_hub_power_w = dt > 0.0 ? hub_work / dt : 0.0;
  r.max_tip_deflection_ratio = rev_max_ratio_;
  r.contact_time_s = s.contact_time_s - mark_.contact_time;
  r.peak_normal_force_n = rev_peak_force_;
  r.q = q;
  r.qd = qd;
  bool steady = false;
  if (complete) {
    section_state(system_.beam, q, qd, section_);
    auto distance = [this](const Eigen::VectorXd& z) { return rotbeam::section_distance(section_, z); };
    r.section_distance = distance(section_prev_);
    // A steady state may repeat after p revolutions (a subharmonic orbit): the earlier sections.
    SteadyState& st = result_.summary.steady_state;
    int period = r.section_distance < options_.steady_tolerance ? 1 : 0;
    for (std::size_t p = 2; period == 0 && p <= older_sections_.size() + 1; ++p)
      if (distance(older_sections_[older_sections_.size() - (p - 1)]) < options_.steady_tolerance)
        period = static_cast<int>(p);
    older_sections_.push_back(section_prev_);
    if (static_cast<int>(older_sections_.size()) > kMaxSteadyPeriod - 1) older_sections_.erase(older_sections_.begin());
    section_prev_ = section_;
    last_distance_ = r.section_distance;
    last_complete_ = r;
    have_complete_ = true;
    if (options_.until_steady && period > 0 && !st.reached) {
      st.reached = true;
      st.after_revolutions = r.revolution;
      st.period_revolutions = period;
      steady = true;
    }
  }
  if (control_.sink)
    control_.sink->revolution(r);
  else
    result_.revolutions.push_back(r);
  revolution_open_ = false;
  return steady;
}

void PassRecorder::drop_old_revolutions() {
  const int keep = options_.history_revolutions;
  auto& intervals = result_.summary.contact_intervals;
  if (keep > 0) {
    const int oldest = revolution_ - keep + 1;  // the oldest revolution kept (the open one counts)
    intervals.erase(std::remove_if(intervals.begin(), intervals.end(),
                                   [oldest](const ContactInterval& c) { return c.revolution < oldest; }),
                    intervals.end());
  }
  if (control_.sink || keep <= 0 || static_cast<int>(kept_marks_.size()) <= keep) return;
  const RevolutionMark& first_kept = kept_marks_[kept_marks_.size() - keep];
  const std::size_t rows = first_kept.history_rows, events = first_kept.events;
  result_.history.erase(result_.history.begin(), result_.history.begin() + static_cast<std::ptrdiff_t>(rows));
  result_.events.erase(result_.events.begin(), result_.events.begin() + static_cast<std::ptrdiff_t>(events));
  kept_marks_.erase(kept_marks_.begin(), kept_marks_.end() - keep);
  for (RevolutionMark& m : kept_marks_) {
    m.history_rows -= rows;
    m.events -= events;
  }
}

bool PassRecorder::end_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  if (close_revolution(t, q, qd, true)) return true;
  open_revolution(t, q, qd);
  drop_old_revolutions();
  return false;
}

void PassRecorder::accept(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase,
                          const ContactLoad& load, const StepIntegrals& in, bool force_sample) {
  PassSummary& s = result_.summary;
  s.ledger += in.integral;
  if (deliveries_) {
    // The hub's angular impulse over the step: ΔH_z less the contact force's angular impulse.
    const double h = system_.beam.energy(q, qd, *ws_).angular_momentum;
    MomentumDelivery d;
    d.from_deg = relative_angle_deg(last_t_);
    d.span_deg = system_.beam.hub_motion().omega * (t - last_t_) * 180.0 / M_PI;
    d.hub_angular_impulse_n_m_s = h - last_h_;
    if (phase != Phase::free) {
      d.normal_n_s = in.integral[LedgerTerm::normal_impulse];
      d.tangential_n_s = -in.integral[LedgerTerm::tangential_impulse];  // on the surface
      d.hub_angular_impulse_n_m_s -= in.integral[LedgerTerm::contact_moment];
      d.along_m = tip_y(t, q);
    }
    last_h_ = h;
    control_.sink->delivery(d);
  }
  if (phase != Phase::free) {
    // The surface receives the opposite of friction's impulse on the tip.
    const double omega = system_.beam.hub_motion().omega;
    bins_.add_spread(relative_angle_deg(last_t_), omega * (t - last_t_) * 180.0 / M_PI,
                     in.integral[LedgerTerm::normal_impulse], -in.integral[LedgerTerm::tangential_impulse]);
    s.contact_time_s += t - last_t_;
    normal_time_integral_ += in.integral[LedgerTerm::normal_impulse];
    note_force(std::max(load.normal_force, in.peak_normal_force));
  }
  last_t_ = t;
  track(t, q);
  const bool near = near_surface(t, q);
  if (force_sample || t >= next_sample_t_ || (near && t >= next_near_t_)) sample(t, q, qd, phase, load);
}

void PassRecorder::impact(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd_before,
                          const Eigen::VectorXd& qd_after, const ImpactResult& r) {
  PassSummary& s = result_.summary;
  ++s.impacts;
  if (r.restitution == 0.0) ++s.plastic_impacts;
  const double theta = system_.beam.theta(t);
  const double theta_deg = theta * 180.0 / M_PI;
  if (s.impacts == 1) s.first_impact_deg = theta_deg;
  s.last_separation_deg = theta_deg;
  if (revolution_ > 0) {
    if (s.impacts - mark_.impacts == 1) rev_first_impact_deg_ = relative_angle_deg(t);
    rev_last_separation_deg_ = relative_angle_deg(t);
  }
  bins_.add_impulse(relative_angle_deg(t), std::abs(r.impulse), -r.tangential_impulse);  // on the surface
  impact_jumps_ += r.delta_t2;
  // The hub's work during the impact: ω times its angular impulse, ΔH_z less the moment of the contact
  // impulse (q is unchanged, so ΔH_z = Δ(p(q)·q̇)).
  const Eigen::Vector2d at = tip_position(system_.beam, t, q);
  const double impulse_moment = at.x() * r.impulse_y - at.y() * r.impulse_x;
  const double dh = system_.beam.energy(q, qd_after, *ws_).angular_momentum -
                    system_.beam.energy(q, qd_before, *ws_).angular_momentum;
  const double hub_work = system_.beam.hub_motion().omega * (dh - impulse_moment);
  LedgerValues jump;
  jump[LedgerTerm::normal_impulse] = std::abs(r.impulse);
  jump[LedgerTerm::tangential_impulse] = r.tangential_impulse;
  jump[LedgerTerm::contact_moment] = impulse_moment;
  // The impulse's work less a moving surface's part (which is the surface's work, not a loss).
  jump[LedgerTerm::impact_loss] = r.contact_work - r.surface_work;
  jump[LedgerTerm::surface_work] = r.surface_work;
  s.ledger += jump;
  if (deliveries_) {
    const double h_after = system_.beam.energy(q, qd_after, *ws_).angular_momentum;
    MomentumDelivery d;
    d.from_deg = relative_angle_deg(t);
    d.normal_n_s = std::abs(r.impulse);
    d.tangential_n_s = -r.tangential_impulse;
    d.hub_angular_impulse_n_m_s = h_after - last_h_ - impulse_moment;  // = dh − impulse_moment when at the accepted point
    d.along_m = tip_y(t, q);
    d.impact = true;
    last_h_ = h_after;
    control_.sink->delivery(d);
  }
  s.hub_impulsive_work_j += hub_work;
  sample(t, q, qd_before, Phase::free, ContactLoad{});
  PassEvent e;
  e.t = t;
  e.theta = theta;
  e.y_tip = tip_y(t, q);
  e.kind = EventKind::impact;
  e.vx_before = r.vx_before;
  e.vx_after = r.vx_after;
  e.restitution = r.restitution;
  e.impulse = r.impulse;
  e.hub_work = hub_work;
  e.detail = r.restitution == 0.0 ? "plastic" : "";
  emit(e);
  sample(t, q, qd_after, Phase::free, ContactLoad{});
  last_t_ = t;
}

void PassRecorder::contact_start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                 const ContactLoad& load, const std::string& detail) {
  in_episode_ = true;
  episode_t0_ = t;
  episode_theta0_ = system_.beam.theta(t);
  episode_y0_ = tip_y(t, q);
  event(EventKind::contact_start, t, q, detail);
  // The force right after the plastic impact that opens an episode is often the episode's largest.
  note_force(load.normal_force);
  sample(t, q, qd, Phase::contact, load);
  last_t_ = t;
}

void PassRecorder::compliant_touch(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                   const ContactLoad& load, const std::string& detail) {
  PassSummary& s = result_.summary;
  if (!touched_) s.first_impact_deg = system_.beam.theta(t) * 180.0 / M_PI;
  touched_ = true;
  if (revolution_ > 0 && std::isnan(rev_first_impact_deg_)) rev_first_impact_deg_ = relative_angle_deg(t);
  contact_start(t, q, qd, load, detail);
}

double PassRecorder::contact_energy(double t, const Eigen::VectorXd& q) const {
  return system_.law.stored_energy(system_, t, q);
}

void PassRecorder::contact_end(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                               const std::string& detail) {
  in_episode_ = false;
  if (t > episode_t0_) {
    PassSummary& s = result_.summary;
    ++s.contact_episodes;
    s.contact_intervals.push_back({episode_t0_, t, episode_theta0_, system_.beam.theta(t), episode_y0_, tip_y(t, q),
                                   std::max(revolution_, 1)});
    s.last_separation_deg = system_.beam.theta(t) * 180.0 / M_PI;
    if (revolution_ > 0) rev_last_separation_deg_ = relative_angle_deg(t);
  }
  event(EventKind::contact_end, t, q, detail);
  sample(t, q, qd, Phase::free, ContactLoad{});
  last_t_ = t;
}

void PassRecorder::event(EventKind kind, double t, const Eigen::VectorXd& q, const std::string& detail) {
  PassEvent e;
  e.t = t;
  e.theta = system_.beam.theta(t);
  e.y_tip = tip_y(t, q);
  e.kind = kind;
  e.detail = detail;
  emit(e);
}

void PassRecorder::warn(double t, const Eigen::VectorXd& q, const std::string& message) {
  for (const std::string& w : result_.summary.warnings)
    if (w == message) return;
  result_.summary.warnings.push_back(message);
  event(EventKind::warning, t, q, message);
}

void PassRecorder::fail(FailureKind kind, double t, const std::string& message) {
  NumericalFailure f;
  f.kind = kind;
  f.t = t;
  f.theta = system_.beam.theta(t);
  f.message = message;
  result_.failure = f;
  PassEvent e;
  e.t = t;
  e.theta = f.theta;
  e.y_tip = NAN;  // the failure's instant may lie inside a step, where the state is not known
  e.kind = EventKind::failure;
  e.detail = std::string(failure_name(kind)) + ": " + message;
  emit(e);
}

void PassRecorder::finish(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase,
                          const StepperStatistics& statistics) {
  if (in_episode_) {
    if (!result_.failure) warn(t, q, "the tip is still in contact at the end angle");
    contact_end(t, q, qd, "end of the pass");
  } else {
    sample(t, q, qd, phase, ContactLoad{});  // outside an episode there is no contact load
  }
  PassSummary& s = result_.summary;
  s.steps = statistics.steps;
  s.rhs_evaluations = statistics.rhs_evaluations;
  s.corrector_iterations = statistics.corrector_iterations;
  s.corrector_iterations_max = statistics.corrector_iterations_max;
  s.mean_normal_force_n = s.contact_time_s > 0 ? normal_time_integral_ / s.contact_time_s : 0.0;
  const EnergyTerms e = system_.beam.energy(q, qd, *ws_);
  energy_scale_ = std::max({energy_scale_, std::abs(e.jacobi), e.t2});
  s.energy_audit_residual = std::abs(e.jacobi - h_start_ - s.ledger[LedgerTerm::contact_work] -
                                     s.ledger[LedgerTerm::damping_work] - impact_jumps_) /
                            energy_scale_;
  // The hub's work from the angular-momentum balance: dH_z/dt = τ + (R × F)_z, with impulses at impacts.
  s.ledger[LedgerTerm::hub_work] = system_.beam.hub_motion().omega *
                                   (e.angular_momentum - momentum_start_ - s.ledger[LedgerTerm::contact_moment]);
  s.ledger.energy_change_j = e.kinetic + e.potential + contact_energy(t, q) - energy_start_;
  result_.final_t = t;
  result_.final_q = q;
  result_.final_qd = qd;
  const double omega = system_.beam.hub_motion().omega;
  if (options_.revolutions > 0) {
    if (revolution_open_) {
      const double t_end = options_.revolutions * 2.0 * M_PI / omega;
      close_revolution(t, q, qd, !result_.failure && t >= t_end * (1.0 - 1e-12));
    }
    s.revolutions = have_complete_ ? last_complete_.revolution : 0;
    if (have_complete_) s.last_revolution = last_complete_;
    if (have_complete_) {
      s.mean_hub_torque_n_m = last_complete_.mean_hub_torque_n_m;
      s.mean_hub_power_w = last_complete_.mean_hub_power_w;
    }
    SteadyState& st = s.steady_state;
    st.sought = options_.until_steady;
    st.tolerance = options_.steady_tolerance;
    st.method = options_.steady_method;
    st.final_distance = last_distance_;
    if (st.sought && st.method == SteadyMethod::brute_force) {
      std::ostringstream m;
      if (st.reached)
        m << "reached after " << st.after_revolutions << (st.after_revolutions == 1 ? " revolution, " : " revolutions, ")
          << (st.period_revolutions == 1 ? std::string("periodic every revolution")
                                         : "periodic every " + std::to_string(st.period_revolutions) + " revolutions")
          << " (section distance over the period < " << options_.steady_tolerance << ")";
      else if (result_.failure)
        m << "not reached: the run stopped in revolution " << revolution_;
      else if (options_.revolutions == 1)
        m << "not reached within 1 revolution (its section compared with the start only: distance " << last_distance_
          << ", tolerance " << options_.steady_tolerance << ")";
      else
        m << "not reached within " << options_.revolutions << " revolutions (section distance " << last_distance_
          << ", tolerance " << options_.steady_tolerance << ")";
      st.note = m.str();
      if (!st.reached && !result_.failure) warn(t, q, "no steady state: " + st.note);
    }
  } else if (t > t_start_) {
    // One pass: the means over the pass.
    s.mean_hub_torque_n_m = s.ledger[LedgerTerm::hub_work] / (omega * (t - t_start_));
    s.mean_hub_power_w = s.ledger[LedgerTerm::hub_work] / (t - t_start_);
  }
  if (options_.revolutions > 0 && have_complete_) {
    result_.force_bins = complete_bins_;
    s.binned_force = complete_peaks_;
  } else {
    result_.force_bins = bins_.table();
    s.binned_force = bins_.peaks();
  }
  event(EventKind::end, t, q, "");
}

}  // namespace rotbeam
