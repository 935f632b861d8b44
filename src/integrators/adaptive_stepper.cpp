// The adaptive event-driven scheme as a stepper (SPEC §6): Dormand–Prince 5(4) with dense output
// from Boost.Odeint, roots located on the dense output, projection onto the constraint in contact.
//
// State x = (q, q̇, W, W_f, I_n, I_m, W_d), or with the integrating factor (the default,
// integrating_factor.hpp) x = (v, W, …) where (η, η̇) = E(t − t_b) v are the linear modal
// coordinates: the linear oscillation about q = 0 is then exact and the pair's error control sees
// only the nonlinear remainder, so the step is no longer set by the highest mode's period. W = ∫q̇ᵀQ dt, W_f = ∫F_t V_t dt, I_n = ∫F_n dt, the contact
// force's angular impulse I_m = ∫(X_t F_Y − Y_t F_X) dt and the damping work W_d = −∫q̇ᵀCq̇ dt are
// integrated with the motion (under the same error control) and reset after every accepted contact
// step and at every start of free flight, so the energy audit and the integrals are as accurate as
// the tolerance.
//   free flight  q̈ = −M⁻¹Ψ; root C = 0 (upward)
//   contact      q̈ = M⁻¹(−Ψ + λ∇C + |λ|Q*) with λ from a λ + b|λ| = c at every evaluation;
//                roots λ = 0 (upward) and s_t V_t = 0 (downward); before each step q and q̇ are
//                projected (mass-weighted) onto C = 0 and Ċ = 0, and again at its end
//   compliant    (contact.model = "hertz") q̈ = M⁻¹(−Ψ + Q) with Q from contact_load at λ = −F_n,
//                F_n = hertz_normal_force(δ = C, δ̇ = Ċ) and the regularised slip: a smooth
//                right-hand side inside the contact, whose duration the error control resolves;
//                root C = 0 (downward, the contact's end); W_c = ∫ dissipation dt is integrated too
// Each step's dense output is sampled at interior points before root finding (TOMS 748), so a
// crossing and re-crossing within one step is still found; the largest normal force inside a
// contact step is found on the dense output too (Brent), and so is a whole rebound flight that fits
// inside one step (the lowest gap of the step arms the impact detector).
#include "rotbeam/integrating_factor.hpp"
#include "rotbeam/rigid_contact.hpp"
#include "rotbeam/stepper.hpp"
#include "rotbeam/detail/diagnostics.hpp"

#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint.hpp>
#include <array>
#include <cmath>
#include <functional>
#include <optional>

namespace rotbeam {

namespace {

namespace odeint = boost::numeric::odeint;
using State = std::vector<double>;
using DenseStepper = odeint::result_of::make_dense_output<odeint::runge_kutta_dopri5<State>>::type;

constexpr int kSamplesPerStep = 4;  // interior samples of the dense output per step (at least)
// Free flight samples the gap at least this many times per period of the highest linear mode, so
// that a step spanning several of its periods (the integrating factor allows it) misses no touch.
constexpr double kSamplesPerPeriod = 8.0;
constexpr int kIntegrals = 7;       // W, W_f, I_n, I_m, W_d, W_s, W_c after q and q̇ in the state
constexpr int kDampingWork = 4;     // W_d's place among them
constexpr int kSurfaceWork = 5;     // W_s's (a moving surface's work through friction)
constexpr int kContactDissipation = 6;  // W_c's (a compliant contact's damping)
constexpr int kBrentBits = 30;      // a maximum or minimum on the dense output to ~1e-9 of its bracket
// An accepted step shorter than this fraction of the pass means the tolerance cannot be met in
// double precision (at rtol ≥ 1e-13 the steps stay above ~1e-9 s for a pass of ~1e-2 s).
constexpr double kMinStepFraction = 1e-12;

using detail::short_number;

class AdaptiveStepper final : public Stepper {
public:
  AdaptiveStepper(const System& system, const PassOptions& options)
      : sys_(system),
        opt_(options),
        n_(system.beam.modes()),
        ws_(system.beam.make_workspace()),
        ews_(system.beam.make_workspace()),
        tip_(n_),
        etip_(n_),
        x_(2 * n_ + kIntegrals, 0.0),
        xs_(2 * n_ + kIntegrals, 0.0),
        q_(n_),
        qd_(n_),
        qstar_(n_),
        force_(n_),
        w_(n_),
        pq_(n_),
        pqd_(n_),
        pa_(n_),
        stepper_(odeint::make_dense_output(options.atol, options.rtol, options.max_step_s,
                                           odeint::runge_kutta_dopri5<State>())) {
    if (opt_.integrating_factor == FactorUse::always ||
        (opt_.integrating_factor == FactorUse::automatic && !sys_.beam.damped())) {
      factor_.emplace(sys_.beam.linearization());
      highest_hz_ = factor_->highest_frequency() / (2.0 * M_PI);
      // Rebase once στ reaches 1, or after 10⁶ radians of the highest mode (the phase Ωτ keeps its digits).
      factor_rebase_rate_ = factor_->largest_decay_rate() + 1e-6 * factor_->highest_frequency();
    }
  }

