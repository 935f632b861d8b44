#include "rotbeam/first_impact.hpp"

#include "rotbeam/kinematics.hpp"

#include <stdexcept>

namespace rotbeam {

FirstImpactResult first_impact(const Model& model, const ImpactLaw& law, const InitialConditions& initial,
                               double end_angle_rad, double step_s) {
  const int n = model.n;
  Workspace ws(n);
  TipKinematics tip(n);
  FirstImpactResult r;
  if (initial.rigid_start) {
    const double theta_star = model.rigid_contact_angle();
    if (theta_star >= end_angle_rad) {
      r.min_gap = gap(model, model.time_at(end_angle_rad), Eigen::VectorXd::Zero(n));
      return r;
    }
    r.t = model.time_at(theta_star);
    r.q = Eigen::VectorXd::Zero(n);
    r.qd_before = Eigen::VectorXd::Zero(n);
  } else {
    FreeFlightOptions options;
    options.step_s = step_s;
    options.end_time_s = model.time_at(end_angle_rad);
    options.stop_at_contact = true;
    if (gap(model, 0.0, initial.q0) >= 0.0)
      throw std::invalid_argument("the initial shape already touches the surface (C(0) >= 0)");
    FreeFlightResult flight = integrate_free_flight(model, 0.0, initial.q0, initial.qd0, options, ws);
    r.steps = flight.steps;
    r.rhs_evaluations = flight.rhs_evaluations;
    r.min_gap = flight.min_gap;
    if (flight.end != FreeFlightEnd::contact) return r;
    r.t = flight.t;
    r.q = flight.q;
    r.qd_before = flight.qd;
  }
  r.found = true;
  r.theta = model.theta(r.t);
  r.qd_after = r.qd_before;
  r.impact = apply_impact(model, law, r.t, r.q, r.qd_after, ws, tip);
  r.x_tip = tip.X;
  r.y_tip = tip.Y;
  return r;
}

}  // namespace rotbeam
