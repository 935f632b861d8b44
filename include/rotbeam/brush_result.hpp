// The results of a brush (docs/brush.md): its filaments as drawn, each distinct filament's steady
// state, and what the brush puts on the workpiece. Words only; run_brush (brush.hpp) makes them and
// the brush's files (brush_output.hpp) write them.
#pragma once

#include "rotbeam/brush_settings.hpp"
#include "rotbeam/wear_record.hpp"
#include "rotbeam/force_record.hpp"
#include "rotbeam/ledger.hpp"
#include "rotbeam/outcome.hpp"
#include "rotbeam/pass.hpp"

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace rotbeam {

/// One filament of the brush as drawn from the configuration (brush_filaments).
struct BrushFilament {
  int index = 0;            // 0-based: row r, position k → r·brush.filaments + k
  int row = 0, position = 0;
  double phase_deg = 0;     // how far ahead of the reference filament (index 0 without jitter) it sits [°]
  double length_m = 0, diameter_m = 0;
  // Its own surface.depth_fraction: the surface stays where the nominal filament's depth puts it, so
  // p_k = (L_k − L + pL)/L_k; ≤ 0 when the filament is too short to reach it.
  double depth_fraction = 0;
  int group = 0;            // the distinct filament (length, diameter) it is a copy of; "population": the nearest representative
};

/// One distinct filament at its steady state: per-revolution means over its orbit's m revolutions
/// (m = 1 when the steady state was not reached: the last complete revolution).
struct FilamentSteadyState {
  bool reaches = true;            // the tip reaches the surface at all (depth_fraction > 0)
  bool ran = false;               // its run finished (steady or at simulation.revolutions)
  bool steady = false;            // the periodic steady state was reached
  int period_revolutions = 0;     // m
  int revolutions_run = 0;
  double mean_normal_force_n = 0;       // normal impulse per revolution / revolution period
  double mean_tangential_force_n = 0;
  double mean_hub_torque_n_m = 0;       // hub work per revolution / 2π
  double mean_hub_power_w = 0;          // hub work per revolution / revolution period
  double impacts_per_revolution = 0;
  double contact_time_s = 0;            // per revolution
  double peak_normal_force_n = 0;       // over the orbit, at any instant (0 for impacts alone)
  double max_tip_deflection_ratio = 0;  // over the orbit
  Validity validity = Validity::within;  // of its whole run (pass.hpp)
  double first_contact_deg = NAN, last_contact_deg = NAN;  // relative angle of its first and last delivery of momentum
  double along_min_m = NAN, along_max_m = NAN;             // where its tip touched, along the surface
  // The ledger per revolution (means over the orbit; ledger.hpp) and its largest residual [J].
  Ledger ledger;
  double ledger_residual_max_j = 0;
  std::vector<WearBin> wear_profile;  // its load–distance and heat along the surface per revolution, the orbit's mean
  double wall_time_s = 0;
  std::optional<NumericalFailure> failure;
  std::string error;  // a run that ended without a failure and without a complete revolution, in words
};

/// A filament that was run for the brush: a distinct filament (brush.method = "filaments"), or a
/// representative of the population, with the share of the brush it stands for.
struct RunFilament {
  double length_m = 0, diameter_m = 0, depth_fraction = 0;
  double weight = 0;  // filaments it stands for: its copies, or the sum of its interpolation weights
  int nearest = 0;    // filaments of which it is the nearest (its copies for "filaments")
};

/// One filament's per-revolution values interpolated from the representatives (brush.method =
/// "population"; docs/brush.md), as filaments.csv gives them.
struct FilamentEstimate {
  double mean_normal_force_n = 0, mean_tangential_force_n = 0, mean_hub_torque_n_m = 0, mean_hub_power_w = 0;
  double impacts_per_revolution = 0, contact_time_s = 0, peak_normal_force_n = 0, max_tip_deflection_ratio = 0;
  double ledger_residual_max_j = 0;
};

/// How well the population's interpolation resolves the brush (brush.method = "population").
struct PopulationEstimate {
  double tolerance = 0;   // brush.population_tolerance
  bool converged = false; // the estimated errors are within the tolerance
  int rounds = 0;         // refinement rounds
  int lengths = 0, diameters = 0;  // nodes of the grid in each direction
  int exact_filaments = 0;         // filaments run on their own (cells holding fewer than splitting them costs)
  // Estimated errors of the brush's sums relative to the filament-by-filament route over the same
  // filaments: the interpolation's change at its last refinement, summed in magnitude over the
  // cells; relative to the sum itself.
  double normal_force_error = 0, tangential_force_error = 0, hub_torque_error = 0;
};

/// What the brush puts on the workpiece, and the groups that present it (docs/brush.md).
struct BrushSummary {
  BrushMethod method = BrushMethod::filaments;
  std::optional<PopulationEstimate> population;  // brush.method = "population"
  int filaments = 0, distinct_filaments = 0, reaching = 0, steady = 0, not_steady = 0, failed = 0;
  double revolution_period_s = 0;
  double mean_normal_force_n = 0, mean_tangential_force_n = 0;   // over the revolution [N]
  double peak_normal_force_n = 0, peak_tangential_force_n = 0;   // of the binned force [N]
  double peak_normal_at_deg = NAN;                               // the centre of that bin [°]
  double mean_hub_torque_n_m = 0, mean_hub_power_w = 0;
  // The contact zone: the relative angles over which any filament delivers momentum, and the
  // extent along the surface of where tips touch it.
  double contact_zone_from_deg = NAN, contact_zone_to_deg = NAN, contact_zone_deg = 0, contact_zone_width_m = 0;
  // The brush's ledger per revolution, summed over the filaments (ledger.hpp): its energy terms sum to
  // the energy change (0 on a periodic orbit); the residual is the largest filament's, summed.
  Ledger ledger;
  double ledger_residual_max_j = 0;
  // Dimensionless groups: depth p = d/L; speed Ω/ω₁ (ω₁ the first bending frequency of the nominal
  // cantilever at rest, 1.87510² √(EI/(ρAL⁴))); force per filament F̄/(3EI·pL/L³) (the mean
  // normal force per filament over the static tip force that bends the nominal cantilever by the depth).
  double depth_ratio = 0, speed_ratio = 0, force_ratio = 0;
  double bin_deg = 0;
  // The largest |y_t|/L of the finished filaments' orbits, and the worst of their runs' validity
  // (pass.hpp; docs/model.md, "Validity of a pass").
  double max_tip_deflection_ratio = 0;
  Validity validity = Validity::within;
  double wall_time_s = 0;
  std::optional<NumericalFailure> failure;  // the first filament's failure (or the interruption), if any
  int failed_filament = -1;                 // its index
  std::vector<int> failed_indices;          // every filament that reaches the surface and failed (0-based)
  // The share of the brush's mean normal force that the failed filaments are estimated to carry: each
  // counted as the finished filament of the nearest depth fraction; 0 when none failed, NaN when no
  // filament finished.
  double missing_force_fraction = 0;
  // How much the sums would differ for a brush drawn with another seed: √N·σ/|sum|, σ the standard
  // deviation of the filaments' values over this brush (the filaments too short to reach count 0),
  // relative to the sum; 0 without scatter.
  double seed_spread_normal_force = 0, seed_spread_hub_torque = 0;
  // The filaments the model describes least well: beyond simulation.deflection_warning_ratio (at the
  // edge of the quadratic foreshortening, or outside the model), and those that barely reach the
  // surface (their own depth below a quarter of the nominal one, where the force changes most from
  // filament to filament).
  int at_edge_of_model = 0, outside_model = 0, barely_reaching = 0;
  std::string error;                        // a filament whose run ended without a result, in words ("" for none)
  std::vector<std::string> warnings;
};

struct BrushResult {
  std::vector<BrushFilament> filaments;
  std::vector<FilamentSteadyState> distinct;  // the filaments run: by group, or the representatives
  std::vector<RunFilament> run;               // what each of `distinct` is and stands for
  std::vector<FilamentEstimate> estimates;    // "population": per filament, interpolated (else empty)
  std::vector<ForceBin> workpiece;            // every bin of one revolution of the reference hub angle
  // The force profile across the contact zone: the filaments' deliveries at their own relative angle
  // (0° where a filament points at the surface's deepest point), summed and divided by the number of
  // filaments: the mean filament's force against its angle (impacts counted per filament, summed).
  std::vector<ForceBin> profile;
  // The load–distance and heat all the filaments leave along the surface per revolution (docs/wear.md),
  // in the surface's coordinate (its name, unit and metres per unit).
  std::vector<WearBin> wear_profile;
  std::string wear_coordinate, wear_coordinate_unit;
  double wear_metres_per_unit = 1.0;
  double wear_period = 0.0;  // the coordinate's period (0: not periodic)
  BrushSummary summary;
};

}  // namespace rotbeam
