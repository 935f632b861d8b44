#include "rotbeam/wear.hpp"

#include <algorithm>
#include <cmath>

namespace rotbeam {

WearAmounts wear_amounts(const WearSettings& w, double sliding_load_n_m, double heat_j, double filament_diameter_m) {
  WearAmounts a;
  a.sliding_load_n_m = sliding_load_n_m;
  a.surface_volume_m3 = w.surface_coefficient * a.sliding_load_n_m / w.surface_hardness_pa;
  a.filament_volume_m3 = w.filament_coefficient * a.sliding_load_n_m / w.filament_hardness_pa;
  a.filament_length_m = a.filament_volume_m3 / (0.25 * M_PI * filament_diameter_m * filament_diameter_m);
  a.heat_j = heat_j;
  a.heat_to_filament_j = w.heat_to_filament * a.heat_j;
  a.heat_to_surface_j = a.heat_j - a.heat_to_filament_j;
  return a;
}

void WearTrack::add(double s0, double s1, double sliding_load_n_m, double heat_j) {
  if (period_ > 0.0) s1 = s0 + std::remainder(s1 - s0, period_);
  pieces_.push_back({s0, s1, sliding_load_n_m, heat_j});
}

void WearTrack::append(const WearTrack& other) { pieces_.insert(pieces_.end(), other.pieces_.begin(), other.pieces_.end()); }

namespace {

// Spreads `load` and `heat`, uniform over [a, b] (a ≤ b; a point where a = b), onto the bins of width h
// from lo: each bin takes the part that overlaps it.
void spread(std::vector<WearBin>& out, double lo, double h, double a, double b, double load, double heat) {
  const int count = static_cast<int>(out.size());
  auto index = [&](double s) { return std::clamp(static_cast<int>(std::floor((s - lo) / h)), 0, count - 1); };
  const int i0 = index(a), i1 = index(b);
  if (i0 == i1 || !(b > a)) {
    out[i0].sliding_load_n_m += load;
    out[i0].heat_j += heat;
    return;
  }
  const double length = b - a;
  for (int i = i0; i <= i1; ++i) {
    // The first and last bins take their overlap; the clamped ends take what lies beyond them.
    const double from = i == i0 ? a : lo + i * h, to = i == i1 ? b : lo + (i + 1) * h;
    const double f = (to - from) / length;
    out[i].sliding_load_n_m += f * load;
    out[i].heat_j += f * heat;
  }
}

std::vector<WearBin> empty_bins(double lo, double hi, int count) {
  std::vector<WearBin> out(count);
  const double h = (hi - lo) / count;
  for (int i = 0; i < count; ++i) out[i].from = lo + i * h, out[i].to = i + 1 == count ? hi : lo + (i + 1) * h;
  return out;
}

}  // namespace

std::vector<WearBin> WearTrack::bins(int count, double min_span, double weight) const {
  if (pieces_.empty() || count < 1) return {};
  // A periodic coordinate: every piece moved by whole periods to start within half a period of the
  // load-weighted circular mean of the pieces (so the same spot of the surface has one place).
  double ref = pieces_.front().s0;
  if (period_ > 0.0) {
    double c = 0, s = 0;
    for (const Piece& p : pieces_) {
      const double a = 2.0 * M_PI * 0.5 * (p.s0 + p.s1) / period_, w = p.load + p.heat;
      c += w * std::cos(a), s += w * std::sin(a);
    }
    if (c != 0.0 || s != 0.0) ref = std::atan2(s, c) * period_ / (2.0 * M_PI);
  }
  auto shift = [&](double s0) { return period_ > 0.0 ? ref + std::remainder(s0 - ref, period_) - s0 : 0.0; };
  double lo = INFINITY, hi = -INFINITY;
  for (const Piece& p : pieces_) {
    const double d = shift(p.s0);
    lo = std::min({lo, p.s0 + d, p.s1 + d});
    hi = std::max({hi, p.s0 + d, p.s1 + d});
  }
  // Around a whole period (a tip sliding all the way round): the bins cover one period from half a
  // period before the first piece, and a piece that runs past its end continues from its start.
  const bool around = period_ > 0.0 && hi - lo >= period_;
  if (around) lo = ref - 0.5 * period_, hi = lo + period_;
  if (hi - lo < min_span) {
    const double c = 0.5 * (lo + hi);
    lo = c - 0.5 * min_span, hi = c + 0.5 * min_span;
  }
  std::vector<WearBin> out = empty_bins(lo, hi, count);
  const double h = (hi - lo) / count;
  for (const Piece& p : pieces_) {
    const double d = shift(p.s0);
    double a = std::min(p.s0, p.s1) + d, b = std::max(p.s0, p.s1) + d;
    const double load = weight * p.load, heat = weight * p.heat;
    if (around && (a < lo || b > hi)) {
      if (a < lo) a += period_, b += period_;
      if (a >= hi) a -= period_, b -= period_;
      if (b > hi && b > a) {  // the part past the end, from the start
        const double f = (b - hi) / (b - a);
        spread(out, lo, h, lo, lo + (b - hi), f * load, f * heat);
        spread(out, lo, h, a, hi, (1.0 - f) * load, (1.0 - f) * heat);
        continue;
      }
    }
    spread(out, lo, h, a, b, load, heat);
  }
  return out;
}

std::vector<WearBin> rebin(const std::vector<std::vector<WearBin>>& profiles, const std::vector<double>& weights,
                           int count, double period) {
  if (period > 0.0) {
    // Folded as a track of the bins' pieces (each a span; a wide one split so that no half exceeds half a period).
    WearTrack track(period);
    for (std::size_t k = 0; k < profiles.size(); ++k)
      for (const WearBin& b : profiles[k]) {
        const int parts = static_cast<int>(std::ceil((b.to - b.from) / (0.25 * period)));
        for (int i = 0; i < std::max(parts, 1); ++i) {
          const double f = 1.0 / std::max(parts, 1);
          track.add(b.from + i * f * (b.to - b.from), b.from + (i + 1) * f * (b.to - b.from),
                    f * weights[k] * b.sliding_load_n_m, f * weights[k] * b.heat_j);
        }
      }
    return track.bins(count, 0.0);
  }
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& p : profiles)
    for (const WearBin& b : p) lo = std::min(lo, b.from), hi = std::max(hi, b.to);
  if (!(hi > lo) || count < 1) return {};
  std::vector<WearBin> out = empty_bins(lo, hi, count);
  const double h = (hi - lo) / count;
  for (std::size_t k = 0; k < profiles.size(); ++k)
    for (const WearBin& b : profiles[k])
      spread(out, lo, h, b.from, b.to, weights[k] * b.sliding_load_n_m, weights[k] * b.heat_j);
  return out;
}

