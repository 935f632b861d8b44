// The thesis's scheme for a whole pass (thesis §4.6–4.7, Appendix B rotate.m and children), with
// the physical forces of SPEC §4 and the decisions recorded in docs/deviations.md:
//   free flight   fixed-step Butcher RK5 (h_free); C = 0 located on the step itself
//   impact        momentum balance (SPEC §5); a bouncing impact (Ċ⁺ < 0) returns to free flight,
//                 a plastic one (Ċ⁺ = 0) starts sustained contact
//   contact       λ predicted from the acceleration-level equation (4-109) at the start of an
//                 episode, then the previous step's λ; one RK5 step of the constrained system; the
//                 corrector (4-113…4-117) iterated until λ changes by less than the tolerance
//                 between iterates (capped); step h_contact, or h_fine while 0 < |λ| < fine_below_n
//   separation    λ > 0: linear interpolation to λ = 0 over the last step (Step 4b), one free step
//                 of h_contact, and while the tip is still at or beyond the surface, free steps of
//                 h_free until it is clear (Step 5a, the tip-distance rule)
#include "rotbeam/free_flight.hpp"
#include "rotbeam/pass.hpp"
#include "rotbeam/pass_recorder.hpp"
#include "rotbeam/detail/diagnostics.hpp"

#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <sstream>

namespace rotbeam {

namespace {

constexpr double kSurfaceTolerance = 1e-9;  // [m]

using detail::short_number;

class ThesisScheme {
public:
  ThesisScheme(const Model& model, const ImpactLaw& law, const FrictionModel& friction, const PassOptions& options,
               PassResult& result)
      : model_(model),
        law_(law),
        friction_(friction),
        opt_(options),
        result_(result),
        rec_(model, friction, options, result),
        n_(model.n),
        ws_(n_),
        tip_(n_),
        rk_(n_),
        q_(n_), qd_(n_), q1_(n_), qd1_(n_), xp_(n_), up_(n_), xn_(n_), un_(n_), x2_(n_), qstar_(n_), force_(n_),
        minv_(n_) {
    t_end_ = model.time_at(options.end_angle_rad);
  }

  void run(const InitialConditions& ic) {
    if (ic.rigid_start) {
      q_.setZero();
      qd_.setZero();
      t_ = 0.0;
      rec_.start(t_, q_, qd_);
      const double t_star = model_.time_at(model_.rigid_contact_angle());
      if (t_star >= t_end_) return finish_free_to(t_end_);
      t_ = t_star;
      rec_.accept(t_, q_, qd_, Phase::free, {}, {}, true);
      if (!impact()) return;
    } else {
      q_ = ic.q0;
      qd_ = ic.qd0;
      t_ = 0.0;
      rec_.start(t_, q_, qd_);
      if (gap(model_, t_, q_) >= 0.0) {
        rec_.fail("initial_state", t_, "the initial shape already touches the surface (C(0) >= 0)");
        return rec_.finish(t_, q_, qd_, Phase::free, {});
      }
    }
    loop();
  }

private:
  enum class Next { free, contact, done };

  void loop() {
    Next next = Next::free;
    // After a rigid-start impact the phase was chosen in impact().
    next = after_impact_;
    while (next != Next::done) {
      if (next == Next::free)
        next = free_flight();
      else
        next = contact();
    }
  }

