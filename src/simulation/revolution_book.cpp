#include "revolution_book.hpp"

namespace rotbeam {

void section_state(const BeamModel& beam, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Eigen::VectorXd& z) {
  const double L = beam.beam_length(), omega = beam.hub_motion().omega;
  z.resize(q.size() + qd.size());
  z << q / L, qd / (omega * L);
}

Eigen::VectorXd section_state(const BeamModel& beam, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  Eigen::VectorXd z;
  section_state(beam, q, qd, z);
  return z;
}

double section_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const double scale = std::max(a.norm(), b.norm());
  return scale > 0.0 ? (a - b).norm() / scale : 0.0;
}

void RevolutionBook::start(double, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  section_state(ctx_.system.beam, q, qd, section_prev_);
  section_.resize(section_prev_.size());
}

void RevolutionBook::close_revolution(double, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, RevolutionRecord& r) {
  r.q = q;
  r.qd = qd;
  if (!r.complete) return;
  section_state(ctx_.system.beam, q, qd, section_);
  r.section_distance = section_distance(section_, section_prev_);
  section_prev_ = section_;
  last_distance_ = r.section_distance;
  last_complete_ = r;
  have_complete_ = true;
}

void RevolutionBook::finish(double, const Eigen::VectorXd&, const Eigen::VectorXd&) {
  if (ctx_.options.revolutions <= 0) return;
  PassSummary& s = ctx_.result.summary;
  s.revolutions = have_complete_ ? last_complete_.revolution : 0;
  if (!have_complete_) return;
  s.last_revolution = last_complete_;
  s.mean_hub_torque_n_m = last_complete_.mean_hub_torque_n_m;
  s.mean_hub_power_w = last_complete_.mean_hub_power_w;
}

}  // namespace rotbeam
