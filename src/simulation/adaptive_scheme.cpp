// The adaptive event-driven scheme (SPEC §6): Dormand–Prince 5(4) with dense output from
// Boost.Odeint, events located on the dense output, projection onto the constraint in contact.
//
// State x = (q, q̇, W, W_f, I_n): W = ∫q̇ᵀQ dt, W_f = ∫F_t V_t dt, I_n = ∫F_n dt are integrated with
// the motion (under the same error control) and reset after every accepted contact step, so the
// energy audit and the contact integrals are as accurate as the tolerance.
//   free flight  q̈ = −M⁻¹Ψ; event C = 0 (approach) → impact (or contact for a grazing touch)
//   contact      q̈ = M⁻¹(−Ψ + λ∇C + |λ|Q*) with λ from a λ + b|λ| = c at every evaluation;
//                events λ = 0 (→ separation) and V_t = 0 (→ slip reversal, stick or lift-off);
//                after each step q and q̇ are projected (mass-weighted) onto C = 0 and Ċ = 0
// Each step's dense output is sampled at interior points before root finding (TOMS 748), so a
// crossing and re-crossing within one step is still found.
#include "rotbeam/pass.hpp"
#include "rotbeam/pass_recorder.hpp"
#include "rotbeam/detail/diagnostics.hpp"

#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <functional>
#include <sstream>

namespace rotbeam {

namespace {

namespace odeint = boost::numeric::odeint;
using State = std::vector<double>;
using DenseStepper = odeint::result_of::make_dense_output<odeint::runge_kutta_dopri5<State>>::type;

constexpr int kSamplesPerStep = 4;      // interior samples of the dense output per step
constexpr int kMaxInstantTransitions = 50;  // phase changes without time advancing → chatter diagnostic
// An accepted step shorter than this fraction of the pass means the tolerance cannot be met in
// double precision (at rtol ≥ 1e-13 the steps stay above ~1e-9 s for a pass of ~1e-2 s).
constexpr double kMinStepFraction = 1e-12;

using detail::short_number;

class AdaptiveScheme {
public:
  AdaptiveScheme(const Model& model, const ImpactLaw& law, const FrictionModel& friction, const PassOptions& options,
                 PassResult& result)
      : model_(model),
        law_(law),
        friction_(friction),
        opt_(options),
        result_(result),
        rec_(model, friction, options, result),
        n_(model.n),
        ws_(n_),
        ews_(n_),
        tip_(n_),
        etip_(n_),
        x_(2 * n_ + 3, 0.0),
        xs_(2 * n_ + 3, 0.0),
        q_(n_),
        qd_(n_),
        qstar_(n_),
        force_(n_),
        w_(n_),
        stepper_(odeint::make_dense_output(options.atol, options.rtol, options.max_step_s,
                                           odeint::runge_kutta_dopri5<State>())) {
    t_end_ = model.time_at(options.end_angle_rad);
  }

  void run(const InitialConditions& ic) {
    t_ = 0.0;
    if (ic.rigid_start) {
      q_.setZero();
      qd_.setZero();
      rec_.start(t_, q_, qd_);
      const double t_star = model_.time_at(model_.rigid_contact_angle());
      if (t_star >= t_end_) {
        phase_ = Phase::free;
        loop();
        return;
      }
      t_ = t_star;
      rec_.accept(t_, q_, qd_, Phase::free, {}, {}, true);
      if (!impact()) return;
    } else {
      q_ = ic.q0;
      qd_ = ic.qd0;
      rec_.start(t_, q_, qd_);
      if (gap(model_, t_, q_) >= 0.0) {
        rec_.fail("initial_state", t_, "the initial shape already touches the surface (C(0) >= 0)");
        rec_.finish(t_, q_, qd_, Phase::free, {});
        return;
      }
      phase_ = Phase::free;
    }
    loop();
  }

private:
  // ---- state packing ------------------------------------------------------------------------
  void pack() {
    for (int i = 0; i < n_; ++i) {
      x_[i] = q_[i];
      x_[n_ + i] = qd_[i];
    }
    x_[2 * n_] = x_[2 * n_ + 1] = x_[2 * n_ + 2] = 0.0;
  }
  void unpack(const State& x) {
    for (int i = 0; i < n_; ++i) {
      q_[i] = x[i];
      qd_[i] = x[n_ + i];
    }
  }
  StepIntegrals integrals_of(const State& x) const { return {x[2 * n_], x[2 * n_ + 1], x[2 * n_ + 2]}; }