  // Free RK5 steps until contact (→ impact or contact) or the end angle.
  Next free_flight() {
    auto accel = [&](double, const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& a) {
      acceleration(model_, q, v, nullptr, ws_, a);
    };
    double c0 = gap(model_, t_, q_);
    while (t_ < t_end_) {
      const double h = std::min(opt_.free_step_s, t_end_ - t_);
      rec_.rhs() += rk_.step(accel, t_, q_, qd_, h, q1_, qd1_);
      ++rec_.steps();
      const double c1 = gap(model_, t_ + h, q1_);
      if (!q1_.allFinite() || !qd1_.allFinite()) {
        rec_.fail("non_finite", t_, "the free-flight state became non-finite");
        rec_.finish(t_, q_, qd_, Phase::free, {});
        return Next::done;
      }
      if (c0 < 0.0 && c1 >= 0.0) {
        // Root of C on the RK5 step itself.
        auto gap_after = [&](double tau) {
          if (tau <= 0.0) return c0;
          rec_.rhs() += rk_.step(accel, t_, q_, qd_, tau, xp_, up_);
          return gap(model_, t_ + tau, xp_);
        };
        boost::uintmax_t max_iter = 100;
        const auto tol = [h](double a, double b) { return std::abs(b - a) <= 1e-15 * h + 1e-18; };
        const auto br = boost::math::tools::toms748_solve(gap_after, 0.0, h, c0, c1, tol, max_iter);
        const double tau = br.second;  // the end with C >= 0
        rec_.rhs() += rk_.step(accel, t_, q_, qd_, tau, q_, qd_);
        t_ += tau;
        rec_.accept(t_, q_, qd_, Phase::free, {}, {}, true);
        tip_kinematics(model_, t_, q_, qd_, tip_);
        if (tip_.gap_rate > 0.0) {
          if (!impact()) return Next::done;
          return after_impact_;
        }
        // Grazing touch with no approach speed: sustained contact may begin without an impact.
        return begin_contact("touch without approach speed");
      }
      q_.swap(q1_);
      qd_.swap(qd1_);
      t_ += h;
      c0 = c1;
      rec_.accept(t_, q_, qd_, Phase::free, {}, {});
      if (rec_.stop_requested(t_)) break;
    }
    rec_.finish(t_, q_, qd_, Phase::free, {});
    return Next::done;
  }

  // Momentum-balance impact at (t_, q_, qd_). Sets after_impact_. False on failure.
  bool impact() {
    if (rec_.impacts_exhausted(t_)) {
      rec_.finish(t_, q_, qd_, Phase::free, {});
      return false;
    }
    up_ = qd_;
    const ImpactResult r = apply_impact(model_, law_, t_, q_, qd_, ws_, tip_);
    rec_.impact(t_, q_, up_, qd_, r);
    if (r.vx_after < -1e-12 * std::abs(r.vx_before)) {
      after_impact_ = Next::free;
      return true;
    }
    after_impact_ = begin_contact(r.restitution == 0.0 ? "after a plastic impact" : "after an impact");
    return after_impact_ != Next::done;
  }

  // Enters sustained contact at (t_, q_, qd_) with C = Ċ = 0 (thesis Step 2 → 3).
  Next begin_contact(const std::string& why) {
    evaluate_dynamics(model_, q_, qd_, ws_);
    tip_kinematics(model_, t_, q_, qd_, tip_);
    const SlipDecision slip = decide_slip(model_, friction_, tip_, ws_);
    if (slip.kind == SlipDecision::Kind::stick) return fail_stick(slip);
    if (slip.kind == SlipDecision::Kind::separate) {
      rec_.event(t_, q_, "lift_off", detail::lift_off_message(slip.stick_normal));
      return separate(t_, q_, qd_);
    }
    slip_ = slip.direction;
    const AccelerationMultiplier am = acceleration_multiplier(model_, friction_, t_, q_, qd_, slip_, ws_, tip_);
    if (am.solution.status != MultiplierSolution::Status::unique) return fail_painleve(am.a, am.b, am.c);
    lambda_pred_ = am.solution.lambda;
    lambda_prev_ = 0.0;  // rotate.m resets the multiplier at every contact start
    rec_.contact_start(t_, q_, qd_, why);
    load_prev_ = ContactLoad{};
    return Next::contact;
  }

  // One constrained RK5 step with λ fixed (the predictor).
  void predictor(double h) {
    auto accel = [&](double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& a) {
      evaluate_dynamics(model_, q, v, ws_);
      tip_kinematics(model_, t, q, v, tip_);
      friction_direction(friction_, tip_, slip_, qstar_);
      a = lambda_pred_ * tip_.grad_gap + std::abs(lambda_pred_) * qstar_ - ws_.psi;
      ws_.mass_llt.solveInPlace(a);
    };
    rec_.rhs() += rk_.step(accel, t_, q_, qd_, h, xp_, up_);
  }