  StepperTraits traits() const override { return {Scheme::adaptive, true, true}; }

  void begin_free(const FilamentState& s, FreeStart start) override {
    phase_ = Phase::free;
    // A new flight starts with a small trial step: after an impact or a separation the previous
    // step size belongs to the motion before the jump, and a step that holds a whole short rebound
    // flight would leave its impact to the dense output's interpolant (measured: 1e-5 relative error
    // in the contact time with the integrating factor's longer steps, 2e-8 with the restart).
    dt_ = kInitialStep;
    t_ = s.t;
    q_ = s.q;
    qd_ = s.qd;
    reinitialize();
    free_damping_ = 0.0;
    // Just after a bounce or a separation the tip sits on the surface (C ≈ 0) and recedes, after a
    // λ = 0 separation only tangentially (C̈ = 0), so the dense output's error can put C a hair above
    // zero: a root there is not an impact (SPEC §5). The detector is armed once the tip has been
    // below −ε; until then only a penetration beyond +ε counts. ε is ten times the local error
    // allowed on the gap: Σ|∂C/∂q_i|·(atol + rtol·(|q_i| + h|q̇_i|)), the error control being on q.
    tip_kinematics(sys_.beam, sys_.surface, t_, q_, qd_, tip_);
    double allowed = 0.0;
    for (int i = 0; i < n_; ++i)
      allowed += std::abs(tip_.grad_gap[i]) * (opt_.atol + opt_.rtol * (std::abs(q_[i]) + dt_ * std::abs(qd_[i])));
    eps_ = 10.0 * allowed;
    const double c = tip_.gap;
    armed_ = c < -eps_;
    offset_ = armed_ ? 0.0 : eps_;
    g_prev_ = c - offset_;
  }

  void begin_contact(const FilamentState&, double) override { phase_ = Phase::contact; }

  void begin_compliant_contact(const FilamentState& s, double damping) override {
    phase_ = Phase::contact;
    damping_ = damping;
    dt_ = kInitialStep;
    t_ = s.t;
    q_ = s.q;
    qd_ = s.qd;
    reinitialize();
    marks_.fill(0.0);
  }

  StepOutcome step(FilamentState& s, double t_stop) override {
    if (s.phase == Phase::free) return free_step(s, t_stop);
    return compliant_ ? compliant_step(s, t_stop) : contact_step(s, t_stop);
  }

  const StepperStatistics& statistics() const override { return stats_; }

