// The revolutions of a run over many (docs/model.md §11): each one's section state z = (q/L, q̇/(ωL)) at its
// end, its distance from the previous section (revolutions.csv's section_distance), and the last
// complete one's record, which the summary reports.
#pragma once

#include "pass_observer.hpp"

namespace rotbeam {

class RevolutionBook final : public PassObserver {
public:
  explicit RevolutionBook(PassContext& context) : ctx_(context) {}

  void start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;
  void close_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, RevolutionRecord& r) override;
  void finish(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;

  /// The last complete revolution's section distance (NaN before one).
  double last_distance() const { return last_distance_; }

private:
  PassContext& ctx_;
  Eigen::VectorXd section_prev_, section_;  // z at the open revolution's start, and scratch
  double last_distance_ = NAN;
  RevolutionRecord last_complete_;
  bool have_complete_ = false;
};

}  // namespace rotbeam
