#include "pass_driver.hpp"

#include "rotbeam/detail/diagnostics.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace rotbeam {

namespace {
constexpr int kMaxInstantTransitions = 50;  // phase changes without time advancing → chatter diagnostic
constexpr double kInstant = 1e-12;          // [s]: a phase that lasted less did not advance time
constexpr double kClearCheckDeg = 0.5;      // simulation.end_when_clear: hub angle between checks [deg]
using detail::short_number;
}  // namespace

PassDriver::PassDriver(const System& system, const PassOptions& options, Stepper& stepper, PassRecorder& recorder,
                       const PassControl& control)
    : system_(system),
      options_(options),
      stepper_(stepper),
      rec_(recorder),
      traits_(stepper.traits()),
      ws_(system.beam.make_workspace()),
      tip_(system.beam.modes()),
      state_(system.beam.modes()),
      scratch_(system.beam.modes()),
      on_progress_(control.on_progress) {
  t_end_ = system.beam.time_at(options.end_angle_deg * M_PI / 180.0);
  if (options.revolutions > 0) {
    // docs/model.md §11: revolution k spans [θ0 + 360°(k − 1), θ0 + 360°k); its end is the section.
    period_ = 2.0 * M_PI / system.beam.hub_motion().omega;
    t_end_ = options.revolutions * period_;
    next_section_ = options.revolutions > 1 ? period_ : INFINITY;
  }
}

void PassDriver::report_progress() {
  if (!on_progress_ || !progress_clock_.due()) return;
  PassProgress p;
  p.theta_deg = system_.beam.theta(state_.t) * 180.0 / M_PI;
  p.start_deg = system_.beam.theta(flexible_from_t_) * 180.0 / M_PI;
  p.end_deg = options_.end_angle_deg;
  p.elapsed_s = progress_clock_.elapsed_s();
  p.steps = stepper_.statistics().steps;
  p.revolution = rec_.revolution();
  p.revolutions = options_.revolutions;
  p.section_distance = rec_.section_distance();
  on_progress_(p);
}

void PassDriver::run(const InitialConditions& ic) {
  const int n = system_.beam.modes();
  if (options_.tangent) {
    state_.tangent = Eigen::MatrixXd::Identity(2 * n, 2 * n);
    tangent_ws_.emplace(system_.beam);
    if (options_.scheme != Scheme::adaptive) lose_tangent("the thesis scheme does not integrate the variational equations");
    if (ic.rigid_start) lose_tangent("a rigid start is not a function of the state");
  }
  state_.t = 0.0;
  state_.phase = Phase::free;
  state_.episode = {};
  if (ic.rigid_start) {
    system_.beam.rest_state(state_.q);
    state_.qd.setZero();
  } else {
    if (ic.q0.size() != n || ic.qd0.size() != n)
      throw std::invalid_argument("initial conditions: q0 and qd0 must have " + std::to_string(n) + " values");
    state_.q = ic.q0;
    state_.qd = ic.qd0;
  }
  rec_.start(state_.t, state_.q, state_.qd);
  if (gap(system_.beam, system_.surface, state_.t, state_.q) >= 0.0) {
    fail_at(FailureKind::initial_state, state_.t, "the initial shape already touches the surface (C(0) >= 0)", Phase::free);
    return;
  }
  if (ic.rigid_start) {
    // Thesis §4.6 Step 1: the undeformed filament turns rigidly until its tip reaches the surface.
    const double theta_star = system_.surface.first_contact_angle(system_.beam.tip_radius(), system_.beam.theta(0.0));
    const double t_star = std::isnan(theta_star) ? INFINITY : system_.beam.time_at(theta_star);
    if (t_star < t_end_) {
      state_.t = t_star;
      flexible_from_t_ = t_star;  // the rigid turn costs nothing: progress counts from here
      rec_.rigid_turn(t_star);
      rec_.accept(state_.t, state_.q, state_.qd, Phase::free, {}, {}, true);
      system_.law.touch(*this);
      if (done_) return;
      loop();
      return;
    }
  }
  stepper_.begin_free(state_, FreeStart::pass_start);
  loop();
}

bool PassDriver::cross_section() {
  ++section_index_;
  next_section_ = section_index_ + 1 < options_.revolutions ? (section_index_ + 1) * period_ : INFINITY;
  if (rec_.end_revolution(state_.t, state_.q, state_.qd)) return true;
  if (state_.phase == Phase::free) stepper_.begin_free(state_, FreeStart::pass_start);
  return false;
}

void PassDriver::loop() {
  while (!done_) {
    if (instant_transitions_ > kMaxInstantTransitions) {
      fail_at(FailureKind::chatter, state_.t, "the tip switches between contact and free flight without time advancing",
              state_.phase);
      return;
    }
    if (state_.phase == Phase::free)
      free_flight();
    else
      contact();
  }
}