  bool interpolate(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd) override {
    if (phase_ != Phase::free) return false;
    stepper_.calc_state(t, xs_);  // the dense output of the last step, which holds t
    physical(t, xs_, q, qd);
    return true;
  }

private:
  // ---- state packing ------------------------------------------------------------------------
  // The integrated state is x = (q, q̇, integrals), or with the integrating factor
  // x = (v, integrals) with y = E(t − t_b) v (integrating_factor.hpp); the base time t_b is the
  // last (re)initialisation.
  void pack() {
    base_ = t_;
    if (factor_) {
      factor_->to_integration(q_.data(), qd_.data(), x_.data());
    } else {
      for (int i = 0; i < n_; ++i) {
        x_[i] = q_[i];
        x_[n_ + i] = qd_[i];
      }
    }
    for (int k = 0; k < kIntegrals; ++k) x_[2 * n_ + k] = 0.0;
  }
  // q, q̇ of the integrated state x at time t.
  template <class Q, class Qd>
  void physical(double t, const State& x, Q& q, Qd& qd) {
    if (factor_) {
      factor_->at(t - base_);
      factor_->to_physical(x.data(), q.data(), qd.data());
      return;
    }
    for (int i = 0; i < n_; ++i) {
      q[i] = x[i];
      qd[i] = x[n_ + i];
    }
  }
  void unpack(double t, const State& x) { physical(t, x, q_, qd_); }
  // Interior samples of a free-flight step of length h.
  int free_samples(double h) const {
    return std::max(kSamplesPerStep, static_cast<int>(std::ceil(kSamplesPerPeriod * h * highest_hz_)));
  }
  StepIntegrals integrals_of(const State& x) const {
    return {x[2 * n_],           x[2 * n_ + 1], x[2 * n_ + 2], x[2 * n_ + 3], 0.0, x[2 * n_ + kDampingWork],
            x[2 * n_ + kSurfaceWork], x[2 * n_ + kContactDissipation]};
  }
  void store(FilamentState& s) const {
    s.t = t_;
    s.q = q_;
    s.qd = qd_;
  }

  // ---- right-hand side ----------------------------------------------------------------------
  void rhs(const State& x, State& dxdt, double t) {
    ++stats_.rhs_evaluations;
    physical(t, x, pq_, pqd_);
    const Eigen::VectorXd& q = pq_;
    const Eigen::VectorXd& qd = pqd_;
    Eigen::VectorXd& a = pa_;
    if (phase_ == Phase::free) {
      acceleration(sys_.beam, q, qd, nullptr, *ws_, a);
      motion_derivative(dxdt);
      for (int k = 0; k < kIntegrals; ++k) dxdt[2 * n_ + k] = 0.0;
      if (damped_) dxdt[2 * n_ + kDampingWork] = -sys_.beam.dissipation(qd);
      return;
    }
    if (compliant_) {
      const HertzContact& hertz = sys_.law.hertz;
      tip_kinematics(sys_.beam, sys_.surface, t, q, qd, tip_);
      const double fn = hertz_normal_force(hertz, damping_, tip_.gap, tip_.gap_rate);
      const double slip = regularized_slip(tip_.slip_speed, hertz.friction_regularization_m_s);
      const ContactLoad load = contact_load(sys_.law.friction, tip_, qd, -fn, slip, force_);
      acceleration(sys_.beam, q, qd, &force_, *ws_, a);
      motion_derivative(dxdt);
      integral_rates(load, qd, hertz_dissipation_rate(hertz, fn, tip_.gap, tip_.gap_rate), dxdt);
      return;
    }
    const AccelerationMultiplier am =
        acceleration_multiplier(sys_.beam, sys_.surface, sys_.law.friction, t, q, qd, slip_, *ws_, tip_);
    if (am.solution.status != MultiplierSolution::Status::unique && !painleve_) {
      painleve_ = true;
      painleve_t_ = t;
      painleve_abc_[0] = am.a, painleve_abc_[1] = am.b, painleve_abc_[2] = am.c;
    }
    // Past a separation (λ > 0) the contact force is zero; the step is cut at λ = 0 anyway.
    const double lambda = std::min(am.solution.lambda, 0.0);
    const ContactLoad load = contact_load(sys_.law.friction, tip_, qd, lambda, slip_, force_);
    a = force_ - ws_->psi;
    ws_->mass_llt.solveInPlace(a);
    motion_derivative(dxdt);
    integral_rates(load, qd, 0.0, dxdt);
  }

  // The rates of the contact step's integrals (the ledger's terms) from its load, the beam's damping
  // at q̇ and a compliant contact's dissipation rate [W].
  void integral_rates(const ContactLoad& load, const Eigen::VectorXd& qd, double contact_dissipation, State& dxdt) {
    dxdt[2 * n_] = load.power;
    dxdt[2 * n_ + 1] = load.slip_power;
    dxdt[2 * n_ + 2] = load.normal_force;
    dxdt[2 * n_ + 3] = load.moment;
    dxdt[2 * n_ + kSurfaceWork] = load.surface_power;
    dxdt[2 * n_ + kDampingWork] = damped_ ? -sys_.beam.dissipation(qd) : 0.0;
    dxdt[2 * n_ + kContactDissipation] = contact_dissipation;
  }

