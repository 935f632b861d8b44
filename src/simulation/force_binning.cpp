#include "force_binning.hpp"

#include <cmath>

namespace rotbeam {

void ForceBinning::step(const StepView& v) {
  if (v.phase == Phase::free) return;
  // The surface receives ∫F_n dt into it and the opposite of friction's impulse on the tip.
  bins_.add_spread(ctx_.relative_angle_deg(v.t0), ctx_.omega() * (v.t - v.t0) * 180.0 / M_PI,
                   v.integrals.integral[LedgerTerm::normal_impulse], -v.integrals.integral[LedgerTerm::tangential_impulse]);
}

void ForceBinning::impact(const ImpactView& v) {
  bins_.add_impulse(ctx_.relative_angle_deg(v.t), std::abs(v.result.impulse), -v.result.tangential_impulse);
}

void ForceBinning::open_revolution(double, const Eigen::VectorXd&, const Eigen::VectorXd&) { bins_.clear(); }

void ForceBinning::close_revolution(double, const Eigen::VectorXd&, const Eigen::VectorXd&, RevolutionRecord& r) {
  if (!r.complete) return;
  complete_bins_ = bins_.table();
  complete_peaks_ = bins_.peaks();
  have_complete_ = true;
}

void ForceBinning::finish(double, const Eigen::VectorXd&, const Eigen::VectorXd&) {
  if (ctx_.options.revolutions > 0 && have_complete_) {
    ctx_.result.force_bins = complete_bins_;
    ctx_.result.summary.binned_force = complete_peaks_;
  } else {
    ctx_.result.force_bins = bins_.table();
    ctx_.result.summary.binned_force = bins_.peaks();
  }
}

}  // namespace rotbeam