  // ---- right-hand side ----------------------------------------------------------------------
  void rhs(const State& x, State& dxdt, double t) {
    ++rec_.rhs();
    const Eigen::Map<const Eigen::VectorXd> q(x.data(), n_), qd(x.data() + n_, n_);
    Eigen::Map<Eigen::VectorXd> dq(dxdt.data(), n_), a(dxdt.data() + n_, n_);
    dq = qd;
    if (phase_ == Phase::free) {
      acceleration(model_, q, qd, nullptr, ws_, a);
      dxdt[2 * n_] = dxdt[2 * n_ + 1] = dxdt[2 * n_ + 2] = 0.0;
      return;
    }
    const AccelerationMultiplier am = acceleration_multiplier(model_, friction_, t, q, qd, slip_, ws_, tip_);
    if (am.solution.status != MultiplierSolution::Status::unique && !painleve_) {
      painleve_ = true;
      painleve_t_ = t;
      painleve_abc_[0] = am.a, painleve_abc_[1] = am.b, painleve_abc_[2] = am.c;
    }
    // Past a separation (λ > 0) the contact force is zero; the step is cut at λ = 0 anyway.
    const double lambda = std::min(am.solution.lambda, 0.0);
    friction_direction(friction_, tip_, slip_, qstar_);
    force_ = lambda * tip_.grad_gap + std::abs(lambda) * qstar_;
    a = force_ - ws_.psi;
    ws_.mass_llt.solveInPlace(a);
    const double ft = -effective_friction(friction_, tip_) * std::abs(lambda) * slip_;
    dxdt[2 * n_] = qd.dot(force_);
    dxdt[2 * n_ + 1] = ft * tip_.VY;
    dxdt[2 * n_ + 2] = reported_normal_force(friction_, tip_, lambda);
  }

  // ---- event functions on the dense output ----------------------------------------------------
  double state_gap(double t, const State& x) {
    const Eigen::Map<const Eigen::VectorXd> q(x.data(), n_);
    return gap(model_, t, q);
  }
  double state_lambda(double t, const State& x) {
    const Eigen::Map<const Eigen::VectorXd> q(x.data(), n_), qd(x.data() + n_, n_);
    return acceleration_multiplier(model_, friction_, t, q, qd, slip_, ews_, etip_).solution.lambda;
  }
  double state_slip_speed(double t, const State& x) {
    const Eigen::Map<const Eigen::VectorXd> q(x.data(), n_), qd(x.data() + n_, n_);
    tip_kinematics(model_, t, q, qd, etip_);
    return slip_ * etip_.VY;
  }

  // First t in (ta, tb] where g changes from < 0 to ≥ 0, given g(ta) < 0; NaN if none.
  double first_root(const std::function<double(double)>& g, double ta, double tb, double ga) {
    double t_prev = ta, g_prev = ga;
    for (int k = 1; k <= kSamplesPerStep; ++k) {
      const double tk = ta + (tb - ta) * k / kSamplesPerStep;
      const double gk = g(tk);
      if (g_prev < 0.0 && gk >= 0.0) {
        boost::uintmax_t iters = 200;
        const double tol_s = opt_.event_tolerance_s;
        const auto tol = [tol_s](double a, double b) { return std::abs(b - a) <= tol_s; };
        const auto br = boost::math::tools::toms748_solve(g, t_prev, tk, g_prev, gk, tol, iters);
        return br.second;
      }
      t_prev = tk;
      g_prev = gk;
    }
    return NAN;
  }