  // The derivative of the motion's part of x from q̇ (pqd_) and q̈ (pa_) at the state of the last
  // physical() call.
  void motion_derivative(State& dxdt) {
    if (factor_) {
      factor_->derivative(pa_.data(), dxdt.data());
      return;
    }
    for (int i = 0; i < n_; ++i) {
      dxdt[i] = pqd_[i];
      dxdt[n_ + i] = pa_[i];
    }
  }

  // ---- root functions on the dense output ---------------------------------------------------
  double state_gap(double t, const State& x) {
    physical(t, x, pq_, pqd_);
    return gap(sys_.beam, sys_.surface, t, pq_);
  }
  double state_lambda(double t, const State& x) {
    physical(t, x, pq_, pqd_);
    return acceleration_multiplier(sys_.beam, sys_.surface, sys_.law.friction, t, pq_, pqd_, slip_, *ews_, etip_)
        .solution.lambda;
  }
  // The reported normal force for the multiplier just computed by state_lambda (etip_ at its state).
  double normal_force_of(double lambda) const {
    return reported_normal_force(sys_.law.friction, etip_, std::min(lambda, 0.0));
  }
  double state_slip_speed(double t, const State& x) {
    physical(t, x, pq_, pqd_);
    tip_kinematics(sys_.beam, sys_.surface, t, pq_, pqd_, etip_);
    return slip_ * etip_.slip_speed;
  }

  // First t in (ta, tb] where g changes from < 0 to ≥ 0, given g(ta) < 0, looked for at `samples`
  // interior points; NaN if none.
  double first_root(const std::function<double(double)>& g, double ta, double tb, double ga,
                    int samples = kSamplesPerStep) {
    double t_prev = ta, g_prev = ga;
    for (int k = 1; k <= samples; ++k) {
      const double tk = ta + (tb - ta) * k / samples;
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
      tip_kinematics(sys_.beam, sys_.surface, t, q_, qd_, tip_);
      if (std::abs(tip_.gap) <= 1e-15 * sys_.beam.tip_radius()) break;
      sys_.beam.evaluate_mass(q_, *ws_);
      w_ = tip_.grad_gap;
      ws_->mass_llt.solveInPlace(w_);
      q_ -= (tip_.gap / tip_.grad_gap.dot(w_)) * w_;
    }
    tip_kinematics(sys_.beam, sys_.surface, t, q_, qd_, tip_);
    sys_.beam.evaluate_mass(q_, *ws_);
    w_ = tip_.grad_gap;
    ws_->mass_llt.solveInPlace(w_);
    qd_ -= (tip_.gap_rate / tip_.grad_gap.dot(w_)) * w_;
  }

  void reinitialize() {
    pack();
    stepper_.initialize(x_, t_, std::max(dt_, 1e-9));
  }

  // One accepted step of the dense-output stepper; false (with `out` set to a step_underflow
  // failure at the current state) when the step-size control cannot meet the tolerance.
  bool advance(double t_stop, double& ta, double& tb, StepOutcome& out) {
    try {
      const auto interval = stepper_.do_step([this](const State& x, State& d, double t) { rhs(x, d, t); });
      ta = interval.first;
      tb = interval.second;
    } catch (const std::exception& e) {
      return underflow(std::string("the step-size control failed: ") + e.what(), out);
    }
    dt_ = stepper_.current_time_step();
    ++stats_.steps;
    const double min_step = kMinStepFraction * t_stop;
    if (!(tb > ta) || tb - ta < min_step)
      return underflow("the accepted step " + short_number(tb - ta) + " s is below " + short_number(min_step) + " s", out);
    return true;
  }

  bool underflow(const std::string& why, StepOutcome& out) {
    out = failed(FailureKind::step_underflow,
                 why + " (rtol = " + short_number(opt_.rtol) + ", atol = " + short_number(opt_.atol) + ", last step " +
                     short_number(dt_) + " s): the tolerance cannot be met in double precision here");
    return false;
  }

