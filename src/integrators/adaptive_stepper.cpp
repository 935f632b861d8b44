// The adaptive event-driven scheme as a stepper (docs/model.md §6): Dormand–Prince 5(4) with dense output
// from Boost.Odeint, roots located on the dense output, the contact law's phases integrated as it
// says (contact_law.hpp).
//
// State x = (q, q̇, L), or with the integrating factor (the default, integrating_factor.hpp)
// x = (v, L) where (η, η̇) = E(t − t_b) v are the linear modal coordinates: the linear oscillation
// about q = 0 is then exact and the pair's error control sees only the nonlinear remainder, so the
// step is no longer set by the highest mode's period. L holds the ledger's terms (ledger.hpp),
// integrated with the motion under the same error control from the rates the contact law gives
// (and the beam's damping), so the energy audit and the integrals are as accurate as the tolerance.
//   free flight      q̈ = −M⁻¹Ψ; root C = 0 (upward)
//   a constraint     (the rigid law's sliding contact) q̈ = M⁻¹(−Ψ + Q) with Q from the law at every
//                    evaluation (λ from a λ + b|λ| = c); before each step q and q̇ are projected
//                    (mass-weighted) onto C = 0 and Ċ = 0, and again at its end; L restarts each step
//   a force          (the compliant law) q̈ = M⁻¹(−Ψ + Q): a smooth right-hand side inside the
//                    contact, whose duration the error control resolves; L runs on, each step reports
//                    its increment
// Each step's dense output is sampled at interior points before root finding (TOMS 748), so a
// crossing and re-crossing within one step is still found; the first root of a contact phase is
// sampled with the normal force, whose largest value inside the step is found on the dense output too
// (Brent), and so is a whole rebound flight that fits inside one step (the lowest gap of the step
// arms the impact detector).
#include "rotbeam/integrating_factor.hpp"
#include "rotbeam/stepper.hpp"
#include "rotbeam/tangent.hpp"
#include "rotbeam/detail/diagnostics.hpp"

#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint.hpp>
#include <array>
#include <span>
#include <stdexcept>
#include <cmath>
#include <functional>
#include <optional>

namespace rotbeam {

namespace {

namespace odeint = boost::numeric::odeint;
using State = std::vector<double>;

// Odeint's default error checker (the largest of |err_i| / (atol + rtol(|x_i| + h|ẋ_i|)), computed as
// it computes it) over the components that steer the steps: the motion and the balance's terms. The
// terms reported beside the balance (ledger.hpp: frictional heat, Archard's load–distance) ride along
// on the steps the others choose, so adding such a term changes no step of a pass.
class SteeringErrorChecker {
public:
  using value_type = double;
  using algebra_type = odeint::range_algebra;
  using operations_type = odeint::default_operations;

  SteeringErrorChecker(double eps_abs = 1e-6, double eps_rel = 1e-6, std::vector<char> steers = {})
      : eps_abs_(eps_abs), eps_rel_(eps_rel), steers_(std::move(steers)) {}

