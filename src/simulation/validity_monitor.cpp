#include "validity_monitor.hpp"

#include "rotbeam/kinematics.hpp"

#include <algorithm>
#include <sstream>

namespace rotbeam {

namespace {
// Below this |y_t|/L the model's foreshortening stays close to the exact one (≈ 0.05 L at 0.3 L), so
// the tip is within reach and the distance is not computed.
constexpr double kReachCheckRatio = 0.3;
}  // namespace

void ValidityMonitor::start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd&) { track(t, q); }

void ValidityMonitor::step(const StepView& v) {
  track(v.t, v.q);
  // The largest deflection between the step's ends, where the stepper found one on its dense output.
  if (std::isfinite(v.integrals.peak_tip_deflection))
    track_ratio(v.t, v.q, v.integrals.peak_tip_deflection / ctx_.system.beam.beam_length());
  if (v.phase == Phase::contact) track_penetration(v.t, v.q);
}

void ValidityMonitor::open_revolution(double, const Eigen::VectorXd& q, const Eigen::VectorXd&) {
  rev_max_ratio_ = ctx_.system.beam.tip_deflection(q) / ctx_.system.beam.beam_length();
}

void ValidityMonitor::close_revolution(double, const Eigen::VectorXd&, const Eigen::VectorXd&, RevolutionRecord& r) {
  r.max_tip_deflection_ratio = rev_max_ratio_;
}

std::string ValidityMonitor::breach_message() const {
  std::ostringstream s;
  s << "max |y_t|/L = " << breach_ratio_ << " exceeds simulation.deflection_warning_ratio = "
    << ctx_.options.deflection_warning_ratio
    << " (simulation.deflection_limit_is_error = true): beyond the quadratic foreshortening model";
  return s.str();
}

void ValidityMonitor::track(double t, const Eigen::VectorXd& q) {
  const BeamModel& beam = ctx_.system.beam;
  track_ratio(t, q, beam.tip_deflection(q) / beam.beam_length());
}

void ValidityMonitor::track_ratio(double t, const Eigen::VectorXd& q, double ratio) {
  const BeamModel& beam = ctx_.system.beam;
  const PassOptions& o = ctx_.options;
  PassSummary& s = ctx_.result.summary;
  if (ratio > s.max_tip_deflection_ratio) s.max_tip_deflection_ratio = ratio;
  rev_max_ratio_ = std::max(rev_max_ratio_, ratio);
  // The deflection warning is the foreshortening model's (docs/model.md §10): the elastica's geometry is exact.
  const bool limited = !beam.geometrically_exact();
  if (limited && o.deflection_limit_is_error && ratio > o.deflection_warning_ratio && !breached_) {
    breached_ = true;
    breach_ratio_ = ratio;
  }
  if (limited && ratio > o.deflection_warning_ratio && s.validity == Validity::within) s.validity = Validity::edge;
  if (limited && !deflection_warned_ && ratio > o.deflection_warning_ratio) {
    deflection_warned_ = true;
    std::ostringstream m;
    m << "tip deflection exceeds " << o.deflection_warning_ratio
      << " of the length: the quadratic foreshortening model is at the edge of its validity, its tip about "
         "0.24 (|y_t|/L)^3 L from the exact one; beam.theory = \"elastica\" is exact at any deflection "
         "(rotbeam theories compares the two) (docs/model.md §10)";
    journal_.warn(t, q, m.str());
  }
  // Past kOutsideDeflectionRatio the foreshortening's tip is 1e-2 L or more from the exact one.
  if (limited && !outside_warned_ && ratio > kOutsideDeflectionRatio) {
    outside_warned_ = true;
    s.validity = Validity::outside;
    std::ostringstream m;
    m.precision(3);
    m << "max |y_t|/L = " << ratio << " passes " << kOutsideDeflectionRatio
      << ", where the quadratic foreshortening's tip is 0.01 L or more from the exact one: the results are not "
         "the physical filament's; run beam.theory = \"elastica\" (exact at any deflection; rotbeam theories "
         "compares the two) (docs/model.md §10)";
    journal_.warn(t, q, m.str());
  }
  // An inextensible filament's tip cannot be farther than L from its clamp at (r_h, 0); where the
  // model puts it there, it has left its geometry (only possible at large deflection).
  if (!geometry_warned_ && ratio > kReachCheckRatio) {
    const double reach = tip_reach(beam, q);
    if (reach > kReachLimit) {
      s.validity = Validity::outside;
      s.left_geometry = true;
      geometry_warned_ = true;
      std::ostringstream m;
      m.precision(3);
      m << "the tip is " << reach << " L from its clamp, farther than a filament of length L can reach: the model "
        << "has left its geometry and its results are not physical (docs/model.md §10)";
      journal_.warn(t, q, m.str());
      if (o.deflection_limit_is_error && !breached_) {
        breached_ = true;
        breach_ratio_ = ratio;
      }
    }
  }
}

// A compliant contact's penetration beyond its law's theory (Hertz: δ ≤ 0.1 R, docs/contact.md):
// warned once, and the pass's validity is at its edge (the force law is extrapolated).
void ValidityMonitor::track_penetration(double t, const Eigen::VectorXd& q) {
  const double limit = ctx_.system.law.largest_valid_penetration();
  if (!(limit > 0.0) || penetration_warned_) return;
  const double delta = gap(ctx_.system.beam, ctx_.system.surface, t, q);
  if (!(delta > limit)) return;
  penetration_warned_ = true;
  PassSummary& s = ctx_.result.summary;
  if (s.validity == Validity::within) s.validity = Validity::edge;
  std::ostringstream m;
  m.precision(3);
  m << "the penetration " << delta << " m exceeds " << limit
    << " m, a tenth of the tip radius (contact.tip_radius_m): Hertz's law, a small contact against the tip's "
       "radius, is extrapolated beyond its validity (docs/contact.md)";
  journal_.warn(t, q, m.str());
}

}  // namespace rotbeam