  StepOutcome failed(FailureKind kind, std::string message) const {
    StepOutcome out;
    out.status = StepStatus::failed;
    out.failure = NumericalFailure{kind, t_, 0.0, std::move(message)};
    return out;
  }

  StepOutcome free_step(FilamentState& s, double t_stop) {
    StepOutcome out;
    // With a damped mode the factor's E(−τ) grows like e^{στ}: the base moves up to the current
    // time (where the dense output's last step ends) before that costs digits.
    if (factor_ && stepper_.current_time() == t_ && (t_ - base_) * factor_rebase_rate_ > 1.0) {
      reinitialize();
      free_damping_ = 0.0;
    }
    double ta = 0, tb = 0;
    if (!advance(t_stop, ta, tb, out)) return out;
    const double te = std::min(tb, t_stop);
    auto gap_at = [&](double t) {
      stepper_.calc_state(t, xs_);
      return state_gap(t, xs_);
    };
    double t_from = ta, g_from = g_prev_;
    const int samples = free_samples(te - ta);
    if (!armed_) arm_within(gap_at, ta, te, samples, t_from, g_from);
    const double offset = offset_;
    auto g = [&](double t) { return gap_at(t) - offset; };
    const double root = first_root(g, t_from, te, std::min(g_from, -1e-300), samples);
    if (!std::isnan(root)) {
      stepper_.calc_state(root, xs_);
      unpack(root, xs_);
      t_ = root;
      store(s);
      out.integrals.damping_work = xs_[2 * n_ + kDampingWork] - free_damping_;
      out.status = StepStatus::root;
      out.root = Root::gap_closes;
      return out;
    }
    if (te < tb) stepper_.calc_state(te, xs_);
    const State& xe = te < tb ? xs_ : stepper_.current_state();
    unpack(te, xe);
    out.integrals.damping_work = xe[2 * n_ + kDampingWork] - free_damping_;
    free_damping_ = xe[2 * n_ + kDampingWork];
    if (!q_.allFinite() || !qd_.allFinite()) return failed(FailureKind::non_finite, "the free-flight state became non-finite");
    t_ = te;
    const double c_now = gap(sys_.beam, sys_.surface, t_, q_);
    if (!armed_ && c_now < -eps_) armed_ = true, offset_ = 0.0;
    g_prev_ = c_now - offset_;
    store(s);
    return out;
  }

  // Before the tip has been clear of the surface by ε, a whole rebound flight can fit inside one
  // step. The lowest gap of the step on the dense output decides: below −ε the detector arms there
  // (t_from, g_from) and the return to C = 0 after it is the next impact; otherwise a root counts
  // only beyond +ε (see begin_free).
  template <class GapAt>
  void arm_within(GapAt& gap_at, double ta, double te, int samples, double& t_from, double& g_from) {
    double c_low = INFINITY, t_left = ta, t_right = te;
    double t_prev = ta;
    for (int k = 1; k <= samples; ++k) {
      const double tk = ta + (te - ta) * k / samples;
      const double ck = gap_at(tk);
      if (ck < -eps_) {  // clear of the surface at this sample: arm here
        arm_at(tk, ck, t_from, g_from);
        return;
      }
      if (ck < c_low) c_low = ck, t_left = t_prev, t_right = std::min(tk + (te - ta) / samples, te);
      t_prev = tk;
    }
    boost::uintmax_t iters = 100;
    const auto low = boost::math::tools::brent_find_minima(gap_at, t_left, t_right, kBrentBits, iters);
    if (low.second < -eps_) arm_at(low.first, low.second, t_from, g_from);
  }

  void arm_at(double t, double c, double& t_from, double& g_from) {
    armed_ = true;
    offset_ = 0.0;
    t_from = t;
    g_from = c;
  }

