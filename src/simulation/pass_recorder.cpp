#include "pass_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rotbeam {

namespace {
constexpr double kReachLimit = 1.01;  // tip-to-clamp distance / L beyond which the geometry is impossible
// Below this |y_t|/L the model's foreshortening stays close to the exact one (≈ 0.05 L at 0.3 L), so
// the tip is within reach and the distance is not computed.
constexpr double kReachCheckRatio = 0.3;
}  // namespace

const char* phase_name(Phase p) {
  switch (p) {
    case Phase::free: return "free";
    case Phase::contact: return "contact";
    case Phase::stick: return "stick";
  }
  return "?";
}

PassRecorder::PassRecorder(const System& system, const PassOptions& options, const PassControl& control,
                           PassResult& result)
    : system_(system),
      options_(options),
      control_(control),
      result_(result),
      ws_(system.beam.make_workspace()),
      tip_(system.beam.modes()),
      generalized_force_(system.beam.modes()),
      qdd_(system.beam.modes()) {
  row_.q.resize(system.beam.modes());
  row_.qd.resize(system.beam.modes());
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
  const ContactLoad l = contact_load(system_.law.friction, tip_, qd, load.lambda, load.slip, generalized_force_);
  acceleration(system_.beam, q, qd, l.lambda != 0.0 ? &generalized_force_ : nullptr, *ws_, qdd_);
  const double dh = system_.beam.angular_momentum_rate(q, qd, qdd_, *ws_);
  return dh - (tip_.X * l.force_y - tip_.Y * l.force_x);
}

void PassRecorder::track(double t, const Eigen::VectorXd& q) {
  const double ratio = system_.beam.tip_deflection(q) / system_.beam.beam_length();
  if (ratio > result_.summary.max_tip_deflection_ratio) result_.summary.max_tip_deflection_ratio = ratio;
  if (options_.deflection_limit_is_error && ratio > options_.deflection_warning_ratio && !validity_breached_) {
    validity_breached_ = true;
    validity_ratio_ = ratio;
  }
  if (!deflection_warned_ && ratio > options_.deflection_warning_ratio) {
    deflection_warned_ = true;
    std::ostringstream s;
    s << "tip deflection exceeds " << options_.deflection_warning_ratio
      << " of the length: the quadratic foreshortening model is at the edge of its validity (SPEC §10)";
    warn(t, q, s.str());
  }
  // An inextensible filament's tip cannot be farther than L from its clamp at (r_h, 0); where the
  // model puts it there, it has left its geometry (only possible at large deflection).
  if (!geometry_warned_ && ratio > kReachCheckRatio) {
    const Eigen::Vector2d r = system_.beam.tip_position(q);
    const double L = system_.beam.beam_length();
    const double reach = std::hypot(r.x() - (system_.beam.tip_radius() - L), r.y()) / L;
    if (reach > kReachLimit) {
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
  if (options_.output_interval_s <= 0.0) return;  // every accepted point is sampled
  next_sample_t_ = options_.output_interval_s * (std::floor(t / options_.output_interval_s) + 1.0);
}

void PassRecorder::start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  next_sample_t_ = t;
  last_t_ = t;
  const EnergyTerms e = system_.beam.energy(q, qd, *ws_);
  h_start_ = e.jacobi;
  energy_start_ = e.kinetic + e.potential;
  momentum_start_ = e.angular_momentum;
  energy_scale_ = std::abs(h_start_);
  track(t, q);
  sample(t, q, qd, Phase::free, ContactLoad{});
}

bool PassRecorder::impacts_exhausted(double t) {
  if (result_.summary.impacts < options_.max_impacts) return false;
  fail(FailureKind::impacts, t,
       "more than " + std::to_string(options_.max_impacts) +
           " impacts in one pass: impacts accumulate (raise impact.plastic_below_m_s)");
  return true;
}

void PassRecorder::accept(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase,
                          const ContactLoad& load, const StepIntegrals& in, bool force_sample) {
  PassSummary& s = result_.summary;
  s.damping_work_j += in.damping_work;
  if (phase != Phase::free) {
    s.contact_time_s += t - last_t_;
    normal_time_integral_ += in.normal_impulse;
    s.friction_work_j += in.friction_work;
    work_ += in.work;
    contact_moment_ += in.contact_moment;
    s.peak_normal_force_n = std::max({s.peak_normal_force_n, load.normal_force, in.peak_normal_force});
  }
  last_t_ = t;
  track(t, q);
  if (force_sample || t >= next_sample_t_) sample(t, q, qd, phase, load);
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
  s.normal_impulse_n_s += std::abs(r.impulse);
  impact_jumps_ += r.delta_t2;
  // The hub's work during the impact: ω times its angular impulse, ΔH_z less the moment of the contact
  // impulse (q is unchanged, so ΔH_z = Δ(p(q)·q̇)).
  const Eigen::Vector2d at = tip_position(system_.beam, t, q);
  const double impulse_moment = at.x() * r.impulse_y - at.y() * r.impulse_x;
  const double dh = system_.beam.energy(q, qd_after, *ws_).angular_momentum -
                    system_.beam.energy(q, qd_before, *ws_).angular_momentum;
  const double hub_work = system_.beam.hub_motion().omega * (dh - impulse_moment);
  impulse_moment_ += impulse_moment;
  s.hub_impulsive_work_j += hub_work;
  s.impact_loss_j += r.contact_work;
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
  result_.summary.peak_normal_force_n = std::max(result_.summary.peak_normal_force_n, load.normal_force);
  sample(t, q, qd, Phase::contact, load);
  last_t_ = t;
}

void PassRecorder::contact_end(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                               const std::string& detail) {
  in_episode_ = false;
  if (t > episode_t0_) {
    PassSummary& s = result_.summary;
    ++s.contact_episodes;
    s.contact_intervals.push_back({episode_t0_, t, episode_theta0_, system_.beam.theta(t), episode_y0_, tip_y(t, q)});
    s.last_separation_deg = system_.beam.theta(t) * 180.0 / M_PI;
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
  s.normal_impulse_n_s += normal_time_integral_;
  s.mean_normal_force_n = s.contact_time_s > 0 ? normal_time_integral_ / s.contact_time_s : 0.0;
  const EnergyTerms e = system_.beam.energy(q, qd, *ws_);
  energy_scale_ = std::max({energy_scale_, std::abs(e.jacobi), e.t2});
  s.energy_audit_residual = std::abs(e.jacobi - h_start_ - work_ - s.damping_work_j - impact_jumps_) / energy_scale_;
  // The hub's work from the angular-momentum balance: dH_z/dt = τ + (R × F)_z, with impulses at impacts.
  s.hub_work_j = system_.beam.hub_motion().omega *
                 (e.angular_momentum - momentum_start_ - contact_moment_ - impulse_moment_);
  s.energy_change_j = e.kinetic + e.potential - energy_start_;
  event(EventKind::end, t, q, "");
}

}  // namespace rotbeam
