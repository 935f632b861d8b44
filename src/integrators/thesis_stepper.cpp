// The thesis's scheme as a stepper (thesis §4.6–4.7, Appendix B rotate.m and children), with the
// physical forces of docs/model.md §4 and the decisions recorded in docs/deviations.md:
//   free flight   fixed-step Butcher RK5 (h_free); C = 0 located on the RK5 step itself (TOMS 748)
//   contact       λ predicted from the acceleration-level equation (4-109) at the start of an
//                 episode (the driver's λ0), then the previous step's λ; one RK5 step of the
//                 constrained system; the corrector (4-113…4-117) iterated until λ changes by less
//                 than the tolerance between iterates (capped); step h_contact, or h_fine while
//                 0 < |λ| < fine_below_n; contact integrals by the trapezoidal rule, from λ = 0 at
//                 the episode's start (rotate.m resets the multiplier there)
//   damping work  −∫q̇ᵀCq̇ dt by the RK5 step's own quadrature in free flight and by the trapezoidal
//                 rule over contact steps (docs/model.md §11)
//   separation    λ > 0: linear interpolation to λ = 0 over the last step (Step 4b); then one free
//                 step of h_contact and, while the tip is still at or beyond the surface, free steps
//                 of h_free until it is clear (Step 5a, the tip-distance rule)
#include "rotbeam/rigid_contact.hpp"
#include "rotbeam/rk5.hpp"
#include "rotbeam/stepper.hpp"
#include "rotbeam/detail/diagnostics.hpp"

#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>

namespace rotbeam {

namespace {

constexpr double kSurfaceTolerance = 1e-9;  // [m]: gaps within 1 nm after a separation are the corrector's round-off
constexpr double kMinStepFraction = 1e-12;  // a configured step below this fraction of the pass's end time

using detail::short_number;

// The contact's integrals over a step by the trapezoidal rule, from its loads at both ends.
StepIntegrals trapezoid(const ContactLoad& begin, const ContactLoad& end, double dt) {
  StepIntegrals out;
  for (std::size_t k = 0; k < kLedgerTermCount; ++k)
    out.integral.value[k] = 0.5 * (begin.rate.value[k] + end.rate.value[k]) * dt;
  out.peak_normal_force = std::max(begin.normal_force, end.normal_force);
  return out;
}

class ThesisStepper final : public Stepper {
public:
  ThesisStepper(const System& system, const PassOptions& options)
      : sys_(system),
        opt_(options),
        n_(system.beam.modes()),
        ws_(system.beam.make_workspace()),
        tip_(n_),
        rk_(n_),
        q1_(n_), qd1_(n_), xp_(n_), up_(n_), xn_(n_), un_(n_), x2_(n_), qstar_(n_), force_(n_), minv_(n_),
        damped_(system.beam.damped()) {}

  StepperTraits traits() const override { return {Scheme::thesis, false, false, false}; }

  void begin_free(const FilamentState& s, FreeStart start) override {
    mode_ = start == FreeStart::separation ? Mode::separation_step : Mode::free;
    start_free_grid(s.t);
    c0_ = gap(sys_.beam, sys_.surface, s.t, s.q);
  }

  // The rigid law's episode starts with its acceleration-level multiplier λ0 (the first prediction).
  void begin_contact(const FilamentState& s) override {
    lambda_pred_ = s.episode.parameter[0];
    lambda_prev_ = 0.0;
    load_prev_ = ContactLoad{};
  }

  StepOutcome step(FilamentState& s, double t_stop) override {
    return s.phase == Phase::free ? free_step(s, t_stop) : contact_step(s, t_stop);
  }

  const StepperStatistics& statistics() const override { return stats_; }

private:
  enum class Mode { free, separation_step, clearing };

  void accel_free(double, const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& a) {
    acceleration(sys_.beam, q, v, nullptr, *ws_, a);
  }

  // A step that cannot advance t in double precision (t + h == t), or a configured step so small that
  // the pass would need over 1e12 of them, would run for ever.
  static bool stalls(double t, double h) { return !(t + h > t); }
  bool too_small(double step, double t_stop) const { return step < kMinStepFraction * std::abs(t_stop); }
  StepOutcome step_too_small(double t, double step, double t_stop) const {
    return failed(FailureKind::step_underflow, t,
                  "the step " + short_number(step) + " s would need over 1e12 steps to reach t = " + short_number(t_stop) +
                      " s");
  }
  StepOutcome stalled(double t, double h) const {
    return failed(FailureKind::step_underflow, t,
                  "the step " + short_number(h) + " s does not advance t = " + short_number(t) +
                      " s in double precision (t + h == t)");
  }