std::vector<WearBin> mean_profile(const std::vector<std::vector<WearBin>>& revolution_profiles, int m, int count,
                                  double period) {
  if (m < 1 || static_cast<int>(revolution_profiles.size()) < m) return {};
  const std::vector<std::vector<WearBin>> last(revolution_profiles.end() - m, revolution_profiles.end());
  return rebin(last, std::vector<double>(m, 1.0 / m), count, period);
}

std::vector<WearBin> spread_around(const std::vector<WearBin>& profile, int count, double period) {
  double load = 0, heat = 0;
  for (const WearBin& b : profile) load += b.sliding_load_n_m, heat += b.heat_j;
  std::vector<WearBin> out = empty_bins(-0.5 * period, 0.5 * period, std::max(count, 1));
  for (WearBin& b : out) b.sliding_load_n_m = load / out.size(), b.heat_j = heat / out.size();
  return out;
}

WearReport wear_report(const PassResult& result, const WearSettings& w, const Surface& surface,
                       double filament_diameter_m, int profile_bins) {
  WearReport r;
  r.coordinate = surface.coordinate();
  r.track_width_m = w.track_width_m > 0.0 ? w.track_width_m : filament_diameter_m;
  const PassSummary& s = result.summary;
  double load = 0, heat = 0;
  if (s.revolutions > 0 || !result.wear_revolution_profiles.empty()) {
    const SteadyState& st = s.steady_state;
    int m = st.reached ? std::max(st.period_revolutions, 1) : 1;
    if (m > static_cast<int>(result.wear_revolution_profiles.size())) {
      r.note = "the last " + std::to_string(result.wear_revolution_profiles.size()) +
               " complete revolutions were kept, fewer than the orbit's period of " + std::to_string(m) +
               ": per revolution over the last one";
      m = 1;
    }
    if (result.wear_revolution_profiles.empty()) {
      r.note = "no revolution completed: over the run so far";
      r.profile = result.wear_profile;
    } else {
      r.revolutions = m;
      r.profile = mean_profile(result.wear_revolution_profiles, m, profile_bins, r.coordinate.period);
      if (r.note.empty())
        r.note = st.reached ? "per revolution: the mean over the steady orbit's period of " + std::to_string(m)
                            : "per revolution: the last complete revolution (no steady state was sought or reached)";
    }
  } else {
    r.profile = result.wear_profile;
    r.note = "over the pass";
  }
  for (const WearBin& b : r.profile) load += b.sliding_load_n_m, heat += b.heat_j;
  r.amounts = wear_amounts(w, load, heat, filament_diameter_m);
  return r;
}

double removed_depth_m(const WearBin& bin, const WearSettings& w, const SurfaceCoordinate& coordinate,
                       double track_width_m) {
  const double volume = w.surface_coefficient * bin.sliding_load_n_m / w.surface_hardness_pa;
  return volume / (track_width_m * (bin.to - bin.from) * coordinate.metres_per_unit);
}

}  // namespace rotbeam