  // ---- projection onto C = 0, Ċ = 0 (mass-weighted) ------------------------------------------
  void project(double t) {
    for (int it = 0; it < 4; ++it) {
      tip_kinematics(model_, t, q_, qd_, tip_);
      if (std::abs(tip_.gap) <= 1e-15 * (model_.hub_radius + model_.length)) break;
      evaluate_mass(model_, q_, ws_);
      ws_.mass_llt.compute(ws_.mass);
      w_ = tip_.grad_gap;
      ws_.mass_llt.solveInPlace(w_);
      q_ -= (tip_.gap / tip_.grad_gap.dot(w_)) * w_;
    }
    tip_kinematics(model_, t, q_, qd_, tip_);
    evaluate_mass(model_, q_, ws_);
    ws_.mass_llt.compute(ws_.mass);
    w_ = tip_.grad_gap;
    ws_.mass_llt.solveInPlace(w_);
    qd_ -= (tip_.gap_rate / tip_.grad_gap.dot(w_)) * w_;
  }

  ContactLoad contact_load(double t) {
    const AccelerationMultiplier am = acceleration_multiplier(model_, friction_, t, q_, qd_, slip_, ws_, tip_);
    return rec_.load(t, q_, qd_, std::min(am.solution.lambda, 0.0), slip_);
  }

  // ---- phases -------------------------------------------------------------------------------
  void loop() {
    while (!done_) {
      if (instant_transitions_ > kMaxInstantTransitions) {
        rec_.fail("chatter", t_, "the tip switches between contact and free flight without time advancing");
        rec_.finish(t_, q_, qd_, phase_, {});
        return;
      }
      if (phase_ == Phase::free)
        free_flight();
      else
        contact();
    }
  }

  // One accepted step of the dense-output stepper; false (with a `step_underflow` failure recorded
  // and the pass finished) when the step-size control cannot meet the tolerance.
  bool step(double& ta, double& tb) {
    try {
      const auto interval = stepper_.do_step([this](const State& x, State& d, double t) { rhs(x, d, t); });
      ta = interval.first;
      tb = interval.second;
    } catch (const std::exception& e) {
      return fail_step(std::string("the step-size control failed: ") + e.what());
    }
    dt_ = stepper_.current_time_step();
    ++rec_.steps();
    const double min_step = kMinStepFraction * t_end_;
    if (!(tb > ta) || tb - ta < min_step)
      return fail_step("the accepted step " + short_number(tb - ta) + " s is below " + short_number(min_step) + " s");
    return true;
  }

  bool fail_step(const std::string& why) {
    rec_.fail("step_underflow", t_,
              why + " (rtol = " + short_number(opt_.rtol) + ", atol = " + short_number(opt_.atol) + ", last step " + short_number(dt_) +
                  " s): the tolerance cannot be met in double precision here");
    rec_.finish(t_, q_, qd_, phase_, load_);
    done_ = true;
    return false;
  }

  void reinitialize() {
    pack();
    stepper_.initialize(x_, t_, std::max(dt_, 1e-9));
  }

  void free_flight() {
    const double t_enter = t_;
    reinitialize();
    // Just after a bounce or a separation the tip sits on the surface (C ≈ 0) and recedes, after a
    // λ = 0 separation only tangentially (C̈ = 0), so the dense output's error can put C a hair above
    // zero: a root there is not an impact (SPEC §5). The detector is armed once the tip has been
    // below −ε; until then only a penetration beyond +ε counts. ε is ten times the local error
    // allowed on the tip position.
    const double eps = 10.0 * (opt_.atol + opt_.rtol * (model_.hub_radius + model_.length));
    bool armed = gap(model_, t_, q_) < -eps;
    double offset = armed ? 0.0 : eps;
    double g_prev = gap(model_, t_, q_) - offset;
    while (t_ < t_end_) {
      double ta = 0, tb = 0;
      if (!step(ta, tb)) return;
      const double te = std::min(tb, t_end_);
      auto g = [&](double t) {
        stepper_.calc_state(t, xs_);
        return state_gap(t, xs_) - offset;
      };
      const double root = first_root(g, ta, te, std::min(g_prev, -1e-300));
      if (!std::isnan(root)) {
        stepper_.calc_state(root, xs_);
        unpack(xs_);
        t_ = root;
        instant_transitions_ = (t_ - t_enter < 1e-12) ? instant_transitions_ + 1 : 0;
        rec_.accept(t_, q_, qd_, Phase::free, {}, {}, true);
        tip_kinematics(model_, t_, q_, qd_, tip_);
        if (tip_.gap_rate > 0.0) {
          impact();
        } else {
          begin_contact("touch without approach speed");
        }
        return;
      }
      if (te < tb) stepper_.calc_state(te, xs_);
      unpack(te < tb ? xs_ : stepper_.current_state());
      t_ = te;
      const double c_now = gap(model_, t_, q_);
      if (!armed && c_now < -eps) armed = true, offset = 0.0;
      g_prev = c_now - offset;
      if (!q_.allFinite() || !qd_.allFinite()) {
        rec_.fail("non_finite", t_, "the free-flight state became non-finite");
        break;
      }
      rec_.accept(t_, q_, qd_, Phase::free, {}, {});
      instant_transitions_ = 0;
      if (rec_.stop_requested(t_)) break;
    }
    rec_.finish(t_, q_, qd_, Phase::free, {});
    done_ = true;
  }

