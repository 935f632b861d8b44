#include "pass_driver.hpp"

#include "rotbeam/rigid_contact.hpp"
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
      qd_before_(system.beam.modes()),
      force_(system.beam.modes()),
      on_progress_(control.on_progress) {
  t_end_ = system.beam.time_at(options.end_angle_deg * M_PI / 180.0);
  if (options.revolutions > 0) {
    // SPEC §11: revolution k spans [θ0 + 360°(k − 1), θ0 + 360°k); its end is the section.
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
  state_.t = 0.0;
  state_.phase = Phase::free;
  state_.slip = 0.0;
  if (ic.rigid_start) {
    state_.q.setZero();
    state_.qd.setZero();
  } else {
    if (ic.q0.size() != n || ic.qd0.size() != n)
      throw std::invalid_argument("initial conditions: q0 and qd0 must have " + std::to_string(n) + " values");
    state_.q = ic.q0;
    state_.qd = ic.qd0;
  }
  rec_.start(state_.t, state_.q, state_.qd);
  if (gap(system_.beam, system_.surface, state_.t, state_.q) >= 0.0) {
    fail(FailureKind::initial_state, state_.t, "the initial shape already touches the surface (C(0) >= 0)", Phase::free);
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
      if (compliant_)
        compliant_contact();
      else
        impact();
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
      fail(FailureKind::chatter, state_.t, "the tip switches between contact and free flight without time advancing",
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
    if (o.status == StepStatus::failed) return fail(o.failure->kind, o.failure->t, o.failure->message, Phase::free);
    rec_.free_rows_within(state_.t, state_.q, stepper_);
    if (o.status == StepStatus::root) {  // the gap closed: a touch
      instant_transitions_ = (state_.t - t_enter < kInstant) ? instant_transitions_ + 1 : 0;
      rec_.accept(state_.t, state_.q, state_.qd, Phase::free, {}, o.integrals, true);
      touch();
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
    if (rec_.stop_requested(state_.t)) break;
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

void PassDriver::touch() {
  if (compliant_) return compliant_contact();
  tip_kinematics(system_.beam, system_.surface, state_.t, state_.q, state_.qd, tip_);
  if (tip_.gap_rate > 0.0)
    impact();
  else
    begin_contact("touch without approach speed");
}

void PassDriver::impact() {
  if (rec_.impacts_exhausted(state_.t)) return finish(Phase::free);
  qd_before_ = state_.qd;
  const ImpactResult r = apply_impact(system_.beam, system_.surface, system_.law.impact, state_.t, state_.q, state_.qd,
                                      *ws_, tip_, system_.law.friction.mu);
  if (r.jammed)
    return fail(FailureKind::painleve, state_.t,
                "the frictional impact jams: sliding drives the tip into the surface and the normal approach never "
                "ends (Painlevé's paradox of impacts; impact.friction = \"none\" keeps the thesis's frictionless impact)",
                Phase::free);
  rec_.impact(state_.t, state_.q, qd_before_, state_.qd, r);
  if (rebounds(r)) {
    state_.phase = Phase::free;
    stepper_.begin_free(state_, FreeStart::rebound);
    return;
  }
  begin_contact(r.restitution == 0.0 ? "after a plastic impact" : "after an impact");
}

void PassDriver::begin_contact(const std::string& why) {
  const FrictionModel& friction = system_.law.friction;
  system_.beam.evaluate_dynamics(state_.q, state_.qd, *ws_);
  tip_kinematics(system_.beam, system_.surface, state_.t, state_.q, state_.qd, tip_);
  const SlipDecision slip = decide_slip(system_.beam, friction, tip_, *ws_);
  if (slip.kind == SlipDecision::Kind::stick)
    return fail(FailureKind::stick, state_.t, detail::stick_message(slip, effective_friction(friction, tip_)),
                Phase::stick);
  if (slip.kind == SlipDecision::Kind::separate) {
    rec_.event(EventKind::lift_off, state_.t, state_.q, detail::lift_off_message(slip.stick_normal));
    ++instant_transitions_;
    return separate();
  }
  state_.slip = slip.direction;
  const AccelerationMultiplier am = acceleration_multiplier(system_.beam, system_.surface, friction, state_.t, state_.q,
                                                            state_.qd, state_.slip, *ws_, tip_);
  if (am.solution.status != MultiplierSolution::Status::unique)
    return fail(FailureKind::painleve, state_.t, detail::painleve_message(am.a, am.b, am.c), Phase::contact);
  if (am.solution.lambda > 0.0 && traits_.lifts_off_on_positive_multiplier) {
    rec_.event(EventKind::lift_off, state_.t, state_.q,
               "λ = " + short_number(am.solution.lambda) + " N > 0 at the touch: no sustained contact");
    ++instant_transitions_;
    return separate();
  }
  rec_.contact_start(state_.t, state_.q, state_.qd,
                     contact_load(friction, tip_, state_.qd, std::min(am.solution.lambda, 0.0), state_.slip, force_), why);
  state_.phase = Phase::contact;
  stepper_.begin_contact(state_, am.solution.lambda);
}

void PassDriver::compliant_contact() {
  tip_kinematics(system_.beam, system_.surface, state_.t, state_.q, state_.qd, tip_);
  const double v0 = tip_.gap_rate;
  const double full = std::hypot(tip_.VX - tip_.surface_vx, tip_.VY - tip_.surface_vy);
  const double damping = hertz_damping(system_.law, v0, full);
  state_.slip = regularized_slip(tip_.slip_speed, system_.law.hertz.friction_regularization_m_s);
  ContactLoad zero;
  zero.slip = state_.slip;
  rec_.compliant_touch(state_.t, state_.q, state_.qd, zero,
                       "compliant contact: approach speed " + short_number(v0) + " m/s, Hunt–Crossley c = " +
                           short_number(damping) + " s/m");
  state_.phase = Phase::contact;
  stepper_.begin_compliant_contact(state_, damping);
}

void PassDriver::separate() {
  state_.phase = Phase::free;
  stepper_.begin_free(state_, FreeStart::separation);
}

bool PassDriver::check_slip() {
  const FrictionModel& friction = system_.law.friction;
  system_.beam.evaluate_dynamics(state_.q, state_.qd, *ws_);
  tip_kinematics(system_.beam, system_.surface, state_.t, state_.q, state_.qd, tip_);
  const SlipDecision slip = decide_slip(system_.beam, friction, tip_, *ws_);
  if (slip.kind == SlipDecision::Kind::stick) {
    fail(FailureKind::stick, state_.t, detail::stick_message(slip, effective_friction(friction, tip_)), Phase::stick);
    return false;
  }
  if (slip.kind == SlipDecision::Kind::slip) {
    if (state_.slip != 0.0 && slip.direction != state_.slip)
      rec_.event(EventKind::slip_reversal, state_.t, state_.q, detail::slip_reversal_message(slip.direction));
    state_.slip = slip.direction;
  }
  return true;
}

void PassDriver::contact() {
  const FrictionModel& friction = system_.law.friction;
  const double t_enter = state_.t;
  while (state_.t < t_end_) {
    if (!traits_.locates_slip_stops && !check_slip()) return;
    const StepOutcome o = stepper_.step(state_, stop_time());
    if (o.status == StepStatus::failed) return fail(o.failure->kind, o.failure->t, o.failure->message, Phase::contact);
    if (o.root == Root::multiplier_vanishes || o.root == Root::gap_opens) {  // separation
      ContactLoad zero;  // no force at λ = 0 (or δ = 0); the slip of the step, for the friction's impulse over it
      zero.slip = state_.slip;
      rec_.accept(state_.t, state_.q, state_.qd, Phase::contact, zero, o.integrals, true);
      rec_.contact_end(state_.t, state_.q, state_.qd,
                       o.root == Root::gap_opens ? "the gap opened (δ = 0)" : "λ reached 0");
      instant_transitions_ = (state_.t - t_enter < kInstant) ? instant_transitions_ + 1 : 0;
      return separate();
    }
    const bool section = state_.t >= next_section_;
    rec_.accept(state_.t, state_.q, state_.qd, Phase::contact, o.load, o.integrals,
                o.root == Root::slip_stops || section);
    if (o.root == Root::slip_stops) {
      // V_t = 0: the velocity has no sign to give; the locked-tip analysis decides (SPEC §4).
      system_.beam.evaluate_dynamics(state_.q, state_.qd, *ws_);
      tip_kinematics(system_.beam, system_.surface, state_.t, state_.q, state_.qd, tip_);
      const SlipDecision d = decide_slip_at_rest(friction, tip_, *ws_);
      if (d.kind == SlipDecision::Kind::stick)
        return fail(FailureKind::stick, state_.t, detail::stick_message(d, effective_friction(friction, tip_)),
                    Phase::stick);
      if (d.kind == SlipDecision::Kind::separate) {
        rec_.contact_end(state_.t, state_.q, state_.qd, "the tip stopped sliding and lifts off");
        return separate();
      }
      if (d.direction != state_.slip)
        rec_.event(EventKind::slip_reversal, state_.t, state_.q, detail::slip_reversal_message(d.direction));
      state_.slip = d.direction;
    }
    instant_transitions_ = 0;
    if (section && cross_section()) break;
    report_progress();
    if (rec_.stop_requested(state_.t)) break;
  }
  finish(Phase::contact);
}

void PassDriver::fail(FailureKind kind, double t, const std::string& message, Phase phase) {
  rec_.fail(kind, t, message);
  finish(phase);
}

void PassDriver::finish(Phase phase) {
  rec_.finish(state_.t, state_.q, state_.qd, phase, stepper_.statistics());
  done_ = true;
}

PassResult run_pass(const System& system, const InitialConditions& initial, const PassOptions& options,
                    const PassControl& control) {
  const auto wall0 = std::chrono::steady_clock::now();
  PassResult result;
  result.summary.scheme = options.scheme;
  {
    const std::unique_ptr<Stepper> stepper = make_stepper(system, options);
    PassRecorder recorder(system, options, control, result);
    PassDriver driver(system, options, *stepper, recorder, control);
    driver.run(initial);
  }
  result.summary.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return result;
}

}  // namespace rotbeam
