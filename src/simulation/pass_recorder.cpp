#include "rotbeam/pass_recorder.hpp"

#include <atomic>
#include <cmath>
#include <sstream>

namespace rotbeam {

namespace {
std::atomic<bool> g_interrupt{false};
}  // namespace

void request_interrupt() noexcept { g_interrupt.store(true); }
void clear_interrupt() noexcept { g_interrupt.store(false); }
bool interrupt_requested() noexcept { return g_interrupt.load(); }

bool PassRecorder::stop_requested(double t) {
  if (result_.failure) return true;
  if (g_interrupt.load()) {
    fail("interrupted", t, "the run was interrupted (SIGINT/SIGTERM); results up to here are kept");
    return true;
  }
  if (validity_breached_) {
    std::ostringstream s;
    s << "max |y_t|/L = " << validity_ratio_ << " exceeds simulation.deflection_warning_ratio = "
      << options_.deflection_warning_ratio
      << " (simulation.deflection_limit_is_error = true): beyond the quadratic foreshortening model";
    fail("validity", t, s.str());
    return true;
  }
  return false;
}

const char* phase_name(Phase p) {
  switch (p) {
    case Phase::free: return "free";
    case Phase::contact: return "contact";
    case Phase::stick: return "stick";
  }
  return "?";
}

PassRecorder::PassRecorder(const Model& model, const FrictionModel& friction, const PassOptions& options,
                           PassResult& result)
    : model_(model),
      friction_(friction),
      options_(options),
      result_(result),
      ws_(model.n),
      tip_(model.n),
      generalized_force_(model.n),
      qdd_(model.n),
      q_probe_(model.n),
      qd_probe_(model.n),
      qstar_(model.n) {}

ContactLoad PassRecorder::load(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double lambda,
                               double slip) {
  ContactLoad l;
  if (lambda == 0.0) return l;
  tip_kinematics(model_, t, q, qd, tip_);
  friction_direction(friction_, tip_, slip, qstar_);
  generalized_force_ = lambda * tip_.grad_gap + std::abs(lambda) * qstar_;
  l.lambda = lambda;
  l.slip = slip;
  l.normal_force = reported_normal_force(friction_, tip_, lambda);
  l.friction_force = -effective_friction(friction_, tip_) * std::abs(lambda) * slip;
  l.power = qd.dot(generalized_force_);
  l.slip_power = l.friction_force * tip_.VY;
  return l;
}

double PassRecorder::hub_torque(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                const ContactLoad& load) {
  // q̈ = M⁻¹(Q − Ψ); dH_z/dt = d/dε H_z(q + εq̇, q̇ + εq̈) by Richardson-extrapolated central
  // differences (exact for H_z's degree-4 polynomial dependence on ε, up to round-off).
  tip_kinematics(model_, t, q, qd, tip_);
  if (load.lambda != 0.0) {
    friction_direction(friction_, tip_, load.slip, qstar_);
    generalized_force_ = load.lambda * tip_.grad_gap + std::abs(load.lambda) * qstar_;
    acceleration(model_, q, qd, &generalized_force_, ws_, qdd_);
  } else {
    acceleration(model_, q, qd, nullptr, ws_, qdd_);
  }
  const double eps = 1e-6;
  auto h_at = [&](double e) {
    q_probe_ = q + e * qd;
    qd_probe_ = qd + e * qdd_;
    return evaluate_energy(model_, q_probe_, qd_probe_, ws_).angular_momentum;
  };
  const double d1 = (h_at(eps) - h_at(-eps)) / (2 * eps);
  const double d2 = (h_at(eps / 2) - h_at(-eps / 2)) / eps;
  const double dh = (4 * d2 - d1) / 3;
  tip_kinematics(model_, t, q, qd, tip_);
  const double fx = load.lambda, fy = load.friction_force;
  return dh - (tip_.X * fy - tip_.Y * fx);
}

void PassRecorder::track(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  (void)qd;
  const double ratio = std::abs(model_.integrals->s_tip.dot(q)) / model_.length;
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
    warn(t, s.str());
  }
}

void PassRecorder::sample(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase,
                          const ContactLoad& load) {
  HistoryRow row;
  tip_kinematics(model_, t, q, qd, tip_);
  row.t = t;
  row.theta = tip_.theta;
  row.phase = phase;
  row.x_tip = tip_.X;
  row.y_tip = tip_.Y;
  row.gap = tip_.gap;
  row.vx = tip_.VX;
  row.vy = tip_.VY;
  row.normal_force = load.normal_force;
  row.friction_force = load.friction_force;
  row.lambda = load.lambda;
  row.q = q;
  row.qd = qd;
  const EnergyTerms e = evaluate_energy(model_, q, qd, ws_);
  row.jacobi = e.jacobi;
  energy_scale_ = std::max({energy_scale_, std::abs(e.jacobi), e.t2});
  row.hub_torque = hub_torque(t, q, qd, load);
  result_.history.push_back(std::move(row));
  if (options_.output_interval_s <= 0.0) return;  // every accepted point is sampled
  next_sample_t_ = options_.output_interval_s * (std::floor(t / options_.output_interval_s) + 1.0);
}

void PassRecorder::start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  next_sample_t_ = t;
  last_t_ = t;
  h_start_ = evaluate_energy(model_, q, qd, ws_).jacobi;
  energy_scale_ = std::abs(h_start_);
  track(t, q, qd);
  sample(t, q, qd, Phase::free, ContactLoad{});
}

bool PassRecorder::impacts_exhausted(double t) {
  if (result_.summary.impacts < options_.max_impacts) return false;
  fail("impacts", t,
       "more than " + std::to_string(options_.max_impacts) +
           " impacts in one pass: impacts accumulate (raise impact.plastic_below_m_s)");
  return true;
}