  // Momentum-balance impact at (t_, q_, qd_); chooses the next phase.
  bool impact() {
    if (rec_.impacts_exhausted(t_)) {
      rec_.finish(t_, q_, qd_, Phase::free, {});
      done_ = true;
      return false;
    }
    const Eigen::VectorXd before = qd_;
    const ImpactResult r = apply_impact(model_, law_, t_, q_, qd_, ws_, tip_);
    rec_.impact(t_, q_, before, qd_, r);
    if (r.vx_after < -1e-12 * std::abs(r.vx_before)) {
      phase_ = Phase::free;
      return true;
    }
    begin_contact(r.restitution == 0.0 ? "after a plastic impact" : "after an impact");
    return !done_;
  }

  void begin_contact(const std::string& why) {
    evaluate_dynamics(model_, q_, qd_, ws_);
    tip_kinematics(model_, t_, q_, qd_, tip_);
    const SlipDecision slip = decide_slip(model_, friction_, tip_, ws_);
    if (slip.kind == SlipDecision::Kind::stick) return fail_stick(slip);
    if (slip.kind == SlipDecision::Kind::separate) {
      rec_.event(t_, q_, "lift_off", detail::lift_off_message(slip.stick_normal));
      phase_ = Phase::free;
      ++instant_transitions_;
      return;
    }
    slip_ = slip.direction;
    const AccelerationMultiplier am = acceleration_multiplier(model_, friction_, t_, q_, qd_, slip_, ws_, tip_);
    if (am.solution.status != MultiplierSolution::Status::unique) return fail_painleve(t_, am.a, am.b, am.c);
    if (am.solution.lambda > 0.0) {
      rec_.event(t_, q_, "lift_off", "λ = " + short_number(am.solution.lambda) + " N > 0 at the touch: no sustained contact");
      phase_ = Phase::free;
      ++instant_transitions_;
      return;
    }
    rec_.contact_start(t_, q_, qd_, why);
    phase_ = Phase::contact;
    load_ = contact_load(t_);
  }

