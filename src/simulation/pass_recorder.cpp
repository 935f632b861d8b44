#include "pass_recorder.hpp"

#include "rotbeam/surface.hpp"

#include <cmath>

namespace rotbeam {

double PassContext::omega() const { return system.beam.hub_motion().omega; }

double PassContext::relative_angle_deg(double t) const {
  // docs/model.md §11: relative to the revolution, in (−180°, 180°], 0° at the surface's deepest point.
  double a = std::remainder(system.beam.theta(t) - system.surface.deepest_angle(), 2.0 * M_PI) * 180.0 / M_PI;
  if (a <= -180.0) a += 360.0;
  return a;
}

double PassContext::tip_y(double t, const Eigen::VectorXd& q) const { return tip_position(system.beam, t, q).y(); }

namespace {
// The caller's sink, or the memory one made for a run without.
PassSink& sink_of(const PassControl& control, std::optional<MemorySink>& memory, PassResult& result,
                  const PassOptions& options) {
  if (control.sink) return *control.sink;
  memory.emplace(result, options.history_revolutions);
  return *memory;
}
}  // namespace

PassRecorder::PassRecorder(const System& system, const PassOptions& options, const PassControl& control,
                           PassResult& result)
    : ctx_(system, options, control, result, sink_of(control, memory_, result, options)),
      sampler_(ctx_),
      metrics_(ctx_),
      ledger_(ctx_),
      bins_(ctx_),
      wear_(ctx_),
      validity_(ctx_, *this),
      book_(ctx_) {
  if (ctx_.sink.wants_deliveries()) deliveries_.emplace(ctx_, ledger_);
  observers_ = {&ledger_};
  if (deliveries_) observers_.push_back(&*deliveries_);
  observers_.insert(observers_.end(), {&metrics_, &bins_, &wear_, &validity_, &sampler_, &book_});
}

bool PassRecorder::stop_requested(double t, const Eigen::VectorXd& q) {
  if (ctx_.result.failure) return true;
  if (ctx_.control.stop && ctx_.control.stop->stop_requested()) {
    fail(FailureKind::interrupted, t, "the run was interrupted (SIGINT/SIGTERM or a stop request); results up to here are kept", &q);
    return true;
  }
  if (validity_.breached()) {
    fail(FailureKind::validity, t, validity_.breach_message(), &q);
    return true;
  }
  return false;
}

void PassRecorder::emit(const PassEvent& e) { ctx_.sink.event(e); }

void PassRecorder::start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  last_t_ = t;
  ledger_.start(t, q, qd);
  if (deliveries_) deliveries_->start(t, q, qd);
  book_.start(t, q, qd);
  if (ctx_.control.watcher) ctx_.control.watcher->start(q, qd);
  if (ctx_.options.revolutions > 0) open_revolution(t, q, qd);
  validity_.start(t, q, qd);
  sampler_.start(t, q, qd);
}

bool PassRecorder::impacts_exhausted(double t, const Eigen::VectorXd& q) {
  const int max = ctx_.options.max_impacts;
  if (metrics_.impacts_counted() < max) return false;
  fail(FailureKind::impacts, t,
       "more than " + std::to_string(max) + (max == 1 ? " impact" : " impacts") +
           (ctx_.revolution > 0 ? " in one revolution" : " in one pass") + " (simulation.max_impacts = " +
           std::to_string(max) +
           "): impacts accumulate (raise simulation.max_impacts, or impact.plastic_below_m_s to end a bouncing sequence)",
       &q);
  return true;
}

void PassRecorder::open_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  ++ctx_.revolution;
  revolution_open_ = true;
  revolution_t0_ = t;
  for (PassObserver* o : observers_) o->open_revolution(t, q, qd);
}

bool PassRecorder::close_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, bool complete) {
  RevolutionRecord r;
  r.revolution = ctx_.revolution;
  r.complete = complete;
  r.t_end = t;
  r.t_start = revolution_t0_;
  for (PassObserver* o : observers_) o->close_revolution(t, q, qd, r);
  revolution_open_ = false;
  ctx_.sink.revolution(r);
  return complete && ctx_.control.watcher && ctx_.control.watcher->revolution(r);
}

bool PassRecorder::end_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  if (close_revolution(t, q, qd, true)) return true;
  open_revolution(t, q, qd);
  return false;
}

void PassRecorder::accept(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase,
                          const ContactLoad& load, const StepIntegrals& in, bool force_sample) {
  const StepView v{last_t_, t, q, qd, phase, load, in, force_sample};
  for (PassObserver* o : observers_) o->step(v);
  last_t_ = t;
}

