#include "rotbeam/free_flight.hpp"

#include "rotbeam/kinematics.hpp"

#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <stdexcept>

namespace rotbeam {

FreeFlightResult integrate_free_flight(const Model& model, double t0, const Eigen::VectorXd& q0,
                                       const Eigen::VectorXd& qd0, const FreeFlightOptions& options,
                                       Workspace& ws, const StepObserver& observer) {
  if (!(options.step_s > 0.0)) throw std::invalid_argument("free-flight step must be positive");
  const int n = model.n;
  Rk5Stepper stepper(n);
  auto accel = [&](double, const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& a) {
    acceleration(model, q, v, nullptr, ws, a);
  };

  FreeFlightResult r;
  r.q = q0;
  r.qd = qd0;
  Eigen::VectorXd q_next(n), qd_next(n), q_probe(n), qd_probe(n);
  double t = t0;
  double c_now = gap(model, t, r.q);
  r.min_gap = c_now;
  long k = 0;
  while (t < options.end_time_s) {
    const double t_next = std::min(t0 + static_cast<double>(k + 1) * options.step_s, options.end_time_s);
    const double h = t_next - t;
    r.rhs_evaluations += stepper.step(accel, t, r.q, r.qd, h, q_next, qd_next);
    ++r.steps;
    ++k;
    const double c_next = gap(model, t_next, q_next);
    r.min_gap = std::max(r.min_gap, c_next);
    if (options.stop_at_contact && c_now < 0.0 && c_next >= 0.0) {
      r.linear_estimate_t = t - c_now * h / (c_next - c_now);
      // Root of C along the RK5 step itself: a fifth-order continuous extension of the step.
      auto gap_after = [&](double tau) {
        if (tau <= 0.0) return c_now;
        r.rhs_evaluations += stepper.step(accel, t, r.q, r.qd, tau, q_probe, qd_probe);
        return gap(model, t + tau, q_probe);
      };
      boost::uintmax_t max_iter = 100;
      const auto tol = [h](double a, double b) { return std::abs(b - a) <= 1e-15 * h + 1e-18; };
      const auto bracket = boost::math::tools::toms748_solve(gap_after, 0.0, h, c_now, c_next, tol, max_iter);
      const double tau = 0.5 * (bracket.first + bracket.second);
      r.rhs_evaluations += stepper.step(accel, t, r.q, r.qd, tau, r.q, r.qd);
      r.t = t + tau;
      r.end = FreeFlightEnd::contact;
      if (observer) observer(r.t, r.q, r.qd);
      return r;
    }
    r.q.swap(q_next);
    r.qd.swap(qd_next);
    t = t_next;
    c_now = c_next;
    if (observer) observer(t, r.q, r.qd);
  }
  r.t = t;
  r.end = FreeFlightEnd::end_time;
  return r;
}

}  // namespace rotbeam