  template <class S, class D, class E, class T>
  double error(const S& x_old, const D& dxdt_old, E& x_err, T dt) const {
    double worst = 0.0;
    const double a_dxdt = std::abs(dt);
    for (std::size_t i = 0; i < x_err.size(); ++i) {
      if (i < steers_.size() && !steers_[i]) continue;
      const double e = std::abs(x_err[i]) / (eps_abs_ + eps_rel_ * (1.0 * std::abs(x_old[i]) + a_dxdt * std::abs(dxdt_old[i])));
      worst = std::max(worst, e);
    }
    return worst;
  }
  template <class S, class D, class E, class T>
  double error(algebra_type&, const S& x_old, const D& dxdt_old, E& x_err, T dt) const {
    return error(x_old, dxdt_old, x_err, dt);
  }

private:
  double eps_abs_, eps_rel_;
  std::vector<char> steers_;  // per component; components past its end steer
};

using Controlled = odeint::controlled_runge_kutta<odeint::runge_kutta_dopri5<State>, SteeringErrorChecker,
                                                  odeint::default_step_adjuster<double, double>, odeint::initially_resizer,
                                                  odeint::explicit_error_stepper_fsal_tag>;
using DenseStepper = odeint::dense_output_runge_kutta<Controlled, odeint::explicit_controlled_stepper_fsal_tag>;

// The state's components that steer the steps: all but the ledger's terms reported beside the balance
// and the variational equations' Φ (`tangent` components after them), which ride on the motion's steps.
std::vector<char> steering_components(int n, int tangent) {
  std::vector<char> steers(2 * n + kIntegratedTermCount + tangent, 1);
  for (int k = 0; k < tangent; ++k) steers[2 * n + kIntegratedTermCount + k] = 0;
  for (std::size_t k = 0; k < kIntegratedTermCount; ++k)
    if (ledger_term_info(kIntegratedTerms[k]).report == LedgerReport::beside) steers[2 * n + k] = 0;
  return steers;
}

constexpr int kSamplesPerStep = 4;  // interior samples of the dense output per step (at least)
// Free flight samples the gap at least this many times per period of the highest linear mode, so
// that a step spanning several of its periods (the integrating factor allows it) misses no touch.
constexpr double kSamplesPerPeriod = 8.0;
// The ledger's integrated terms after q and q̇ in the state (ledger.hpp: kIntegratedTerms), and the
// beam's damping work's place among them.
constexpr int kLedger = static_cast<int>(kIntegratedTermCount);
constexpr int kDampingWork = [] {
  for (int k = 0; k < kLedger; ++k)
    if (kIntegratedTerms[k] == LedgerTerm::damping_work) return k;
  return -1;
}();
static_assert(kDampingWork >= 0, "the beam's damping work is integrated");
constexpr int kBrentBits = 30;      // a maximum or minimum on the dense output to ~1e-9 of its bracket
// An accepted step shorter than this fraction of the pass means the tolerance cannot be met in
// double precision (at rtol ≥ 1e-13 the steps stay above ~1e-9 s for a pass of ~1e-2 s).
constexpr double kMinStepFraction = 1e-12;

using detail::short_number;
using Samples = std::array<double, kSamplesPerStep + 1>;

class AdaptiveStepper final : public Stepper {
public:
  AdaptiveStepper(const System& system, const PassOptions& options)
      : sys_(system),
        law_(system.law),
        opt_(options),
        n_(system.beam.modes()),
        ws_(system.beam.make_workspace()),
        ews_(system.beam.make_workspace()),
        tip_(n_),
        etip_(n_),
        tangent_(options.tangent ? 4 * n_ * n_ : 0),
        x_(2 * n_ + kLedger + tangent_, 0.0),
        xs_(2 * n_ + kLedger + tangent_, 0.0),
        q_(n_),
        qd_(n_),
        force_(n_),
        w_(n_),
        w2_(n_),
        pq_(n_),
        pqd_(n_),
        pa_(n_),
        stepper_(Controlled(SteeringErrorChecker(options.atol, options.rtol, steering_components(n_, tangent_)),
                            odeint::default_step_adjuster<double, double>(options.max_step_s),
                            odeint::runge_kutta_dopri5<State>())) {
    if (opt_.integrating_factor == FactorUse::always ||
        (opt_.integrating_factor == FactorUse::automatic && !sys_.beam.damped())) {
      factor_.emplace(sys_.beam.linearization());
      highest_hz_ = factor_->highest_frequency() / (2.0 * M_PI);
      // Rebase once στ reaches 1, or after 10⁶ radians of the highest mode (the phase Ωτ keeps its digits).
      factor_rebase_rate_ = factor_->largest_decay_rate() + 1e-6 * factor_->highest_frequency();
    }
    if (tangent_) {
      tws_.emplace(sys_.beam);
      phi_ = Eigen::MatrixXd::Identity(2 * n_, 2 * n_);
      jq_.resize(n_, n_);
      jqd_.resize(n_, n_);
      dq_.resize(n_);
      dqd_.resize(n_);
      dqdd_.resize(n_);
    }
  }

  StepperTraits traits() const override { return {Scheme::adaptive, true, true, true}; }