void PassDriver::free_flight() {
  const double t_enter = state_.t;
  while (state_.t < t_end_) {
    const StepOutcome o = stepper_.step(state_, stop_time());
    if (o.status == StepStatus::failed) return fail_at(o.failure->kind, o.failure->t, o.failure->message, Phase::free);
    rec_.free_rows_within(state_.t, state_.q, stepper_);
    if (o.status == StepStatus::root) {  // the gap closed: a touch, which the contact law resolves
      instant_transitions_ = (state_.t - t_enter < kInstant) ? instant_transitions_ + 1 : 0;
      rec_.accept(state_.t, state_.q, state_.qd, Phase::free, {}, o.integrals, true);
      open_event(EventSurface{});
      system_.law.touch(*this);
      close_event();
      return;
    }
    const bool section = state_.t >= next_section_;
    rec_.accept(state_.t, state_.q, state_.qd, Phase::free, {}, o.integrals, section);
    if (section && cross_section()) break;
    if (options_.end_when_clear && clear_for_the_rest()) break;
    report_progress();
    if (o.note) {
      rec_.event(o.note->kind, state_.t, state_.q, o.note->detail);
      if (!o.note->warning.empty()) rec_.warn(state_.t, state_.q, o.note->warning);
    }
    instant_transitions_ = 0;
    if (rec_.stop_requested(state_.t, state_.q)) break;
  }
  finish(Phase::free);
}

bool PassDriver::clear_for_the_rest() {
  if (state_.t < next_clear_check_t_) return false;
  const HubMotion hub = system_.beam.hub_motion();
  next_clear_check_t_ = state_.t + kClearCheckDeg * M_PI / 180.0 / std::abs(hub.omega);
  const double delta = system_.beam.tip_excursion_bound(state_.q, state_.qd, *ws_);
  if (!std::isfinite(delta)) return false;
  const double theta = hub.theta(state_.t), theta_end = hub.theta(t_end_);
  const double reach = system_.surface.max_gap_on_arc(system_.beam.tip_radius(), std::min(theta, theta_end),
                                                      std::max(theta, theta_end), delta);
  if (!(reach < 0.0)) return false;
  rec_.event(EventKind::clear, state_.t, state_.q,
             "the tip stays within " + short_number(delta) + " m of its undeformed position (Jacobi integral) and so "
             "at least " + short_number(-reach) + " m clear of the surface until the end angle: the pass "
             "ends here (simulation.end_when_clear)");
  rec_.ended_clear(state_.t);
  return true;
}

bool PassDriver::impacts_exhausted() {
  if (!rec_.impacts_exhausted(state_.t, state_.q)) return false;
  finish(Phase::free);
  return true;
}

void PassDriver::impact(const Eigen::VectorXd& qd_before, const ImpactResult& r) {
  rec_.impact(state_.t, state_.q, qd_before, state_.qd, r);
  if (!tracking()) return;
  if (!pending_) return lose_tangent("an impact away from an event of the pass");
  if (r.tangential) return lose_tangent("a tangential impact (Painlevé's paradox) is not differentiated");
  if (++pending_->impacts > 1) return lose_tangent("two impacts at one instant");
}

void PassDriver::rebound() {
  state_.phase = Phase::free;
  state_.episode_tangent.resize(0, 0);
  close_event();
  stepper_.begin_free(state_, FreeStart::rebound);
}

void PassDriver::enter_contact(const ContactLoad& load, const std::string& why, bool first_touch) {
  rec_.contact_start(state_.t, state_.q, state_.qd, load, why, first_touch);
  close_event();
  stepper_.begin_contact(state_);
}

void PassDriver::open_event(const EventSurface& surface) {
  if (!tracking()) return;
  if (pending_) close_event();
  pending_.emplace();
  pending_->surface = surface;
  pending_->before = EventSide{state_.t, state_.q, state_.qd, state_.phase, state_.episode};
}

void PassDriver::close_event() {
  if (!pending_) return;
  const PendingEvent e = std::move(*pending_);
  pending_.reset();
  if (!tracking()) return;
  const EventSide after{state_.t, state_.q, state_.qd, state_.phase, state_.episode};
  // A compliant contact's regularised friction is stiff across V_t = 0 (slope μF_n/v_ε): the
  // variational equations riding on the motion's steps lose accuracy there (measured: 3e-3 of Φ after
  // 14 episodes against 1e-6 without friction; docs/model.md), so the map's Jacobian is differenced.
  if (after.phase != Phase::free && system_.law.kind(after.phase) == PhaseKind::force && system_.law.friction().mu > 0.0)
    return lose_tangent("the compliant law's regularised friction is stiff in the variational equations");
  const bool same_field = e.impacts == 0 && after.phase == e.before.phase &&
                          (after.phase == Phase::free || (after.episode.slip == e.before.episode.slip &&
                                                          after.episode.parameter == e.before.episode.parameter));
  if (same_field) return;  // S = 1
  if (!saltation_matrix(system_, e.surface, e.before, after, e.impacts > 0, *tangent_ws_))
    return lose_tangent("a grazing event (the root function's rate is zero) at t = " + short_number(e.before.t) + " s");
  // A touch that sets the episode's parameters from the state: their sensitivity rides with Φ.
  if (e.surface.gap && after.phase != Phase::free && episode_sensitivity(system_, e.before, *tangent_ws_))
    state_.episode_tangent = tangent_ws_->episode_jacobian * state_.tangent;
  state_.tangent = tangent_ws_->saltation * state_.tangent;
}