  // One RK5 step of free flight in place; returns the gap at its end.
  double free_rk5(FilamentState& s, double h) {
    auto accel = [&](double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& a) {
      accel_free(t, q, v, a);
    };
    stats_.rhs_evaluations += rk_.step(accel, s.t, s.q, s.qd, h, s.q, s.qd);
    ++stats_.steps;
    s.t += h;
    step_damping_ += free_damping_work(h);
    return gap(sys_.beam, sys_.surface, s.t, s.q);
  }

  // The damping work of the last RK5 step of free flight [J].
  double free_damping_work(double h) const {
    if (!damped_) return 0.0;
    return -rk_.stage_quadrature([this](const Eigen::VectorXd& v) { return sys_.beam.dissipation(v); }, h);
  }

  StepOutcome free_step(FilamentState& s, double t_stop) {
    step_damping_ = 0.0;
    StepOutcome out = free_step_body(s, t_stop);
    out.integrals.integral[LedgerTerm::damping_work] = step_damping_;
    return out;
  }

  StepOutcome free_step_body(FilamentState& s, double t_stop) {
    StepOutcome out;
    if (too_small(opt_.free_step_s, t_stop)) return step_too_small(s.t, opt_.free_step_s, t_stop);
    if (too_small(opt_.contact_step_s, t_stop)) return step_too_small(s.t, opt_.contact_step_s, t_stop);
    if (mode_ == Mode::separation_step) {
      // Step 4b: one free step of h_contact from the separation point.
      const double h = std::min(opt_.contact_step_s, t_stop - s.t);
      if (stalls(s.t, h)) return stalled(s.t, h);
      const double c = free_rk5(s, h);
      if (c >= 0.0) {
        deepest_ = c;
        clearing_t0_ = s.t;
        mode_ = Mode::clearing;
        if (s.t >= t_stop) finish_clearing(s, c, out);
      } else {
        mode_ = Mode::free;
        start_free_grid(s.t);
        c0_ = c;
      }
      return out;
    }
    if (mode_ == Mode::clearing) {
      // Step 5a: free steps of h_free while the tip is at or beyond the surface.
      const double h = std::min(opt_.free_step_s, t_stop - s.t);
      if (stalls(s.t, h)) return stalled(s.t, h);
      const double c = free_rk5(s, h);
      deepest_ = std::max(deepest_, c);
      if (c < 0.0 || s.t >= t_stop) finish_clearing(s, c, out);
      return out;
    }
    auto accel = [&](double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& a) {
      accel_free(t, q, v, a);
    };
    // Step ends on the grid t_k = t_free + k h_free (no drift from summing steps), the last at t_stop.
    const double t_next = std::min(free_t0_ + static_cast<double>(free_k_ + 1) * opt_.free_step_s, t_stop);
    const double h = t_next - s.t;
    if (!(t_next > s.t)) return stalled(s.t, opt_.free_step_s);
    stats_.rhs_evaluations += rk_.step(accel, s.t, s.q, s.qd, h, q1_, qd1_);
    ++stats_.steps;
    const double c1 = gap(sys_.beam, sys_.surface, t_next, q1_);
    if (!q1_.allFinite() || !qd1_.allFinite())
      return failed(FailureKind::non_finite, s.t, "the free-flight state became non-finite");
    if (c0_ < 0.0 && c1 >= 0.0) {
      // Root of C on the RK5 step itself: τ ↦ C(RK5(y_n, τ)), a fifth-order continuous extension.
      const double c0 = c0_;
      auto gap_after = [&](double tau) {
        if (tau <= 0.0) return c0;
        stats_.rhs_evaluations += rk_.step(accel, s.t, s.q, s.qd, tau, xp_, up_);
        return gap(sys_.beam, sys_.surface, s.t + tau, xp_);
      };
      boost::uintmax_t max_iter = 100;
      const auto tol = [h](double a, double b) { return std::abs(b - a) <= 1e-15 * h + 1e-18; };
      const auto br = boost::math::tools::toms748_solve(gap_after, 0.0, h, c0, c1, tol, max_iter);
      const double tau = br.second;  // the end with C >= 0
      stats_.rhs_evaluations += rk_.step(accel, s.t, s.q, s.qd, tau, s.q, s.qd);
      step_damping_ += free_damping_work(tau);
      s.t += tau;
      out.status = StepStatus::root;
      out.root = Root::gap_closes;
      return out;
    }
    step_damping_ += free_damping_work(h);
    s.q.swap(q1_);
    s.qd.swap(qd1_);
    s.t = t_next;
    ++free_k_;
    c0_ = c1;
    return out;
  }