  StepOutcome contact_step(FilamentState& s, double t_stop) {
    const FrictionModel& friction = sys_.law.friction;
    StepOutcome out;
    t_ = s.t;
    q_ = s.q;
    qd_ = s.qd;
    slip_ = s.slip;
    project(t_);
    store(s);  // the projected state is the start of the step (and the last good one)
    reinitialize();
    painleve_ = false;
    const double lambda0 = std::min(state_lambda(t_, x_), 0.0);
    load_start_ = normal_force_of(lambda0);
    const double slip0 = state_slip_speed(t_, x_);
    double ta = 0, tb = 0;
    if (!advance(t_stop, ta, tb, out)) return out;
    if (painleve_) {
      out = failed(FailureKind::painleve, detail::painleve_message(painleve_abc_[0], painleve_abc_[1], painleve_abc_[2]));
      out.failure->t = painleve_t_;
      return out;
    }
    const double te = std::min(tb, t_stop);
    // Separation: λ crosses 0 upward. Slip stop: s·V_t crosses 0 downward. λ is sampled at interior
    // points once, for the separation root and for the step's largest normal force.
    auto g_lambda = [&](double t) {
      stepper_.calc_state(t, xs_);
      return state_lambda(t, xs_);
    };
    auto g_slip = [&](double t) {
      stepper_.calc_state(t, xs_);
      return -state_slip_speed(t, xs_);
    };
    std::array<double, kSamplesPerStep + 1> ts{}, fn{};
    ts[0] = ta;
    fn[0] = load_start_;
    int sampled = 0;
    double t_sep = NAN;
    if (lambda0 < 0.0) {
      double l_prev = lambda0;
      for (int k = 1; k <= kSamplesPerStep; ++k) {
        ts[k] = ta + (te - ta) * k / kSamplesPerStep;
        const double lk = g_lambda(ts[k]);
        fn[k] = normal_force_of(lk);
        sampled = k;
        if (l_prev < 0.0 && lk >= 0.0) {
          boost::uintmax_t iters = 200;
          const double tol_s = opt_.event_tolerance_s;
          const auto tol = [tol_s](double a, double b) { return std::abs(b - a) <= tol_s; };
          t_sep = boost::math::tools::toms748_solve(g_lambda, ts[k - 1], ts[k], l_prev, lk, tol, iters).second;
          break;
        }
        l_prev = lk;
      }
    }
    const double t_slip = slip0 > 0.0 ? first_root(g_slip, ta, te, -slip0) : NAN;
    double t_event = te;
    Root root = Root::none;
    if (!std::isnan(t_sep)) t_event = t_sep, root = Root::multiplier_vanishes;
    if (!std::isnan(t_slip) && t_slip < t_event) t_event = t_slip, root = Root::slip_stops;
    const double peak = step_peak(ts, fn, sampled, t_event, g_lambda);
    if (t_event < tb || root != Root::none) stepper_.calc_state(t_event, xs_);
    const State& xe = (t_event < tb || root != Root::none) ? xs_ : stepper_.current_state();
    unpack(t_event, xe);
    out.integrals = integrals_of(xe);
    const double t_start = t_;
    t_ = t_event;
    project(t_);
    if (!q_.allFinite() || !qd_.allFinite()) {
      t_ = t_start;
      return failed(FailureKind::non_finite, "the contact state became non-finite");
    }
    store(s);
    out.root = root;
    out.status = root == Root::none ? StepStatus::advanced : StepStatus::root;
    out.integrals.peak_normal_force = peak;
    if (root == Root::multiplier_vanishes) return out;
    const AccelerationMultiplier am =
        acceleration_multiplier(sys_.beam, sys_.surface, friction, t_, q_, qd_, slip_, *ws_, tip_);
    out.load = contact_load(friction, tip_, qd_, std::min(am.solution.lambda, 0.0), slip_, force_);
    out.integrals.peak_normal_force = std::max(peak, out.load.normal_force);
    return out;
  }

  // The compliant contact at (t, q, q̇) of a dense-output state: tip kinematics into etip_, F_n returned.
  double compliant_force(double t, const State& x) {
    physical(t, x, pq_, pqd_);
    tip_kinematics(sys_.beam, sys_.surface, t, pq_, pqd_, etip_);
    return hertz_normal_force(sys_.law.hertz, damping_, etip_.gap, etip_.gap_rate);
  }