  void begin_free(const FilamentState& s, FreeStart) override {
    phase_ = Phase::free;
    // A new flight starts with a small trial step: after an impact or a separation the previous
    // step size belongs to the motion before the jump, and a step that holds a whole short rebound
    // flight would leave its impact to the dense output's interpolant (measured: 1e-5 relative error
    // in the contact time with the integrating factor's longer steps, 2e-8 with the restart).
    dt_ = kInitialStep;
    t_ = s.t;
    q_ = s.q;
    qd_ = s.qd;
    take_tangent(s);
    reinitialize();
    free_damping_ = 0.0;
    // Just after a bounce or a separation the tip sits on the surface (C ≈ 0) and recedes, after a
    // λ = 0 separation only tangentially (C̈ = 0), so the dense output's error can put C a hair above
    // zero: a root there is not an impact (docs/model.md §5). The detector is armed once the tip has been
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

  // A constraint restarts at every step (contact_step); a force phase starts its integration here.
  void begin_contact(const FilamentState& s) override {
    phase_ = s.phase;
    episode_ = s.episode;
    if (law_.kind(phase_) != PhaseKind::force) return;
    dt_ = kInitialStep;
    t_ = s.t;
    q_ = s.q;
    qd_ = s.qd;
    take_tangent(s);
    reinitialize();
    marks_ = {};
  }

  StepOutcome step(FilamentState& s, double t_stop) override {
    if (s.phase == Phase::free) return free_step(s, t_stop);
    return contact_step(s, t_stop);
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
  // The integrated state is x = (q, q̇, L), or with the integrating factor x = (v, L) with
  // y = E(t − t_b) v (integrating_factor.hpp); the base time t_b is the last (re)initialisation.
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
    for (int k = 0; k < kLedger; ++k) x_[2 * n_ + k] = 0.0;
    for (int c = 0; c < 2 * n_ && tangent_; ++c) {
      double* v = x_.data() + 2 * n_ + kLedger + 2 * n_ * c;
      if (factor_) {
        factor_->to_integration(phi_.col(c).data(), phi_.col(c).data() + n_, v);
      } else {
        for (int i = 0; i < 2 * n_; ++i) v[i] = phi_(i, c);
      }
    }
  }
  // Φ from the state passed to begin_free, begin_contact or a constraint's step.
  void take_tangent(const FilamentState& s) {
    if (!tangent_) return;
    phi_ = s.tangent;
    ptan_ = s.episode_tangent;
    ptan_rows_ = 0;
    for (int k = 0; k < ptan_.rows(); ++k)
      if (ptan_.row(k).cwiseAbs().maxCoeff() > 0.0) ptan_rows_ |= 1u << k;
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
  void unpack(double t, const State& x) {
    physical(t, x, q_, qd_);
    for (int c = 0; c < 2 * n_ && tangent_; ++c) {
      const double* v = x.data() + 2 * n_ + kLedger + 2 * n_ * c;
      if (factor_) {
        factor_->to_physical(v, phi_.col(c).data(), phi_.col(c).data() + n_);
      } else {
        for (int i = 0; i < 2 * n_; ++i) phi_(i, c) = v[i];
      }
    }
  }
  // Interior samples of a free-flight step of length h.
  int free_samples(double h) const {
    return std::max(kSamplesPerStep, static_cast<int>(std::ceil(kSamplesPerPeriod * h * highest_hz_)));
  }
  // The ledger's integrals held in x.
  LedgerValues ledger_of(const State& x) const {
    LedgerValues l;
    for (int k = 0; k < kLedger; ++k) l[kIntegratedTerms[k]] = x[2 * n_ + k];
    return l;
  }
  void store(FilamentState& s) const {
    s.t = t_;
    s.q = q_;
    s.qd = qd_;
    if (tangent_) {
      s.tangent = phi_;
      s.episode_tangent = ptan_;
    }
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
      for (int k = 0; k < kLedger; ++k) dxdt[2 * n_ + k] = 0.0;
      if (damped_) dxdt[2 * n_ + kDampingWork] = -sys_.beam.dissipation(qd);
      if (tangent_) tangent_derivative(t, x, dxdt);
      return;
    }
    const ContactEvaluation e = law_.evaluate(sys_, episode_, t, q, qd, *ws_, tip_, force_);
    if (!e.admissible && (!inadmissible_ || t < inadmissible_t_)) {
      inadmissible_ = true;
      inadmissible_t_ = t;
      inadmissible_at_ = e;
    }
    a = force_ - ws_->psi;
    ws_->mass_llt.solveInPlace(a);
    motion_derivative(dxdt);
    for (int k = 0; k < kLedger; ++k) dxdt[2 * n_ + k] = e.load.rate[kIntegratedTerms[k]];
    dxdt[2 * n_ + kDampingWork] = damped_ ? -sys_.beam.dissipation(qd) : 0.0;
    if (tangent_) tangent_derivative(t, x, dxdt);
  }

  // Φ̇ = A Φ (tangent.hpp) into dxdt's tangent part, at the state of the last physical() call (pq_, pqd_);
  // with the integrating factor each column of Φ is carried in the factor's variables like the state.
  void tangent_derivative(double t, const State& x, State& dxdt) {
    phase_jacobian(sys_, phase_, episode_, t, pq_, pqd_, *tws_, jq_, jqd_);
    // An episode whose parameters the touch set from the state: Φ̇ = AΦ + (0, ∂q̈/∂p) ∂p/∂x₀.
    const bool forced = phase_ != Phase::free && ptan_rows_ != 0;
    if (forced) parameter_field(sys_, phase_, episode_, t, pq_, pqd_, ptan_rows_, *tws_);
    for (int c = 0; c < 2 * n_; ++c) {
      const double* v = x.data() + 2 * n_ + kLedger + 2 * n_ * c;
      double* dv = dxdt.data() + 2 * n_ + kLedger + 2 * n_ * c;
      if (factor_) {
        factor_->to_physical(v, dq_.data(), dqd_.data());
      } else {
        for (int i = 0; i < n_; ++i) dq_[i] = v[i], dqd_[i] = v[n_ + i];
      }
      dqdd_.noalias() = jq_ * dq_;
      dqdd_.noalias() += jqd_ * dqd_;
      if (forced) dqdd_.noalias() += tws_->parameter_field * ptan_.col(c);
      if (factor_) {
        factor_->derivative(dqdd_.data(), dv);
      } else {
        for (int i = 0; i < n_; ++i) dv[i] = dqd_[i], dv[n_ + i] = dqdd_[i];
      }
    }
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
  // The contact law's sample (its first root and the normal force) at the dense output's time t.
  ContactSample state_sample(double t) {
    stepper_.calc_state(t, xs_);
    physical(t, xs_, pq_, pqd_);
    return law_.sample(sys_, episode_, t, pq_, pqd_, *ews_, etip_);
  }
  // The contact law's root k at the dense output's time t.
  double state_root(int k, double t) {
    stepper_.calc_state(t, xs_);
    physical(t, xs_, pq_, pqd_);
    return law_.root_value(phase_, k, sys_, episode_, t, pq_, pqd_, *ews_, etip_);
  }

  // First t in (ta, tb] where a root function changes from < 0 to ≥ 0, given its value ga < 0 at ta:
  // `sampled(k, t)` gives its value at the k-th of `samples` interior points (and may record what it
  // computes there), `refined(t)` at the points TOMS 748 asks for while closing the bracket to
  // options.event_tolerance_s; NaN if none. `sampled_last` is the last sample taken.
  template <class Sampled, class Refined>
  double first_root(Sampled&& sampled, Refined&& refined, double ta, double tb, double ga, int samples,
                    int* sampled_last = nullptr) {
    double t_prev = ta, g_prev = ga;
    for (int k = 1; k <= samples; ++k) {
      const double tk = ta + (tb - ta) * k / samples;
      const double gk = sampled(k, tk);
      if (sampled_last) *sampled_last = k;
      if (g_prev < 0.0 && gk >= 0.0) {
        boost::uintmax_t iters = 200;
        const double tol_s = opt_.event_tolerance_s;
        const auto tol = [tol_s](double a, double b) { return std::abs(b - a) <= tol_s; };
        const auto br = boost::math::tools::toms748_solve(refined, t_prev, tk, g_prev, gk, tol, iters);
        return br.second;
      }
      t_prev = tk;
      g_prev = gk;
    }
    return NAN;
  }
  template <class G>
  double first_root(G&& g, double ta, double tb, double ga, int samples = kSamplesPerStep) {
    return first_root([&g](int, double t) { return g(t); }, g, ta, tb, ga, samples);
  }

  // ---- projection onto C = 0, Ċ = 0 (mass-weighted), and V_t = 0 for a locked phase ------------
  void project(double t, bool locked) {
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
    const double ann = tip_.grad_gap.dot(w_);
    if (locked) {
      // Ċ and V_t are linear in q̇: q̇ −= M⁻¹W (WᵀM⁻¹W)⁻¹ (Ċ, V_t) with W = (∇C, ∂V_t/∂q̇) is exact. Where
      // the two are parallel (locked_tip_forces' `dependent`) holding Ċ = 0 is all there is to hold.
      w2_ = tip_.grad_tangent;
      ws_->mass_llt.solveInPlace(w2_);
      const double ant = tip_.grad_gap.dot(w2_), att = tip_.grad_tangent.dot(w2_);
      const double det = ann * att - ant * ant;
      if (det > 1e-12 * ann * att) {
        const double rn = tip_.gap_rate, rt = tip_.slip_speed;
        const double fn = (att * rn - ant * rt) / det, ft = (ann * rt - ant * rn) / det;
        qd_ -= fn * w_ + ft * w2_;
        return;
      }
    }
    qd_ -= (tip_.gap_rate / ann) * w_;
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
    if (tangent_) stats_.tangent_evaluations = tws_->field_evaluations;
    const double min_step = kMinStepFraction * t_stop;
    if (!(tb > ta) || tb - ta < min_step)
      return underflow("the accepted step " + short_number(tb - ta) + " s is below " + short_number(min_step) + " s", out);
    return true;
  }

  bool underflow(const std::string& why, StepOutcome& out) {
    out = failed(FailureKind::step_underflow,
                 why + " (rtol = " + short_number(opt_.rtol) + ", atol = " + short_number(opt_.atol) + ", last step " +
                     short_number(dt_) + " s): the tolerance cannot be met in double precision here; raise "
                     "simulation.rtol and simulation.atol, or where a contact stiffens it, contact.model = "
                     "\"hertz\" with a smaller contact.stiffness_factor");
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
      out.integrals.integral[LedgerTerm::damping_work] = xs_[2 * n_ + kDampingWork] - free_damping_;
      out.integrals.peak_tip_deflection = interior_deflection_peak(ta, root, s.q, q_);  // (overwrites xs_)
      t_ = root;
      store(s);
      out.status = StepStatus::root;
      out.root = Root::gap_closes;
      return out;
    }
    if (te < tb) stepper_.calc_state(te, xs_);
    const State& xe = te < tb ? xs_ : stepper_.current_state();
    unpack(te, xe);
    out.integrals.integral[LedgerTerm::damping_work] = xe[2 * n_ + kDampingWork] - free_damping_;
    free_damping_ = xe[2 * n_ + kDampingWork];
    out.integrals.peak_tip_deflection = interior_deflection_peak(ta, te, s.q, q_);
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

  // One step of a contact phase of the law (contact_law.hpp). A constraint is projected onto C = 0,
  // Ċ = 0 and restarted at the step's start and projected again at its end; a force phase runs on
  // (restarted where a section cut the step or the integrating factor's base moves). The law's first
  // root is sampled at interior points of the dense output together with the normal force, its other
  // roots on their own; the earliest crossing ends the step, and the step's largest normal force is
  // found on the samples and refined by Brent between the best one's neighbours.
  StepOutcome contact_step(FilamentState& s, double t_stop) {
    StepOutcome out;
    phase_ = s.phase;  // a law may change the phase inside an episode (stick and slip)
    const PhaseKind kind = law_.kind(s.phase);
    const bool constraint = kind != PhaseKind::force, locked = kind == PhaseKind::locked;
    episode_ = s.episode;
    if (constraint) {
      t_ = s.t;
      q_ = s.q;
      qd_ = s.qd;
      take_tangent(s);
      project(t_, locked);
      store(s);  // the projected state is the start of the step (and the last good one)
      reinitialize();
      physical(t_, x_, pq_, pqd_);
    } else {
      const bool rebase = factor_ && (t_ - base_) * factor_rebase_rate_ > 1.0;
      if (stepper_.current_time() != s.t || t_ != s.t || rebase) {  // cut at a section, or the factor's base moves
        t_ = s.t;
        q_ = s.q;
        qd_ = s.qd;
        take_tangent(s);
        reinitialize();
        marks_ = {};
      }
      pq_ = q_;
      pqd_ = qd_;
    }
    inadmissible_ = false;
    const std::span<const ContactRoot> roots = law_.roots(s.phase);
    const int count = static_cast<int>(roots.size());
    const ContactSample start = law_.sample_at_start(sys_, episode_, t_, pq_, pqd_, *ews_, etip_);
    std::array<double, kMaxRoots> g0{};
    for (int k = 1; k < count; ++k) g0[k] = law_.root_value(s.phase, k, sys_, episode_, t_, pq_, pqd_, *ews_, etip_);
    double ta = 0, tb = 0;
    if (!advance(t_stop, ta, tb, out)) return out;
    const double te = std::min(tb, t_stop);
    Samples ts{}, fn{};
    ts[0] = ta;
    fn[0] = start.normal_force;
    int sampled = 0;
    double t_event = te;
    int root = -1;
    if (start.root < 0.0) {
      auto sample = [&](int k, double t) {
        const ContactSample c = state_sample(t);
        ts[k] = t;
        fn[k] = c.normal_force;
        return c.root;
      };
      auto refine = [&](double t) { return state_root(0, t); };
      const double t0 = first_root(sample, refine, ta, te, start.root, kSamplesPerStep, &sampled);
      if (!std::isnan(t0)) t_event = t0, root = 0;
    }
    for (int k = 1; k < count; ++k) {
      if (!(g0[k] < 0.0)) continue;
      const double tk = first_root([&](double t) { return state_root(k, t); }, ta, te, g0[k]);
      if (!std::isnan(tk) && tk < t_event) t_event = tk, root = k;
    }
    // An accepted step whose stages met no admissible force (Painlevé's paradox, a − b < 0; rejected
    // trial steps beyond its end do not count) stands only up to a root of the phase found on its
    // dense output (the law's a − b = 0, where it has one): the law resolves the point there. Without
    // such a root the pass stops with the law's message.
    if (inadmissible_ && inadmissible_t_ <= tb && root < 0) {
      out = failed(law_.failure_kind(inadmissible_at_), law_.failure_message(inadmissible_at_));
      out.failure->t = inadmissible_t_;
      return out;
    }
    const double peak = sampled_peak(ts, fn, sampled, t_event);
    const bool at_dense = constraint ? (t_event < tb || root >= 0) : t_event < tb;
    if (at_dense) stepper_.calc_state(t_event, xs_);
    const State& xe = at_dense ? xs_ : stepper_.current_state();
    unpack(t_event, xe);
    const LedgerValues total = ledger_of(xe);
    out.integrals.peak_tip_deflection = interior_deflection_peak(ta, t_event, s.q, q_);
    out.integrals.integral = constraint ? total : total - marks_;
    if (!constraint) marks_ = total;
    if (constraint) project(t_event, locked);
    if (!q_.allFinite() || !qd_.allFinite())
      return failed(FailureKind::non_finite, std::string("the ") + law_.name() + " contact state became non-finite");
    t_ = t_event;
    store(s);
    out.root = root >= 0 ? Root::contact : Root::none;
    out.contact_root = root;
    out.status = root >= 0 ? StepStatus::root : StepStatus::advanced;
    out.integrals.peak_normal_force = peak;
    if (root >= 0 && roots[root].ends_contact) {
      out.load.slip = s.episode.slip;  // no force once the contact has ended
      return out;
    }
    const ContactEvaluation end = law_.evaluate(sys_, episode_, t_, q_, qd_, *ws_, tip_, force_);
    out.load = end.load;
    s.episode.slip = end.load.slip;
    out.integrals.peak_normal_force = std::max(peak, out.load.normal_force);
    return out;
  }

  // The largest of the sampled normal forces fn at ts[0..sampled] before t_end, refined by Brent's
  // maximisation on the dense output between the best sample's neighbours (the step's start and the
  // next sample where the start is the best): a maximum inside a step is not lost to its samples.
  double sampled_peak(const Samples& ts, const Samples& fn, int sampled, double t_end) {
    int best = 0, last = 0;
    for (int k = 0; k <= sampled && ts[k] < t_end; ++k) {
      last = k;
      if (fn[k] > fn[best]) best = k;
    }
    const double peak = fn[best];
    if (sampled == 0) return peak;
    // The step's start may be the best sample with the maximum just after it (a force still rising
    // where an episode begins): refined between the start and the next sample too.
    const double lo = best > 0 ? ts[best - 1] : ts[0], hi = best < last ? ts[best + 1] : t_end;
    auto minus = [&](double t) { return -state_sample(t).normal_force; };
    boost::uintmax_t iters = 100;
    const auto found = boost::math::tools::brent_find_minima(minus, lo, hi, kBrentBits, iters);
    return std::max(peak, -found.second);
  }

  // The largest tip deflection |y_t| [m] on the dense output over (ta, tb) where a sample inside beats
  // both ends (the states q_a, q_b there; then refined by Brent between that sample's neighbours),
  // else NaN: the maximum between accepted steps that the validity's max |y_t|/L reports. Call it once
  // the step's end is unpacked: it uses xs_, pq_, pqd_.
  double interior_deflection_peak(double ta, double tb, const Eigen::VectorXd& q_a, const Eigen::VectorXd& q_b) {
    if (!(tb > ta)) return NAN;
    const auto at = [&](double t) {
      stepper_.calc_state(t, xs_);
      physical(t, xs_, pq_, pqd_);
      return sys_.beam.tip_deflection(pq_);
    };
    double best = std::max(sys_.beam.tip_deflection(q_a), sys_.beam.tip_deflection(q_b)), best_t = NAN;
    const double h = (tb - ta) / kSamplesPerStep;
    for (int k = 1; k < kSamplesPerStep; ++k) {
      const double t = ta + h * k, d = at(t);
      if (d > best) best = d, best_t = t;
    }
    if (std::isnan(best_t)) return NAN;
    boost::uintmax_t iters = 100;
    const auto found = boost::math::tools::brent_find_minima([&](double t) { return -at(t); }, std::max(ta, best_t - h),
                                                             std::min(tb, best_t + h), kBrentBits, iters);
    return std::max(best, -found.second);
  }

  static constexpr int kMaxRoots = 8;  // root functions of a contact phase (ContactLaw::roots)
  const System sys_;
  const ContactLaw& law_;
  const PassOptions opt_;
  int n_;
  std::unique_ptr<BeamWorkspace> ws_, ews_;
  TipKinematics tip_, etip_;
  // The variational equations (PassOptions::tangent): 4n² components of x after the ledger's, Φ at
  // t_ in physical coordinates, and the scratch of A Φ.
  int tangent_;
  std::optional<TangentWorkspace> tws_;
  Eigen::MatrixXd phi_, jq_, jqd_;
  Eigen::MatrixXd ptan_;     // ∂(episode.parameter)/∂x₀ of the episode under way (empty: none)
  unsigned ptan_rows_ = 0;   // its nonzero rows (bit k: parameter k)
  Eigen::VectorXd dq_, dqd_, dqdd_;
  State x_, xs_;
  Eigen::VectorXd q_, qd_, force_, w_, w2_;
  Eigen::VectorXd pq_, pqd_, pa_;  // q, q̇, q̈ of a state being evaluated (rhs, root functions)
  std::optional<IntegratingFactor> factor_;  // opt_.integrating_factor
  double highest_hz_ = 0;                    // the highest linear mode [Hz] (0 without the factor)
  double base_ = 0;                          // t_b of the integrating factor [s]
  double factor_rebase_rate_ = 0;            // [1/s]: the base moves when (t − t_b)·rate > 1
  DenseStepper stepper_;
  StepperStatistics stats_;
  Phase phase_ = Phase::free;
  ContactEpisode episode_;                   // of the contact step under way
  static constexpr double kInitialStep = 1e-7;  // the first trial step of a run or revolution [s]
  double t_ = 0, dt_ = kInitialStep;
  const bool damped_ = sys_.beam.damped();
  double free_damping_ = 0;  // W_d of the free flight at the last reported point [J]
  // The free-flight gap detector (see begin_free).
  double eps_ = 0, offset_ = 0, g_prev_ = 0;
  bool armed_ = false;
  // The first state of the step where the law had no admissible force (Painlevé's paradox).
  bool inadmissible_ = false;
  double inadmissible_t_ = 0;
  ContactEvaluation inadmissible_at_;
  // A force phase: the ledger's integrals at the last reported point since the last (re)initialisation
  // (zero for a constraint, which restarts every step).
  LedgerValues marks_;
};

}  // namespace

std::unique_ptr<Stepper> make_adaptive_stepper(const System& system, const PassOptions& options) {
  if (static_cast<int>(system.law.roots(Phase::contact).size()) > 8)
    throw std::invalid_argument(std::string("the adaptive scheme takes up to 8 root functions per contact phase; the ") +
                                system.law.name() + " law has more");
  return std::make_unique<AdaptiveStepper>(system, options);
}

}  // namespace rotbeam
