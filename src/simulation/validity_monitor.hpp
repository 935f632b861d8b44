// Whether a pass stays where its model holds (docs/model.md, "Validity"): the largest tip deflection
// |y_t|/L of the pass and of each revolution, the foreshortening model's deflection warning past
// simulation.deflection_warning_ratio, the tip's leaving the filament's geometry, and the breach that
// stops the pass with simulation.deflection_limit_is_error.
#pragma once

#include "pass_observer.hpp"

#include <string>

namespace rotbeam {

class ValidityMonitor final : public PassObserver {
public:
  ValidityMonitor(PassContext& context, PassJournal& journal) : ctx_(context), journal_(journal) {}

  void start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;
  void step(const StepView& v) override;
  void open_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;
  void close_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, RevolutionRecord& r) override;

  /// Set when the pass must stop on its validity (simulation.deflection_limit_is_error), in words.
  bool breached() const { return breached_; }
  std::string breach_message() const;

private:
  void track(double t, const Eigen::VectorXd& q);
  // |y_t|/L = ratio at t: the state q's own, or a maximum inside the step that ends at (t, q).
  void track_ratio(double t, const Eigen::VectorXd& q, double ratio);
  void track_penetration(double t, const Eigen::VectorXd& q);

  PassContext& ctx_;
  PassJournal& journal_;
  double rev_max_ratio_ = 0;
  bool deflection_warned_ = false, outside_warned_ = false, geometry_warned_ = false, penetration_warned_ = false, breached_ = false;
  double breach_ratio_ = 0;
};

}  // namespace rotbeam
