#include "wear_profile.hpp"

#include "rotbeam/kinematics.hpp"

namespace rotbeam {

WearProfile::WearProfile(PassContext& context)
    : ctx_(context),
      period_(context.system.surface.coordinate().period),
      min_span_(context.options.wear_point_span_m / context.system.surface.coordinate().metres_per_unit),
      track_(period_) {
  for (WearTrack& t : kept_) t = WearTrack(period_);
}

double WearProfile::coordinate(double t, const Eigen::VectorXd& q) const {
  return ctx_.system.surface.material_coordinate(tip_position(ctx_.system.beam, t, q), t);
}

std::vector<WearBin> WearProfile::profile(const WearTrack& track) const {
  return track.bins(ctx_.options.wear_profile_bins, min_span_);
}

void WearProfile::step(const StepView& v) {
  if (v.phase == Phase::free) {
    have_last_ = false;
    return;
  }
  // A contact step's load–distance lies uniformly between the material points under its two ends.
  const double s = coordinate(v.t, v.q);
  track_.add(have_last_ ? last_ : s, s, v.integrals.integral[LedgerTerm::sliding_load],
             v.integrals.integral[LedgerTerm::frictional_heat]);
  last_ = s;
  have_last_ = true;
}

void WearProfile::impact(const ImpactView& v) {
  // An impact's load–distance over the contact's own width (the filament's diameter) about its point:
  // a point would put it all into one bin whatever the bins' width.
  const double s = coordinate(v.t, v.q);
  track_.add(s - 0.5 * min_span_, s + 0.5 * min_span_, v.result.sliding_load, v.result.frictional_heat);
}

void WearProfile::contact_start(double t, const Eigen::VectorXd& q, const ContactLoad&, bool) {
  last_ = coordinate(t, q);
  have_last_ = true;
}

void WearProfile::open_revolution(double, const Eigen::VectorXd&, const Eigen::VectorXd&) { track_.clear(); }

void WearProfile::close_revolution(double, const Eigen::VectorXd&, const Eigen::VectorXd&, RevolutionRecord& r) {
  if (!r.complete) return;
  std::swap(kept_[kept_next_], track_);
  kept_next_ = (kept_next_ + 1) % kWearRevolutionsKept;
  kept_count_ = std::min(kept_count_ + 1, kWearRevolutionsKept);
}

void WearProfile::finish(double, const Eigen::VectorXd&, const Eigen::VectorXd&) {
  PassResult& result = ctx_.result;
  result.wear_revolution_profiles.clear();
  if (ctx_.options.revolutions > 0 && kept_count_ > 0) {
    for (int k = kept_count_; k >= 1; --k)
      result.wear_revolution_profiles.push_back(
          profile(kept_[(kept_next_ - k + kWearRevolutionsKept) % kWearRevolutionsKept]));
    result.wear_profile = result.wear_revolution_profiles.back();
  } else {
    result.wear_profile = profile(track_);
  }
}

}  // namespace rotbeam
