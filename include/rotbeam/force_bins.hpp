// The force the tip puts on the surface, binned over the hub angle (docs/model.md §7, output.bin_deg): the
// momentum each bin receives — the impulses of the impacts in it and ∫F dt of sustained contact
// over it — and that momentum divided by the bin's duration, the mean force over the bin. A pass
// made of impacts alone has no contact force at any instant, but its binned force is what the
// surface feels on average; the brush sums these over its filaments (docs/brush.md), phase-shifted,
// from each filament's momentum deliveries, with a third channel: the hub's angular impulse.
#pragma once

#include "rotbeam/force_record.hpp"

#include <vector>

namespace rotbeam {

/// Bins of width bin_deg over the relative hub angle (−180°, 180°] of a hub turning at ω [rad/s].
/// Storage is fixed at construction (360°/bin_deg bins); adding allocates nothing.
class ForceBins {
public:
  ForceBins(double bin_deg, double omega);

  void clear();
  /// An impulse (an impact) at relative angle `angle_deg`: normal ≥ 0 and tangential [N s].
  void add_impulse(double angle_deg, double normal_n_s, double tangential_n_s);
  /// Momentum delivered uniformly in angle from `from_deg` over `span_deg` ≥ 0 (a contact step; the
  /// span may cross ±180°) [N s].
  void add_spread(double from_deg, double span_deg, double normal_n_s, double tangential_n_s,
                  double hub_angular_n_m_s = 0);
  /// A delivery moved by −shift_deg in angle (a filament at phase shift_deg ahead of the reference
  /// reaches angle α when the reference is at α − shift) and scaled by `weight` (1/m for one of the m
  /// revolutions of a period-m orbit); an impact counts `weight` impacts (a bin's count is rounded to
  /// the nearest whole number: per revolution for a period-m orbit).
  void add(const MomentumDelivery& d, double shift_deg = 0, double weight = 1);
  /// `count` impacts at relative angle `angle_deg`, their momentum given elsewhere (a population's
  /// impacts: its filaments' interpolation weights).
  void add_impacts(double angle_deg, double count);
  /// Adds the bins of `other` (same bin_deg and ω) bin by bin.
  void merge(const ForceBins& other);

  double bin_deg() const { return bin_deg_; }
  /// The bins from the first to the last that received momentum (empty when none did).
  std::vector<ForceBin> table() const;
  /// Every bin of the revolution, from −180° to 180°, touched or not.
  std::vector<ForceBin> full_table() const;
  BinnedForcePeaks peaks() const;

private:
  int index(double angle_deg) const;
  double bin_width_deg(int k) const;   // bin_deg, less for a last bin cut at 180°
  double bin_duration_s(int k) const;  // the time the hub takes to turn bin k [s]

  double bin_deg_, omega_;
  int count_;
  ForceBin bin(int k) const;

  std::vector<double> normal_, tangential_, hub_;
  std::vector<double> impacts_;  // weighted counts (ForceBin::impacts rounds them)
  std::vector<char> touched_;
};

}  // namespace rotbeam