void PassRecorder::impact(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd_before,
                          const Eigen::VectorXd& qd_after, const ImpactResult& r) {
  // The hub's work during the impact: ω times its angular impulse, ΔH_z less the moment of the contact
  // impulse (q is unchanged, so ΔH_z = Δ(p(q)·q̇)).
  const Eigen::Vector2d at = tip_position(ctx_.system.beam, t, q);
  const double impulse_moment = at.x() * r.impulse_y - at.y() * r.impulse_x;
  const double h_after = ledger_.angular_momentum(q, qd_after);
  const double dh = h_after - ledger_.angular_momentum(q, qd_before);
  const ImpactView v{t, q, qd_before, qd_after, r, impulse_moment, h_after, ctx_.omega() * (dh - impulse_moment)};
  for (PassObserver* o : observers_) o->impact(v);
  sampler_.before_impact(v);
  PassEvent e;
  e.t = t;
  e.theta = ctx_.system.beam.theta(t);
  e.y_tip = ctx_.tip_y(t, q);
  e.kind = EventKind::impact;
  e.vx_before = r.vx_before;
  e.vx_after = r.vx_after;
  e.restitution = r.restitution;
  e.impulse = r.impulse;
  e.tangential_impulse = r.tangential_impulse;
  e.hub_work = v.hub_work;
  e.impact_loss = r.contact_work - r.surface_work;  // as the ledger books them (energy_ledger.cpp)
  e.frictional_heat = r.frictional_heat;
  e.sliding_load = r.sliding_load;
  e.surface_work = r.surface_work;
  e.detail = r.tangential            ? "tangential: an impact without collision at a Painlevé point, the slip stopped"
             : r.restitution == 0.0 ? "plastic"
                                    : "";
  emit(e);
  sampler_.after_impact(v);
  last_t_ = t;
}

void PassRecorder::contact_start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const ContactLoad& load,
                                 const std::string& detail, bool first_touch) {
  for (PassObserver* o : observers_) o->contact_start(t, q, load, first_touch);
  event(EventKind::contact_start, t, q, detail);
  sampler_.sample(t, q, qd, Phase::contact, load);
  last_t_ = t;
}

void PassRecorder::contact_end(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const std::string& detail) {
  for (PassObserver* o : observers_) o->contact_end(t, q);
  event(EventKind::contact_end, t, q, detail);
  sampler_.sample(t, q, qd, Phase::free, ContactLoad{});
  last_t_ = t;
}

void PassRecorder::event(EventKind kind, double t, const Eigen::VectorXd& q, const std::string& detail) {
  PassEvent e;
  e.t = t;
  e.theta = ctx_.system.beam.theta(t);
  e.y_tip = ctx_.tip_y(t, q);
  e.kind = kind;
  e.detail = detail;
  emit(e);
}

void PassRecorder::warn(double t, const Eigen::VectorXd& q, const std::string& message) {
  for (const std::string& w : ctx_.result.summary.warnings)
    if (w == message) return;
  ctx_.result.summary.warnings.push_back(message);
  event(EventKind::warning, t, q, message);
}

void PassRecorder::fail(FailureKind kind, double t, const std::string& message, const Eigen::VectorXd* q) {
  NumericalFailure f;
  f.kind = kind;
  f.t = t;
  f.theta = ctx_.system.beam.theta(t);
  f.message = message;
  ctx_.result.failure = f;
  PassEvent e;
  e.t = t;
  e.theta = f.theta;
  // The state at t where it is known (the one the history's last row is written from); a failure
  // inside a step, whose state is not known there, has none.
  e.y_tip = q ? ctx_.tip_y(t, *q) : NAN;
  e.kind = EventKind::failure;
  e.detail = std::string(failure_name(kind)) + ": " + message;
  emit(e);
}

void PassRecorder::finish(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Phase phase,
                          const StepperStatistics& statistics) {
  PassResult& result = ctx_.result;
  if (metrics_.in_episode()) {
    if (!result.failure) warn(t, q, "the tip is still in contact at the end angle");
    contact_end(t, q, qd, "end of the pass");
  } else {
    sampler_.sample(t, q, qd, phase, ContactLoad{});  // outside an episode there is no contact load
  }
  PassSummary& s = result.summary;
  s.steps = statistics.steps;
  s.rhs_evaluations = statistics.rhs_evaluations;
  s.corrector_iterations = statistics.corrector_iterations;
  s.corrector_iterations_max = statistics.corrector_iterations_max;
  ledger_.finish_with_scale(t, q, qd, sampler_.energy_scale());
  result.final_t = t;
  result.final_q = q;
  result.final_qd = qd;
  if (ctx_.options.revolutions > 0 && revolution_open_) {
    const double t_end = ctx_.options.revolutions * 2.0 * M_PI / ctx_.omega();
    close_revolution(t, q, qd, !result.failure && t >= t_end * (1.0 - 1e-12));
  }
  for (PassObserver* o : observers_) o->finish(t, q, qd);
  if (ctx_.control.watcher) {
    const std::string warning = ctx_.control.watcher->finish(s, result.failure.has_value(), ctx_.revolution);
    if (!warning.empty()) warn(t, q, warning);
  }
  event(EventKind::end, t, q, "");
}

}  // namespace rotbeam
