#include "brush_filament.hpp"

#include "rotbeam/case.hpp"
#include "rotbeam/wear.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <utility>

namespace rotbeam::detail {

namespace {

// Collects one filament's momentum deliveries revolution by revolution, keeping the last
// kMaxPeriod complete revolutions (the longest orbit the steady-state search finds) and their
// records. Rows and events are dropped. The vectors are recycled, so after the first revolutions
// nothing is allocated.
class DeliveryRing final : public PassSink {
public:
  static constexpr std::size_t kMaxPeriod = 4;

  void row(const HistoryRow&) override {}
  void event(const PassEvent&) override {}
  bool wants_deliveries() const override { return true; }
  void delivery(const MomentumDelivery& d) override { current_.push_back(d); }
  void revolution(const RevolutionRecord& r) override {
    if (!r.complete) {
      current_.clear();
      return;
    }
    std::vector<MomentumDelivery> recycled;
    if (kept_.size() == kMaxPeriod) {
      recycled = std::move(kept_.front().first);
      kept_.pop_front();
    }
    kept_.emplace_back(std::move(current_), r);
    current_ = std::move(recycled);
    current_.clear();
  }
  /// The last m complete revolutions, oldest first (fewer when fewer were run).
  std::vector<const std::pair<std::vector<MomentumDelivery>, RevolutionRecord>*> last(std::size_t m) const {
    std::vector<const std::pair<std::vector<MomentumDelivery>, RevolutionRecord>*> out;
    const std::size_t take = std::min(m, kept_.size());
    for (std::size_t i = kept_.size() - take; i < kept_.size(); ++i) out.push_back(&kept_[i]);
    return out;
  }

private:
  std::vector<MomentumDelivery> current_;
  std::deque<std::pair<std::vector<MomentumDelivery>, RevolutionRecord>> kept_;
};

}  // namespace

Config filament_config(const Config& base, const BrushFilament& f) {
  Config c = base;
  c.brush.reset();
  c.beam.length_m = f.length_m;
  c.beam.diameter_m = f.diameter_m;
  c.surface.depth_fraction = f.depth_fraction;
  c.simulation.output_interval_s = 1e30;
  c.simulation.near_surface_gap_m = 0.0;
  c.simulation.multipliers = false;
  return revalidate(c);
}

double clock_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

FilamentOrbit run_filament_orbit(const Config& config, const StopToken* stop) {
  FilamentOrbit out;
  FilamentSteadyState& s = out.state;
  const double start = clock_s();
  const Case c = build_case(config);
  DeliveryRing ring;
  const PassResult r = run_case(c, {&ring, stop, {}});
  s.wall_time_s = clock_s() - start;
  s.revolutions_run = r.summary.revolutions;
  s.failure = r.failure;
  if (r.failure) return out;
  s.ran = true;
  s.validity = r.summary.validity;
  s.steady = r.summary.steady_state.reached;
  const std::size_t m = s.steady ? static_cast<std::size_t>(std::max(1, r.summary.steady_state.period_revolutions)) : 1;
  const auto orbit = ring.last(m);
  if (orbit.empty()) {  // cannot happen for a run that ended without a failure: said, not hidden
    s.ran = false;
    s.error = "the run ended without a complete revolution";
    return out;
  }
  s.period_revolutions = static_cast<int>(orbit.size());
  const double weight = 1.0 / static_cast<double>(orbit.size());
  const double omega = c.beam->hub_motion().omega;
  const double period_s = 2.0 * M_PI / omega;
  double normal = 0, tangential = 0, hub = 0;
  for (const auto* rev : orbit) {
    for (const MomentumDelivery& d : rev->first) {
      normal += d.normal_n_s;
      tangential += d.tangential_n_s;
      hub += d.hub_angular_impulse_n_m_s;
      if (d.normal_n_s > 0.0) {
        // The delivery's own angles (its first point, and its last for a step).
        const double last = d.from_deg + d.span_deg;
        s.first_contact_deg = std::isnan(s.first_contact_deg) ? d.from_deg : std::min(s.first_contact_deg, d.from_deg);
        s.last_contact_deg = std::isnan(s.last_contact_deg) ? last : std::max(s.last_contact_deg, last);
        if (std::isfinite(d.along_m)) {
          s.along_min_m = std::isnan(s.along_min_m) ? d.along_m : std::min(s.along_min_m, d.along_m);
          s.along_max_m = std::isnan(s.along_max_m) ? d.along_m : std::max(s.along_max_m, d.along_m);
        }
      }
    }
    const RevolutionRecord& rec = rev->second;
    s.impacts_per_revolution += weight * rec.impacts;
    s.contact_time_s += weight * rec.contact_time_s;
    s.peak_normal_force_n = std::max(s.peak_normal_force_n, rec.peak_normal_force_n);
    s.max_tip_deflection_ratio = std::max(s.max_tip_deflection_ratio, rec.max_tip_deflection_ratio);
    for (std::size_t k = 0; k < kLedgerTermCount; ++k) s.ledger.value[k] += weight * rec.ledger.value[k];
    s.ledger.energy_change_j += weight * rec.ledger.energy_change_j;
    s.ledger_residual_max_j = std::max(s.ledger_residual_max_j, std::abs(rec.ledger.residual()));
  }
  s.mean_normal_force_n = weight * normal / period_s;
  s.mean_tangential_force_n = weight * tangential / period_s;
  s.mean_hub_torque_n_m = weight * hub / period_s;
  s.mean_hub_power_w = s.mean_hub_torque_n_m * omega;
  out.weight = weight;
  for (const auto* rev : orbit) out.deliveries.insert(out.deliveries.end(), rev->first.begin(), rev->first.end());
  // The wear along the surface; round a spinning cylinder, whose material turns under the contact and
  // under each copy's phase, spread evenly (wear.hpp).
  const SurfaceCoordinate k = c.surface->coordinate();
  s.wear_profile = mean_profile(r.wear_revolution_profiles, static_cast<int>(orbit.size()), config.simulation.wear_profile_bins,
                                k.period);
  if (config.surface.shape == SurfaceShape::cylinder && config.surface.speed_rpm != 0.0)
    s.wear_profile = spread_around(s.wear_profile, config.simulation.wear_profile_bins, k.period);
  return out;
}

}  // namespace rotbeam::detail