  Next contact() {
    while (t_ < t_end_) {
      const double h = std::min(
          (std::abs(lambda_prev_) > 0.0 && std::abs(lambda_prev_) < opt_.fine_below_n) ? opt_.fine_contact_step_s
                                                                                        : opt_.contact_step_s,
          t_end_ - t_);
      // Slip direction for this step (never from round-off; stick detected).
      evaluate_dynamics(model_, q_, qd_, ws_);
      tip_kinematics(model_, t_, q_, qd_, tip_);
      const double vy0 = tip_.VY;
      const SlipDecision slip = decide_slip(model_, friction_, tip_, ws_);
      if (slip.kind == SlipDecision::Kind::stick) return fail_stick(slip);
      if (slip.kind == SlipDecision::Kind::slip) {
        if (slip_ != 0.0 && slip.direction != slip_)
          rec_.event(t_, q_, "slip_reversal", "V_t changed sign; friction now acts toward " +
                                                  std::string(slip.direction > 0 ? "-Y" : "+Y"));
        slip_ = slip.direction;
      }
      predictor(h);
      const double tn = t_ + h;
      double lambda_iter = lambda_pred_;
      double lambda_n = 0.0;
      bool converged = false;
      int it = 0;
      for (it = 1; it <= opt_.corrector_max_iterations; ++it) {
        // x_n = x_{n−1} + h u^p − δ ∇C(x2), δ = C(x2)/|∇C(x2)|², x2 = x_{n−1} + h u^p (4-113, 4-114).
        x2_ = q_ + h * up_;
        tip_kinematics(model_, tn, x2_, up_, tip_);
        xn_ = x2_ - (tip_.gap / tip_.grad_gap.squaredNorm()) * tip_.grad_gap;
        // λ_n from h a λ + h b|λ| = h∇CᵀM⁻¹Ψ − ∇Cᵀu_{n−1} − ∂C/∂t  (4-116).
        evaluate_dynamics(model_, xn_, up_, ws_);
        tip_kinematics(model_, tn, xn_, up_, tip_);
        friction_direction(friction_, tip_, slip_, qstar_);
        minv_ = tip_.grad_gap;
        ws_.mass_llt.solveInPlace(minv_);
        const double a = h * tip_.grad_gap.dot(minv_);
        const double b = h * minv_.dot(qstar_);
        const double dcdt = opt_.thesis_dcdt ? -tip_.grad_gap.dot(up_) : tip_.gap_time_partial;
        const double c = h * minv_.dot(ws_.psi) - tip_.grad_gap.dot(qd_) - dcdt;
        const MultiplierSolution sol = solve_multiplier(a, b, c);
        if (sol.status != MultiplierSolution::Status::unique) return fail_painleve(a / h, b / h, c / h);
        lambda_n = sol.lambda;
        // u_n = u_{n−1} + h M⁻¹(−Ψ + λ∇C + |λ|Q*)  (4-115).
        force_ = lambda_n * tip_.grad_gap + std::abs(lambda_n) * qstar_ - ws_.psi;
        ws_.mass_llt.solveInPlace(force_);
        un_ = qd_ + h * force_;
        ++rec_.rhs();
        converged = std::abs(lambda_n - lambda_iter) <= opt_.corrector_tolerance * std::abs(lambda_iter) + 1e-12;
        up_ = un_;
        lambda_iter = lambda_n;
        if (converged) break;
      }
      result_.summary.corrector_iterations += std::min(it, opt_.corrector_max_iterations);
      result_.summary.corrector_iterations_max =
          std::max(result_.summary.corrector_iterations_max, std::min(it, opt_.corrector_max_iterations));
      if (!converged || !xn_.allFinite() || !un_.allFinite()) {
        rec_.fail("corrector", t_,
                  "the corrector did not converge in " + std::to_string(opt_.corrector_max_iterations) +
                      " iterations (last λ = " + short_number(lambda_n) + " N, step " + short_number(h) + " s)");
        rec_.finish(t_, q_, qd_, Phase::contact, load_prev_);
        return Next::done;
      }
      ++rec_.steps();
      if (lambda_n <= 0.0) {
        const ContactLoad load = rec_.load(tn, xn_, un_, lambda_n, slip_);
        q_ = xn_;
        qd_ = un_;
        t_ = tn;
        rec_.accept(t_, q_, qd_, Phase::contact, load_prev_, load);
        load_prev_ = load;
        lambda_prev_ = lambda_n;
        lambda_pred_ = lambda_n;
        (void)vy0;
        if (rec_.stop_requested(t_)) break;
        continue;
      }
      // Separation (Step 4b): λ = 0 by linear interpolation over the step.
      const double f = -lambda_prev_ / (lambda_n - lambda_prev_);
      const double ts = t_ + f * h;
      x2_ = q_ + f * (xn_ - q_);
      un_ = qd_ + f * (un_ - qd_);
      rec_.accept(ts, x2_, un_, Phase::contact, load_prev_, ContactLoad{});
      rec_.contact_end(ts, x2_, un_, "λ reached 0 (interpolated)");
      return separate(ts, Eigen::VectorXd(x2_), Eigen::VectorXd(un_));
    }
    rec_.finish(t_, q_, qd_, Phase::contact, load_prev_);
    return Next::done;
  }

