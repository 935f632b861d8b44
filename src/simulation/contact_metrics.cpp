#include "contact_metrics.hpp"

#include <algorithm>
#include <cmath>

namespace rotbeam {

int ContactMetrics::impacts_counted() const {
  return ctx_.result.summary.impacts - (ctx_.revolution > 0 ? mark_impacts_ : 0);
}

void ContactMetrics::note_force(double normal_force) {
  ctx_.result.summary.peak_normal_force_n = std::max(ctx_.result.summary.peak_normal_force_n, normal_force);
  rev_peak_force_ = std::max(rev_peak_force_, normal_force);
}

void ContactMetrics::step(const StepView& v) {
  if (v.phase == Phase::free) return;
  ctx_.result.summary.contact_time_s += v.t - v.t0;
  if (v.phase == Phase::stick) ctx_.result.summary.stick_time_s += v.t - v.t0;
  normal_time_integral_ += v.integrals.integral[LedgerTerm::normal_impulse];
  note_force(std::max(v.load.normal_force, v.integrals.peak_normal_force));
}

void ContactMetrics::impact(const ImpactView& v) {
  PassSummary& s = ctx_.result.summary;
  ++s.impacts;
  if (v.result.restitution == 0.0) ++s.plastic_impacts;
  const double theta_deg = ctx_.system.beam.theta(v.t) * 180.0 / M_PI;
  if (s.impacts == 1) s.first_impact_deg = theta_deg;
  s.last_separation_deg = theta_deg;
  if (ctx_.revolution > 0) {
    if (s.impacts - mark_impacts_ == 1) rev_first_impact_deg_ = ctx_.relative_angle_deg(v.t);
    rev_last_separation_deg_ = ctx_.relative_angle_deg(v.t);
  }
}

void ContactMetrics::contact_start(double t, const Eigen::VectorXd& q, const ContactLoad& load, bool first_touch) {
  if (first_touch) {
    // A compliant contact has no impact: its touch is the pass's and the revolution's first.
    if (!touched_) ctx_.result.summary.first_impact_deg = ctx_.system.beam.theta(t) * 180.0 / M_PI;
    touched_ = true;
    if (ctx_.revolution > 0 && std::isnan(rev_first_impact_deg_)) rev_first_impact_deg_ = ctx_.relative_angle_deg(t);
  }
  in_episode_ = true;
  episode_t0_ = t;
  episode_theta0_ = ctx_.system.beam.theta(t);
  episode_y0_ = ctx_.tip_y(t, q);
  // The force right after the plastic impact that opens an episode is often the episode's largest.
  note_force(load.normal_force);
}

void ContactMetrics::contact_end(double t, const Eigen::VectorXd& q) {
  in_episode_ = false;
  if (!(t > episode_t0_)) return;
  PassSummary& s = ctx_.result.summary;
  ++s.contact_episodes;
  s.contact_intervals.push_back({episode_t0_, t, episode_theta0_, ctx_.system.beam.theta(t), episode_y0_,
                                 ctx_.tip_y(t, q), std::max(ctx_.revolution, 1)});
  s.last_separation_deg = ctx_.system.beam.theta(t) * 180.0 / M_PI;
  if (ctx_.revolution > 0) rev_last_separation_deg_ = ctx_.relative_angle_deg(t);
}

void ContactMetrics::open_revolution(double, const Eigen::VectorXd&, const Eigen::VectorXd&) {
  const PassSummary& s = ctx_.result.summary;
  mark_impacts_ = s.impacts;
  mark_episodes_ = s.contact_episodes;
  mark_contact_time_ = s.contact_time_s;
  mark_stick_time_ = s.stick_time_s;
  rev_first_impact_deg_ = rev_last_separation_deg_ = NAN;
  rev_peak_force_ = 0.0;
  // The intervals of the revolutions kept (output.history_revolutions; the open one counts).
  const int keep = ctx_.options.history_revolutions;
  if (keep <= 0) return;
  const int oldest = ctx_.revolution - keep + 1;
  auto& intervals = ctx_.result.summary.contact_intervals;
  intervals.erase(std::remove_if(intervals.begin(), intervals.end(),
                                 [oldest](const ContactInterval& c) { return c.revolution < oldest; }),
                  intervals.end());
}

void ContactMetrics::close_revolution(double, const Eigen::VectorXd&, const Eigen::VectorXd&, RevolutionRecord& r) {
  const PassSummary& s = ctx_.result.summary;
  r.impacts = s.impacts - mark_impacts_;
  r.contact_episodes = s.contact_episodes - mark_episodes_;
  r.first_impact_deg = rev_first_impact_deg_;
  r.last_separation_deg = rev_last_separation_deg_;
  r.contact_time_s = s.contact_time_s - mark_contact_time_;
  r.stick_time_s = s.stick_time_s - mark_stick_time_;
  r.peak_normal_force_n = rev_peak_force_;
}

void ContactMetrics::finish(double, const Eigen::VectorXd&, const Eigen::VectorXd&) {
  PassSummary& s = ctx_.result.summary;
  s.mean_normal_force_n = s.contact_time_s > 0 ? normal_time_integral_ / s.contact_time_s : 0.0;
}

}  // namespace rotbeam
