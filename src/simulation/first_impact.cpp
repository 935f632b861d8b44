#include "rotbeam/first_impact.hpp"

#include "rotbeam/contact_law.hpp"
#include "rotbeam/stepper.hpp"
#include "rotbeam/surface.hpp"

#include "rotbeam/detail/progress_clock.hpp"

#include <cmath>
#include <stdexcept>

namespace rotbeam {

FirstImpactResult first_impact(const System& system, const InitialConditions& initial, double end_angle_deg,
                               double step_s, const PassControl& control) {
  const StopToken* stop = control.stop;
  const BeamModel& beam = system.beam;
  const int n = beam.modes();
  const double t_end = beam.time_at(end_angle_deg * M_PI / 180.0);
  FirstImpactResult r;
  FilamentState s(n);
  if (!initial.rigid_start) {
    s.q = initial.q0;
    s.qd = initial.qd0;
  } else {
    beam.rest_state(s.q);
  }
  if (gap(beam, system.surface, 0.0, s.q) >= 0.0)
    throw std::invalid_argument("the initial shape already touches the surface (C(0) >= 0)");
  if (initial.rigid_start) {
    const double theta_star = system.surface.first_contact_angle(beam.tip_radius(), beam.theta(0.0));
    const double t_star = std::isnan(theta_star) ? INFINITY : beam.time_at(theta_star);
    if (!(t_star < t_end)) {
      r.min_gap = gap(beam, system.surface, t_end, s.q);
      return r;
    }
    s.t = t_star;
  } else {
    PassOptions options;
    options.scheme = Scheme::thesis;
    options.free_step_s = step_s;
    const std::unique_ptr<Stepper> stepper = make_thesis_stepper(system, options);
    stepper->begin_free(s, FreeStart::pass_start);
    r.min_gap = gap(beam, system.surface, s.t, s.q);
    bool touched = false;
    detail::ProgressClock clock;
    while (s.t < t_end && !touched) {
      if (control.on_progress && clock.due()) {
        PassProgress p;
        p.theta_deg = beam.theta(s.t) * 180.0 / M_PI;
        p.start_deg = beam.theta(0.0) * 180.0 / M_PI;
        p.end_deg = end_angle_deg;
        p.elapsed_s = clock.elapsed_s();
        p.steps = stepper->statistics().steps;
        control.on_progress(p);
      }
      if (stop && stop->stop_requested()) {
        r.failure = NumericalFailure{FailureKind::interrupted, s.t, beam.theta(s.t),
                                     "the search for the first impact was interrupted"};
        r.steps = stepper->statistics().steps;
        return r;
      }
      const StepOutcome o = stepper->step(s, t_end);
      if (o.status == StepStatus::failed) {
        r.failure = o.failure;
        r.failure->theta = beam.theta(r.failure->t);
        r.steps = stepper->statistics().steps;
        return r;
      }
      touched = o.status == StepStatus::root;
      r.min_gap = std::max(r.min_gap, gap(beam, system.surface, s.t, s.q));
    }
    r.steps = stepper->statistics().steps;
    r.rhs_evaluations = stepper->statistics().rhs_evaluations;
    if (!touched) return r;
  }
  r.found = true;
  r.t = s.t;
  r.theta = beam.theta(s.t);
  r.q = s.q;
  r.qd_before = s.qd;
  r.qd_after = s.qd;
  const std::unique_ptr<BeamWorkspace> ws = beam.make_workspace();
  TipKinematics tip(n);
  r.impact = apply_impact(beam, system.surface, system.law.impact_law(), r.t, r.q, r.qd_after, *ws, tip,
                          system.law.friction().mu);
  if (r.impact.jammed) {
    r.found = false;
    r.failure = NumericalFailure{FailureKind::painleve, r.t, r.theta,
                                 "the frictional impact jams: sliding drives the tip into the surface and the normal "
                                 "approach never ends (Painlevé's paradox of impacts)"};
  }
  r.x_tip = tip.X;
  r.y_tip = tip.Y;
  return r;
}

}  // namespace rotbeam
