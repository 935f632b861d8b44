// The force on the surface by hub angle (force_bins.hpp, output.bin_deg): of the pass, or of the last
// complete revolution of a run over many.
#pragma once

#include "pass_observer.hpp"

#include "rotbeam/force_bins.hpp"

namespace rotbeam {

class ForceBinning final : public PassObserver {
public:
  explicit ForceBinning(PassContext& context)
      : ctx_(context), bins_(context.options.bin_deg, context.system.beam.hub_motion().omega) {}

  void step(const StepView& v) override;
  void impact(const ImpactView& v) override;
  void open_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;
  void close_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, RevolutionRecord& r) override;
  void finish(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;

private:
  PassContext& ctx_;
  ForceBins bins_;                       // of the pass, or of the revolution under way
  std::vector<ForceBin> complete_bins_;  // the last complete revolution's (runs over many)
  BinnedForcePeaks complete_peaks_;
  bool have_complete_ = false;
};

}  // namespace rotbeam