  void start_free_grid(double t) {
    free_t0_ = t;
    free_k_ = 0;
  }

  void finish_clearing(const FilamentState& s, double c, StepOutcome& out) {
    mode_ = Mode::free;
    start_free_grid(s.t);
    c0_ = c;
    if (deepest_ > kSurfaceTolerance)
      out.note = StepNote{EventKind::tip_distance_rule,
                          "after separation the free tip stayed beyond the surface for " +
                              short_number(s.t - clearing_t0_) + " s (deepest " + short_number(deepest_) +
                              " m); free steps until clear (thesis Step 5a)",
                          "the thesis's tip-distance rule (Step 5a) was applied: the free tip crossed the surface "
                          "after a separation"};
  }

  // One constrained RK5 step with λ fixed at the prediction (the predictor).
  void predictor(double t, const FilamentState& s, double h) {
    auto accel = [&](double tt, const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& a) {
      sys_.beam.evaluate_dynamics(q, v, *ws_);
      tip_kinematics(sys_.beam, sys_.surface, tt, q, v, tip_);
      contact_load(sys_.law.friction(), tip_, v, lambda_pred_, s.episode.slip, force_);
      a = force_ - ws_->psi;
      ws_->mass_llt.solveInPlace(a);
    };
    stats_.rhs_evaluations += rk_.step(accel, t, s.q, s.qd, h, xp_, up_);
  }