void PassRecorder::accept(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase,
                          const ContactLoad& begin, const ContactLoad& end, bool force_sample) {
  const double dt = t - last_t_;
  PassSummary& s = result_.summary;
  if (phase != Phase::free) {
    s.contact_time_s += dt;
    normal_time_integral_ += 0.5 * (begin.normal_force + end.normal_force) * dt;
    s.friction_work_j += 0.5 * (begin.slip_power + end.slip_power) * dt;
    work_ += 0.5 * (begin.power + end.power) * dt;
    s.peak_normal_force_n = std::max({s.peak_normal_force_n, begin.normal_force, end.normal_force});
  }
  last_t_ = t;
  track(t, q, qd);
  if (force_sample || t >= next_sample_t_) sample(t, q, qd, phase, end);
}

void PassRecorder::accept_integrated(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase,
                                     const ContactLoad& load_end, const StepIntegrals& in, bool force_sample) {
  PassSummary& s = result_.summary;
  if (phase != Phase::free) {
    s.contact_time_s += t - last_t_;
    normal_time_integral_ += in.normal_impulse;
    s.friction_work_j += in.friction_work;
    work_ += in.work;
    s.peak_normal_force_n = std::max(s.peak_normal_force_n, load_end.normal_force);
  }
  last_t_ = t;
  track(t, q, qd);
  if (force_sample || t >= next_sample_t_) sample(t, q, qd, phase, load_end);
}

void PassRecorder::impact(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd_before,
                          const Eigen::VectorXd& qd_after, const ImpactResult& r) {
  PassSummary& s = result_.summary;
  ++s.impacts;
  if (r.restitution == 0.0) ++s.plastic_impacts;
  const double theta_deg = model_.theta(t) * 180.0 / M_PI;
  if (s.impacts == 1) s.first_impact_deg = theta_deg;
  s.last_separation_deg = theta_deg;
  s.normal_impulse_n_s += std::abs(r.impulse);
  impact_jumps_ += r.delta_t2;
  sample(t, q, qd_before, Phase::free, ContactLoad{});
  PassEvent e;
  e.t = t;
  e.theta = model_.theta(t);
  tip_kinematics(model_, t, q, qd_after, tip_);
  e.y_tip = tip_.Y;
  e.kind = "impact";
  e.vx_before = r.vx_before;
  e.vx_after = r.vx_after;
  e.restitution = r.restitution;
  e.impulse = r.impulse;
  e.detail = r.restitution == 0.0 ? "plastic" : "";
  result_.events.push_back(e);
  sample(t, q, qd_after, Phase::free, ContactLoad{});
  last_t_ = t;
}

void PassRecorder::contact_start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                 const std::string& detail) {
  (void)qd;
  in_episode_ = true;
  episode_t0_ = t;
  episode_theta0_ = model_.theta(t);
  episode_y0_ = 0;
  tip_kinematics(model_, t, q, q * 0.0, tip_);
  episode_y0_ = tip_.Y;
  event(t, q, "contact_start", detail);
}

void PassRecorder::contact_end(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                               const std::string& detail) {
  in_episode_ = false;
  tip_kinematics(model_, t, q, qd, tip_);
  if (t > episode_t0_) {
    PassSummary& s = result_.summary;
    ++s.contact_episodes;
    s.contact_intervals.push_back({episode_t0_, t, episode_theta0_, model_.theta(t), episode_y0_, tip_.Y});
    s.last_separation_deg = model_.theta(t) * 180.0 / M_PI;
  }
  event(t, q, "contact_end", detail);
  sample(t, q, qd, Phase::free, ContactLoad{});
  last_t_ = t;
}

void PassRecorder::event(double t, const Eigen::VectorXd& q, const std::string& kind, const std::string& detail) {
  PassEvent e;
  e.t = t;
  e.theta = model_.theta(t);
  tip_kinematics(model_, t, q, q * 0.0, tip_);
  e.y_tip = tip_.Y;
  e.kind = kind;
  e.detail = detail;
  result_.events.push_back(e);
}

void PassRecorder::warn(double t, const std::string& message) {
  for (const std::string& w : result_.summary.warnings)
    if (w == message) return;
  result_.summary.warnings.push_back(message);
  PassEvent e;
  e.t = t;
  e.theta = model_.theta(t);
  e.kind = "warning";
  e.detail = message;
  result_.events.push_back(e);
}

void PassRecorder::fail(const std::string& kind, double t, const std::string& message) {
  NumericalFailure f;
  f.kind = kind;
  f.t = t;
  f.theta = model_.theta(t);
  f.message = message;
  result_.failure = f;
  PassEvent e;
  e.t = t;
  e.theta = f.theta;
  e.kind = "failure";
  e.detail = kind + ": " + message;
  result_.events.push_back(e);
}

void PassRecorder::finish(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase,
                          const ContactLoad& load) {
  if (in_episode_) {
    if (!result_.failure) warn(t, "the tip is still in contact at the end angle");
    contact_end(t, q, qd, "end of the pass");
  } else {
    sample(t, q, qd, phase, load);
  }
  PassSummary& s = result_.summary;
  s.normal_impulse_n_s += normal_time_integral_;
  s.mean_normal_force_n = s.contact_time_s > 0 ? normal_time_integral_ / s.contact_time_s : 0.0;
  const EnergyTerms e = evaluate_energy(model_, q, qd, ws_);
  energy_scale_ = std::max({energy_scale_, std::abs(e.jacobi), e.t2});
  s.energy_audit_residual = std::abs(e.jacobi - h_start_ - work_ - impact_jumps_) / energy_scale_;
  PassEvent end;
  end.t = t;
  end.theta = model_.theta(t);
  end.kind = "end";
  result_.events.push_back(end);
}

}  // namespace rotbeam