  // One step of a compliant (Hertz) contact: the force is a smooth function of the state, so the
  // step is an ordinary error-controlled step (no projection); the contact ends where C crosses 0
  // downward (looked for at interior samples of the dense output, then TOMS 748), and the step's
  // largest F_n is found on the samples and refined by Brent between the best one's neighbours.
  StepOutcome compliant_step(FilamentState& s, double t_stop) {
    StepOutcome out;
    const bool rebase = factor_ && (t_ - base_) * factor_rebase_rate_ > 1.0;
    if (stepper_.current_time() != s.t || t_ != s.t || rebase) {  // cut at a section, or the factor's base moves
      t_ = s.t;
      q_ = s.q;
      qd_ = s.qd;
      reinitialize();
      marks_.fill(0.0);
    }
    const double c_start = gap(sys_.beam, sys_.surface, t_, q_);
    double ta = 0, tb = 0;
    if (!advance(t_stop, ta, tb, out)) return out;
    const double te = std::min(tb, t_stop);
    auto opening = [&](double t) {  // −C: negative inside the contact
      stepper_.calc_state(t, xs_);
      return -state_gap(t, xs_);
    };
    std::array<double, kSamplesPerStep + 1> ts{}, fn{};
    ts[0] = ta;
    stepper_.calc_state(ta, xs_);
    fn[0] = compliant_force(ta, xs_);
    double g_prev = std::min(-c_start, -1e-300);
    double t_end = te;
    Root root = Root::none;
    int sampled = 0;
    for (int k = 1; k <= kSamplesPerStep; ++k) {
      ts[k] = ta + (te - ta) * k / kSamplesPerStep;
      stepper_.calc_state(ts[k], xs_);
      fn[k] = compliant_force(ts[k], xs_);
      const double gk = -etip_.gap;
      sampled = k;
      if (g_prev < 0.0 && gk >= 0.0) {
        boost::uintmax_t iters = 200;
        const double tol_s = opt_.event_tolerance_s;
        const auto tol = [tol_s](double a, double b) { return std::abs(b - a) <= tol_s; };
        t_end = boost::math::tools::toms748_solve(opening, ts[k - 1], ts[k], g_prev, gk, tol, iters).second;
        root = Root::gap_opens;
        break;
      }
      g_prev = gk;
    }
    auto force_at = [&](double t) {
      stepper_.calc_state(t, xs_);
      return compliant_force(t, xs_);
    };
    const double peak = sampled_peak(ts, fn, sampled, t_end, force_at);
    if (t_end < tb) stepper_.calc_state(t_end, xs_);
    const State& xe = t_end < tb ? xs_ : stepper_.current_state();
    unpack(t_end, xe);
    if (!q_.allFinite() || !qd_.allFinite()) return failed(FailureKind::non_finite, "the compliant contact state became non-finite");
    const StepIntegrals total = integrals_of(xe);
    out.integrals = total;
    out.integrals.work -= marks_[0];
    out.integrals.friction_work -= marks_[1];
    out.integrals.normal_impulse -= marks_[2];
    out.integrals.contact_moment -= marks_[3];
    out.integrals.damping_work -= marks_[4];
    out.integrals.surface_work -= marks_[5];
    out.integrals.contact_dissipation -= marks_[6];
    marks_ = {total.work, total.friction_work, total.normal_impulse, total.contact_moment, total.damping_work,
              total.surface_work, total.contact_dissipation};
    t_ = t_end;
    store(s);
    tip_kinematics(sys_.beam, sys_.surface, t_, q_, qd_, tip_);
    const HertzContact& hertz = sys_.law.hertz;
    const double slip = regularized_slip(tip_.slip_speed, hertz.friction_regularization_m_s);
    s.slip = slip;
    const double f_end = root == Root::none ? hertz_normal_force(hertz, damping_, tip_.gap, tip_.gap_rate) : 0.0;
    out.load = contact_load(sys_.law.friction, tip_, qd_, -f_end, slip, force_);
    out.load.slip = slip;
    out.integrals.peak_normal_force = std::max(peak, f_end);
    out.root = root;
    out.status = root == Root::none ? StepStatus::advanced : StepStatus::root;
    return out;
  }