  void contact() {
    const double t_enter = t_;
    while (t_ < t_end_) {
      project(t_);
      reinitialize();
      painleve_ = false;
      const double lambda0 = std::min(state_lambda(t_, x_), 0.0);
      const double slip0 = state_slip_speed(t_, x_);
      double ta = 0, tb = 0;
      if (!step(ta, tb)) return;
      if (painleve_) return fail_painleve(painleve_t_, painleve_abc_[0], painleve_abc_[1], painleve_abc_[2]);
      const double te = std::min(tb, t_end_);
      // Separation: λ crosses 0 upward. Slip stop: s·V_t crosses 0 downward.
      auto g_lambda = [&](double t) {
        stepper_.calc_state(t, xs_);
        return state_lambda(t, xs_);
      };
      auto g_slip = [&](double t) {
        stepper_.calc_state(t, xs_);
        return -state_slip_speed(t, xs_);
      };
      const double t_sep = lambda0 < 0.0 ? first_root(g_lambda, ta, te, lambda0) : NAN;
      const double t_stop = slip0 > 0.0 ? first_root(g_slip, ta, te, -slip0) : NAN;
      double t_event = te;
      int kind = 0;  // 1 separation, 2 slip stop
      if (!std::isnan(t_sep)) t_event = t_sep, kind = 1;
      if (!std::isnan(t_stop) && t_stop < t_event) t_event = t_stop, kind = 2;
      if (t_event < tb || kind != 0) stepper_.calc_state(t_event, xs_);
      const State& xe = (t_event < tb || kind != 0) ? xs_ : stepper_.current_state();
      unpack(xe);
      const StepIntegrals integrals = integrals_of(xe);
      t_ = t_event;
      project(t_);
      if (!q_.allFinite() || !qd_.allFinite()) {
        rec_.fail("non_finite", t_, "the contact state became non-finite");
        rec_.finish(t_, q_, qd_, Phase::contact, load_);
        done_ = true;
        return;
      }
      if (kind == 1) {
        rec_.accept_integrated(t_, q_, qd_, Phase::contact, ContactLoad{}, integrals, true);
        rec_.contact_end(t_, q_, qd_, "λ reached 0");
        phase_ = Phase::free;
        instant_transitions_ = (t_ - t_enter < 1e-12) ? instant_transitions_ + 1 : 0;
        return;
      }
      load_ = contact_load(t_);
      rec_.accept_integrated(t_, q_, qd_, Phase::contact, load_, integrals, kind == 2);
      if (kind == 2) {
        evaluate_dynamics(model_, q_, qd_, ws_);
        tip_kinematics(model_, t_, q_, qd_, tip_);
        const SlipDecision d = decide_slip_at_rest(model_, friction_, tip_, ws_);
        if (d.kind == SlipDecision::Kind::stick) return fail_stick(d);
        if (d.kind == SlipDecision::Kind::separate) {
          rec_.contact_end(t_, q_, qd_, "the tip stopped sliding and lifts off");
          phase_ = Phase::free;
          return;
        }
        if (d.direction != slip_)
          rec_.event(t_, q_, "slip_reversal",
                     "V_t = 0; friction now acts toward " + std::string(d.direction > 0 ? "-Y" : "+Y"));
        slip_ = d.direction;
      }
      instant_transitions_ = 0;
      if (rec_.stop_requested(t_)) break;
    }
    rec_.finish(t_, q_, qd_, Phase::contact, load_);
    done_ = true;
  }

  void fail_painleve(double t, double a, double b, double c) {
    rec_.fail("painleve", t, detail::painleve_message(a, b, c));
    rec_.finish(t_, q_, qd_, Phase::contact, load_);
    done_ = true;
  }

  void fail_stick(const SlipDecision& s) {
    rec_.fail("stick", t_, detail::stick_message(s, effective_friction(friction_, tip_)));
    rec_.finish(t_, q_, qd_, Phase::stick, load_);
    done_ = true;
  }

  const Model& model_;
  const ImpactLaw& law_;
  const FrictionModel& friction_;
  const PassOptions& opt_;
  PassResult& result_;
  PassRecorder rec_;
  int n_;
  Workspace ws_, ews_;
  TipKinematics tip_, etip_;
  State x_, xs_;
  Eigen::VectorXd q_, qd_, qstar_, force_, w_;
  DenseStepper stepper_;
  Phase phase_ = Phase::free;
  double t_ = 0, t_end_ = 0, dt_ = 1e-7, slip_ = 0;
  ContactLoad load_;
  bool done_ = false;
  bool painleve_ = false;
  double painleve_t_ = 0, painleve_abc_[3] = {0, 0, 0};
  int instant_transitions_ = 0;
};

}  // namespace

PassResult run_adaptive_pass(const Model& model, const ImpactLaw& law, const FrictionModel& friction,
                             const InitialConditions& initial, const PassOptions& options) {
  return timed_pass("adaptive", [&](PassResult& result) {
    AdaptiveScheme scheme(model, law, friction, options, result);
    scheme.run(initial);
  });
}

}  // namespace rotbeam