void PassDriver::lose_tangent(const std::string& why) {
  if (tangent_lost_.empty()) tangent_lost_ = why;
  pending_.reset();
}

void PassDriver::lift_off(const std::string& why) {
  rec_.event(EventKind::lift_off, state_.t, state_.q, why);
  ++instant_transitions_;
  separate();
}

void PassDriver::end_contact(const std::string& why) {
  rec_.contact_end(state_.t, state_.q, state_.qd, why);
  separate();
}

void PassDriver::event(EventKind kind, const std::string& detail) { rec_.event(kind, state_.t, state_.q, detail); }

void PassDriver::fail(FailureKind kind, const std::string& message, Phase phase) {
  fail_at(kind, state_.t, message, phase);
}

void PassDriver::separate() {
  state_.phase = Phase::free;
  state_.episode_tangent.resize(0, 0);
  close_event();
  stepper_.begin_free(state_, FreeStart::separation);
}

void PassDriver::contact() {
  const double t_enter = state_.t;
  const ContactLaw& law = system_.law;
  while (state_.t < t_end_) {
    if (!traits_.locates_contact_roots && !law.before_step(*this)) return;
    const StepOutcome o = stepper_.step(state_, stop_time());
    if (o.status == StepStatus::failed) return fail_at(o.failure->kind, o.failure->t, o.failure->message, state_.phase);
    const ContactRoot* root = o.root == Root::contact ? &law.roots(state_.phase)[o.contact_root] : nullptr;
    if (root && root->ends_contact) {  // separation
      ContactLoad zero;  // no force at the contact's end; the slip of the step
      zero.slip = state_.episode.slip;
      rec_.accept(state_.t, state_.q, state_.qd, state_.phase, zero, o.integrals, true);
      rec_.contact_end(state_.t, state_.q, state_.qd, root->end_detail);
      instant_transitions_ = (state_.t - t_enter < kInstant) ? instant_transitions_ + 1 : 0;
      open_event(EventSurface{false, state_.phase, o.contact_root, state_.episode});
      return separate();
    }
    const bool section = state_.t >= next_section_;
    rec_.accept(state_.t, state_.q, state_.qd, state_.phase, o.load, o.integrals, root || section);
    if (root) {
      open_event(EventSurface{false, state_.phase, o.contact_root, state_.episode});
      law.root(*this, o.contact_root);
      close_event();
      if (done_ || state_.phase == Phase::free) return;
    }
    instant_transitions_ = 0;
    if (section && cross_section()) break;
    report_progress();
    if (rec_.stop_requested(state_.t, state_.q)) break;
  }
  finish(state_.phase);
}

void PassDriver::fail_at(FailureKind kind, double t, const std::string& message, Phase phase) {
  // A failure at the state's own time has the state (a stepper's may lie inside its step).
  rec_.fail(kind, t, message, t == state_.t ? &state_.q : nullptr);
  finish(phase);
}

void PassDriver::finish(Phase phase) {
  rec_.finish(state_.t, state_.q, state_.qd, phase, stepper_.statistics());
  done_ = true;
}

PassResult run_pass_with(const System& system, const InitialConditions& initial, const PassOptions& options,
                         Stepper& stepper, const PassControl& control) {
  const auto wall0 = std::chrono::steady_clock::now();
  PassResult result;
  result.summary.scheme = options.scheme;
  {
    PassRecorder recorder(system, options, control, result);
    PassDriver driver(system, options, stepper, recorder, control);
    driver.run(initial);
    if (options.tangent) {
      result.final_tangent = driver.final_tangent();
      result.tangent_lost = driver.tangent_lost();
    }
  }
  result.summary.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return result;
}

PassResult run_pass(const System& system, const InitialConditions& initial, const PassOptions& options,
                    const PassControl& control) {
  const auto wall0 = std::chrono::steady_clock::now();  // the stepper's set-up counts too
  const std::unique_ptr<Stepper> stepper = make_stepper(system, options);
  PassResult result = run_pass_with(system, initial, options, *stepper, control);
  result.summary.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return result;
}

}  // namespace rotbeam