  StepOutcome contact_step(FilamentState& s, double t_stop) {
    const FrictionModel& friction = sys_.law.friction();
    const double h = std::min(
        (std::abs(lambda_prev_) > 0.0 && std::abs(lambda_prev_) < opt_.fine_below_n) ? opt_.fine_contact_step_s
                                                                                      : opt_.contact_step_s,
        t_stop - s.t);
    if (stalls(s.t, h)) return stalled(s.t, h);
    if (too_small(opt_.contact_step_s, t_stop) || too_small(opt_.fine_contact_step_s, t_stop))
      return step_too_small(s.t, std::min(opt_.contact_step_s, opt_.fine_contact_step_s), t_stop);
    predictor(s.t, s, h);
    const double tn = s.t + h;
    double lambda_iter = lambda_pred_;
    double lambda_n = 0.0;
    bool converged = false;
    int it = 0;
    for (it = 1; it <= opt_.corrector_max_iterations; ++it) {
      // x_n = x_{n−1} + h u^p − δ ∇C(x2), δ = C(x2)/|∇C(x2)|², x2 = x_{n−1} + h u^p (4-113, 4-114).
      x2_ = s.q + h * up_;
      tip_kinematics(sys_.beam, sys_.surface, tn, x2_, up_, tip_);
      xn_ = x2_ - (tip_.gap / tip_.grad_gap.squaredNorm()) * tip_.grad_gap;
      // λ_n from h a λ + h b|λ| = h∇CᵀM⁻¹Ψ − ∇Cᵀu_{n−1} − ∂C/∂t  (4-116).
      sys_.beam.evaluate_dynamics(xn_, up_, *ws_);
      tip_kinematics(sys_.beam, sys_.surface, tn, xn_, up_, tip_);
      friction_direction(friction, tip_, s.episode.slip, qstar_);
      minv_ = tip_.grad_gap;
      ws_->mass_llt.solveInPlace(minv_);
      const double a = h * tip_.grad_gap.dot(minv_);
      const double b = h * minv_.dot(qstar_);
      const double dcdt = opt_.thesis_dcdt ? -tip_.grad_gap.dot(up_) : tip_.gap_time_partial;
      const double c = h * minv_.dot(ws_->psi) - tip_.grad_gap.dot(s.qd) - dcdt;
      const MultiplierSolution sol = solve_multiplier(a, b, c);
      if (sol.status != MultiplierSolution::Status::unique)
        return failed(FailureKind::painleve, s.t, detail::painleve_message(a / h, b / h, c / h));
      lambda_n = sol.lambda;
      // u_n = u_{n−1} + h M⁻¹(−Ψ + λ∇C + |λ|Q*)  (4-115).
      contact_load(friction, tip_, up_, lambda_n, s.episode.slip, force_);
      force_ -= ws_->psi;
      ws_->mass_llt.solveInPlace(force_);
      un_ = s.qd + h * force_;
      ++stats_.rhs_evaluations;
      converged = std::abs(lambda_n - lambda_iter) <= opt_.corrector_tolerance * std::abs(lambda_iter) + 1e-12;
      up_ = un_;
      lambda_iter = lambda_n;
      if (converged) break;
    }
    const int used = std::min(it, opt_.corrector_max_iterations);
    stats_.corrector_iterations += used;
    stats_.corrector_iterations_max = std::max(stats_.corrector_iterations_max, used);
    if (!converged || !xn_.allFinite() || !un_.allFinite())
      return failed(FailureKind::corrector, s.t,
                    "the corrector did not converge in " + std::to_string(opt_.corrector_max_iterations) +
                        (opt_.corrector_max_iterations == 1 ? " iteration" : " iterations") + " (last λ = " + short_number(lambda_n) + " N, step " + short_number(h) + " s)");
    ++stats_.steps;
    StepOutcome out;
    if (lambda_n <= 0.0) {
      tip_kinematics(sys_.beam, sys_.surface, tn, xn_, un_, tip_);
      out.load = contact_load(friction, tip_, un_, lambda_n, s.episode.slip, force_);
      out.integrals = trapezoid(load_prev_, out.load, tn - s.t);
      out.integrals.integral[LedgerTerm::damping_work] = contact_damping_work(s.qd, un_, tn - s.t);
      s.q = xn_;
      s.qd = un_;
      s.t = tn;
      load_prev_ = out.load;
      lambda_prev_ = lambda_n;
      lambda_pred_ = lambda_n;
      return out;
    }
    // Separation (Step 4b): λ = 0 by linear interpolation over the step.
    const double f = -lambda_prev_ / (lambda_n - lambda_prev_);
    const double ts = s.t + f * h;
    out.integrals = trapezoid(load_prev_, ContactLoad{}, ts - s.t);
    x2_ = s.q + f * (xn_ - s.q);
    un_ = s.qd + f * (un_ - s.qd);
    out.integrals.integral[LedgerTerm::damping_work] = contact_damping_work(s.qd, un_, ts - s.t);
    s.q = x2_;
    s.qd = un_;
    s.t = ts;
    out.status = StepStatus::root;
    out.root = Root::contact;
    out.contact_root = 0;  // the rigid law's λ = 0
    return out;
  }

  // The damping work over a contact step by the trapezoidal rule [J].
  double contact_damping_work(const Eigen::VectorXd& qd0, const Eigen::VectorXd& qd1, double dt) const {
    if (!damped_) return 0.0;
    return -0.5 * (sys_.beam.dissipation(qd0) + sys_.beam.dissipation(qd1)) * dt;
  }

  static StepOutcome failed(FailureKind kind, double t, std::string message) {
    StepOutcome out;
    out.status = StepStatus::failed;
    out.failure = NumericalFailure{kind, t, 0.0, std::move(message)};
    return out;
  }

  const System sys_;
  const PassOptions opt_;
  int n_;
  std::unique_ptr<BeamWorkspace> ws_;
  TipKinematics tip_;
  Rk5Stepper rk_;
  Eigen::VectorXd q1_, qd1_, xp_, up_, xn_, un_, x2_, qstar_, force_, minv_;
  StepperStatistics stats_;
  Mode mode_ = Mode::free;
  double c0_ = 0;                        // gap at the start of the next free step
  double free_t0_ = 0;                   // start of the current free-flight grid [s]
  long free_k_ = 0;                      // steps taken on it
  double deepest_ = 0, clearing_t0_ = 0; // Step 5a bookkeeping
  double lambda_pred_ = 0, lambda_prev_ = 0;
  ContactLoad load_prev_;
  const bool damped_;          // the beam dissipates (its damping work is computed)
  double step_damping_ = 0;    // damping work of the current free step [J]
};

}  // namespace

std::unique_ptr<Stepper> make_thesis_stepper(const System& system, const PassOptions& options) {
  return std::make_unique<ThesisStepper>(system, options);
}

}  // namespace rotbeam
