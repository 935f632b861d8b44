// The contact metrics of a pass and of each revolution (docs/model.md §7, §11): impacts, the first touch and
// the last separation, contact episodes and their intervals, contact and stick time, the largest normal force
// and the mean one.
#pragma once

#include "pass_observer.hpp"

namespace rotbeam {

class ContactMetrics final : public PassObserver {
public:
  explicit ContactMetrics(PassContext& context) : ctx_(context) {}

  void step(const StepView& v) override;
  void impact(const ImpactView& v) override;
  void contact_start(double t, const Eigen::VectorXd& q, const ContactLoad& load, bool first_touch) override;
  void contact_end(double t, const Eigen::VectorXd& q) override;
  void open_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;
  void close_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, RevolutionRecord& r) override;
  void finish(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;

  bool in_episode() const { return in_episode_; }
  /// Impacts counted against simulation.max_impacts: of the pass, or of the revolution under way.
  int impacts_counted() const;

private:
  void note_force(double normal_force);

  PassContext& ctx_;
  bool in_episode_ = false;
  bool touched_ = false;  // a touch without an impact (a compliant contact) has begun in this pass
  double episode_t0_ = 0, episode_theta0_ = 0, episode_y0_ = 0;
  double normal_time_integral_ = 0;  // ∫ F_n dt over sustained contact [N s]
  // The revolution under way: its first touch and last separation, largest force, and the pass's
  // counts at its start.
  double rev_first_impact_deg_ = NAN, rev_last_separation_deg_ = NAN, rev_peak_force_ = 0;
  int mark_impacts_ = 0, mark_episodes_ = 0;
  double mark_contact_time_ = 0, mark_stick_time_ = 0;
};

}  // namespace rotbeam