  // The largest of the sampled forces fn at ts[0..sampled] before t_end, refined by Brent's
  // maximisation of force_at between the best sample's neighbours when it is an interior one.
  template <class ForceAt>
  double sampled_peak(const std::array<double, kSamplesPerStep + 1>& ts, const std::array<double, kSamplesPerStep + 1>& fn,
                      int sampled, double t_end, ForceAt& force_at) {
    int best = 0, last = 0;
    for (int k = 0; k <= sampled && ts[k] < t_end; ++k) {
      last = k;
      if (fn[k] > fn[best]) best = k;
    }
    const double peak = fn[best];
    if (best == 0 || sampled == 0) return peak;
    const double lo = ts[best - 1], hi = best < last ? ts[best + 1] : t_end;
    auto minus = [&](double t) { return -force_at(t); };
    boost::uintmax_t iters = 100;
    const auto found = boost::math::tools::brent_find_minima(minus, lo, hi, kBrentBits, iters);
    return std::max(peak, -found.second);
  }

  // The largest normal force of a contact step: the sampled values on [ta, t_event) and, where the
  // largest sample is inside that range, Brent's maximisation on the dense output between its
  // neighbours (a maximum inside a step is not lost to the step ends).
  template <class Lambda>
  double step_peak(const std::array<double, kSamplesPerStep + 1>& ts, const std::array<double, kSamplesPerStep + 1>& fn,
                   int sampled, double t_event, Lambda& g_lambda) {
    int best = 0;
    int last = 0;  // the last sample before the step's end event
    for (int k = 0; k <= sampled && ts[k] < t_event; ++k) {
      last = k;
      if (fn[k] > fn[best]) best = k;
    }
    double peak = fn[best];
    if (best == 0 || sampled == 0) return peak;
    const double lo = ts[best - 1], hi = best < last ? ts[best + 1] : t_event;
    auto minus_fn = [&](double t) { return -normal_force_of(g_lambda(t)); };
    boost::uintmax_t iters = 100;
    const auto found = boost::math::tools::brent_find_minima(minus_fn, lo, hi, kBrentBits, iters);
    return std::max(peak, -found.second);
  }

  const System sys_;
  const PassOptions opt_;
  int n_;
  std::unique_ptr<BeamWorkspace> ws_, ews_;
  TipKinematics tip_, etip_;
  State x_, xs_;
  Eigen::VectorXd q_, qd_, qstar_, force_, w_;
  Eigen::VectorXd pq_, pqd_, pa_;  // q, q̇, q̈ of a state being evaluated (rhs, root functions)
  std::optional<IntegratingFactor> factor_;  // opt_.integrating_factor
  double highest_hz_ = 0;                    // the highest linear mode [Hz] (0 without the factor)
  double base_ = 0;                          // t_b of the integrating factor [s]
  double factor_rebase_rate_ = 0;            // [1/s]: the base moves when (t − t_b)·rate > 1
  DenseStepper stepper_;
  StepperStatistics stats_;
  Phase phase_ = Phase::free;
  static constexpr double kInitialStep = 1e-7;  // the first trial step of a run or revolution [s]
  double t_ = 0, dt_ = kInitialStep, slip_ = 0;
  double load_start_ = 0;  // F_n at the (projected) start of the current contact step [N]
  const bool damped_ = sys_.beam.damped();
  double free_damping_ = 0;  // W_d of the free flight at the last reported point [J]
  // The free-flight gap detector (see begin_free).
  double eps_ = 0, offset_ = 0, g_prev_ = 0;
  bool armed_ = false;
  bool painleve_ = false;
  double painleve_t_ = 0, painleve_abc_[3] = {0, 0, 0};
  // The compliant law (contact.model = "hertz"): its damping c [s/m] for the contact under way, and
  // the integrals at the last reported point since the last (re)initialisation.
  const bool compliant_ = sys_.law.model == ContactModel::hertz;
  double damping_ = 0;
  std::array<double, kIntegrals> marks_{};
};

}  // namespace

std::unique_ptr<Stepper> make_adaptive_stepper(const System& system, const PassOptions& options) {
  return std::make_unique<AdaptiveStepper>(system, options);
}

}  // namespace rotbeam