  // Steps 4b/5: one free step of h_contact from the separation point, then the tip-distance rule.
  Next separate(double ts, const Eigen::VectorXd& qs, const Eigen::VectorXd& qds) {
    auto accel = [&](double, const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& a) {
      acceleration(model_, q, v, nullptr, ws_, a);
    };
    t_ = ts;
    q_ = qs;
    qd_ = qds;
    double h = std::min(opt_.contact_step_s, t_end_ - t_);
    if (h <= 0.0) {
      rec_.finish(t_, q_, qd_, Phase::free, {});
      return Next::done;
    }
    rec_.rhs() += rk_.step(accel, t_, q_, qd_, h, q_, qd_);
    ++rec_.steps();
    t_ += h;
    double c = gap(model_, t_, q_);
    rec_.accept(t_, q_, qd_, Phase::free, {}, {});
    if (c >= 0.0) {
      double deepest = c;
      const double t0 = t_;
      while (c >= 0.0 && t_ < t_end_) {
        h = std::min(opt_.free_step_s, t_end_ - t_);
        rec_.rhs() += rk_.step(accel, t_, q_, qd_, h, q_, qd_);
        ++rec_.steps();
        t_ += h;
        c = gap(model_, t_, q_);
        deepest = std::max(deepest, c);
        rec_.accept(t_, q_, qd_, Phase::free, {}, {});
      }
      // Gaps within 1 nm are the corrector's round-off (C is zeroed by one Newton step), not a crossing.
      if (deepest > kSurfaceTolerance) {
        rec_.event(t_, q_, "tip_distance_rule",
                   "after separation the free tip stayed beyond the surface for " + short_number(t_ - t0) + " s (deepest " +
                       short_number(deepest) + " m); free steps until clear (thesis Step 5a)");
        rec_.warn(t_, "the thesis's tip-distance rule (Step 5a) was applied: the free tip crossed the surface after a separation");
      }
    }
    if (t_ >= t_end_) {
      rec_.finish(t_, q_, qd_, Phase::free, {});
      return Next::done;
    }
    return Next::free;
  }

  void finish_free_to(double t_stop) {
    FreeFlightOptions fo;
    fo.step_s = opt_.free_step_s;
    fo.end_time_s = t_stop;
    fo.stop_at_contact = false;
    const FreeFlightResult fr = integrate_free_flight(model_, t_, q_, qd_, fo, ws_);
    t_ = fr.t;
    q_ = fr.q;
    qd_ = fr.qd;
    rec_.steps() += fr.steps;
    rec_.rhs() += fr.rhs_evaluations;
    rec_.finish(t_, q_, qd_, Phase::free, {});
  }

  Next fail_painleve(double a, double b, double c) {
    rec_.fail("painleve", t_, detail::painleve_message(a, b, c));
    rec_.finish(t_, q_, qd_, Phase::contact, load_prev_);
    return Next::done;
  }

  Next fail_stick(const SlipDecision& s) {
    rec_.fail("stick", t_,
              detail::stick_message(s, effective_friction(friction_, tip_)) + "; the thesis scheme cannot hold a stick");
    rec_.finish(t_, q_, qd_, Phase::stick, load_prev_);
    return Next::done;
  }

  const Model& model_;
  const ImpactLaw& law_;
  const FrictionModel& friction_;
  const PassOptions& opt_;
  PassResult& result_;
  PassRecorder rec_;
  int n_;
  Workspace ws_;
  TipKinematics tip_;
  Rk5Stepper rk_;
  Eigen::VectorXd q_, qd_, q1_, qd1_, xp_, up_, xn_, un_, x2_, qstar_, force_, minv_;
  double t_ = 0, t_end_ = 0;
  double slip_ = 0, lambda_pred_ = 0, lambda_prev_ = 0;
  ContactLoad load_prev_;
  Next after_impact_ = Next::free;
};

}  // namespace

PassResult run_thesis_pass(const Model& model, const ImpactLaw& law, const FrictionModel& friction,
                           const InitialConditions& initial, const PassOptions& options) {
  return timed_pass("thesis", [&](PassResult& result) {
    ThesisScheme scheme(model, law, friction, options, result);
    scheme.run(initial);
  });
}

}  // namespace rotbeam
