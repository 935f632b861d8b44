// Wear and frictional heat (docs/wear.md): Archard's law on the contact's load–distance integral,
// the heat friction makes at the contact and its partition between the filament and the surface,
// and the wear profile along the surface (the load–distance binned over Surface::material_coordinate).
// The pass integrates the two ledger terms they rest on (ledger.hpp: frictional_heat, sliding_load);
// everything here is derived from them and from the settings of the [wear] section.
#pragma once

#include "rotbeam/ledger.hpp"
#include "rotbeam/pass.hpp"
#include "rotbeam/surface.hpp"
#include "rotbeam/wear_record.hpp"

#include <string>
#include <vector>

namespace rotbeam {

/// The [wear] section: Archard's coefficient and hardness of each body, the heat's partition and the
/// profile's geometry. The defaults are those of a hard steel wire on a mild-steel part in mild
/// (oxidative) sliding wear (docs/wear.md gives their sources and ranges).
struct WearSettings {
  double surface_coefficient = 1e-4;   // k_s, Archard's dimensionless wear coefficient of the surface's material
  double surface_hardness_pa = 2e9;    // H_s, the surface material's hardness [Pa] (≈ 200 HV)
  double filament_coefficient = 1e-5;  // k_f, the filament's [-]
  double filament_hardness_pa = 5e9;   // H_f [Pa] (≈ 500 HV, a spring-steel wire)
  double heat_to_filament = 0.5;       // the share of the frictional heat that flows into the filament [-]
  double track_width_m = 0;            // the worn track's width across the plane of motion [m] (0: the filament's diameter)
};

/// The worn volumes [m³] and heats [J] of a load–distance integral S [N m] and a frictional heat Q [J]:
/// V = k S / H per body; Q split by heat_to_filament.
struct WearAmounts {
  double sliding_load_n_m = 0;   // S = ∫F_n|V_t| dt (+ the impacts') [N m]
  double surface_volume_m3 = 0;  // k_s S / H_s
  double filament_volume_m3 = 0; // k_f S / H_f
  double filament_length_m = 0;  // the filament's volume over its cross-section πD²/4 [m]
  double heat_j = 0;             // Q [J]
  double heat_to_filament_j = 0;
  double heat_to_surface_j = 0;
};
WearAmounts wear_amounts(const WearSettings& w, double sliding_load_n_m, double heat_j, double filament_diameter_m);

/// What a contact left along the surface: pieces [s0, s1] of the coordinate (s0 = s1 for an impact),
/// each with its load–distance and heat spread uniformly over it. Storage grows to the largest
/// revolution's number of contact steps and is reused after clear().
class WearTrack {
public:
  explicit WearTrack(double period = 0) : period_(period) {}
  void clear() { pieces_.clear(); }
  bool empty() const { return pieces_.empty(); }
  /// A piece from s0 to s1 (a periodic coordinate is unwrapped so that the piece is the shorter arc).
  void add(double s0, double s1, double sliding_load_n_m, double heat_j);
  /// Appends the pieces of `other` (the same coordinate).
  void append(const WearTrack& other);
  /// `bins` equal bins over the span the pieces cover (at least `min_span` wide, centred on them; a
  /// periodic coordinate's span is taken where its pieces are, continued across the seam), each
  /// holding the part of every piece that overlaps it, the whole scaled by `weight`. Exact in the sums:
  /// the bins add up to the pieces' totals times weight.
  std::vector<WearBin> bins(int bins, double min_span, double weight = 1.0) const;

private:
  struct Piece {
    double s0, s1, load, heat;
  };
  double period_;
  std::vector<Piece> pieces_;
};

/// Moves the bins of several profiles (each exact in its sums) onto `count` equal bins over the span
/// they all cover, by overlap: the totals are kept to round-off. Weights scale each profile. On a
/// periodic coordinate (period > 0) the profiles are folded onto one window about their circular mean,
/// so that a spot of the surface has one place whichever revolution put it at φ or φ − 360°.
std::vector<WearBin> rebin(const std::vector<std::vector<WearBin>>& profiles, const std::vector<double>& weights,
                           int count, double period = 0.0);

/// A profile's totals spread evenly over one period of its coordinate in `count` bins: where a spinning
/// cylinder's wear falls over many revolutions (its spin and the hub's are not locked).
std::vector<WearBin> spread_around(const std::vector<WearBin>& profile, int count, double period);

/// The mean profile per revolution of a period-m orbit: the last m of a pass's revolution profiles
/// (PassResult::wear_revolution_profiles) rebinned onto `count` bins with weight 1/m each. Empty when
/// fewer than m were kept.
std::vector<WearBin> mean_profile(const std::vector<std::vector<WearBin>>& revolution_profiles, int m, int count,
                                  double period = 0.0);

/// What a pass wore and heated, as summary.json's `wear` and wear_profile.csv report it: over the pass
/// (revolutions = 0), or per revolution as the mean over the steady orbit's period (or the last
/// complete revolution when no steady state was reached; `note` says which).
struct WearReport {
  int revolutions = 0;               // 0: the whole pass; m: per revolution, the mean of the last m
  std::vector<WearBin> profile;      // its bins (they sum to amounts' load–distance and heat)
  WearAmounts amounts;
  double track_width_m = 0;          // wear.track_width_m, or the filament's diameter
  SurfaceCoordinate coordinate{};
  std::string note;
};
WearReport wear_report(const PassResult& result, const WearSettings& w, const Surface& surface,
                       double filament_diameter_m, int profile_bins);

/// The removed depth [m] of a bin: its surface volume k_s S / H_s over the track's width times the
/// bin's length along the surface (coordinate.metres_per_unit).
double removed_depth_m(const WearBin& bin, const WearSettings& w, const SurfaceCoordinate& coordinate,
                       double track_width_m);

}  // namespace rotbeam
