// What a brush runs of one filament (docs/brush.md): its configuration drawn from the nominal one,
// and its run to the periodic steady state, reduced to the per-revolution means and the momentum
// deliveries of its orbit. Shared by the filament-by-filament route (brush.cpp) and the population
// (brush_population.cpp).
#pragma once

#include "rotbeam/brush.hpp"
#include "rotbeam/brush_result.hpp"
#include "rotbeam/force_bins.hpp"
#include "rotbeam/config.hpp"
#include "rotbeam/force_record.hpp"
#include "rotbeam/stop_token.hpp"

#include <vector>

namespace rotbeam::detail {

/// The configuration of one filament: the nominal one with its length, diameter and depth, no rows
/// or near-surface rows sampled (the brush keeps no history) and no Floquet multipliers (the brush
/// reports none; they would cost 4n runs of the orbit), validated as a file is. Throws ConfigError.
Config filament_config(const Config& base, const BrushFilament& f);

/// A filament at its steady state: its means per revolution, and its orbit's momentum deliveries
/// (relative angle, 0° where it points at the surface's deepest point), each to be counted with
/// `weight` = 1/m for the orbit's m revolutions.
struct FilamentOrbit {
  FilamentSteadyState state;
  std::vector<MomentumDelivery> deliveries;
  double weight = 1.0;
};

/// Runs the filament of `config` to its periodic steady state (until_steady as configured). Never
/// throws for numerical trouble: a failure is kept in state.failure.
FilamentOrbit run_filament_orbit(const Config& config, const StopToken* stop);

/// A monotonic clock [s].
double clock_s();

/// The brush's sums, counts and warnings from its filaments run (result.distinct with result.run's
/// weights; each filament counted as result.distinct[f.group]), the workpiece's bins `total` and the
/// own-angle bins `profile` (summed over the filaments; divided here by their number).
void finish_brush(BrushResult& result, const Config& config, const ForceBins& total, const ForceBins& profile,
                  double start_s);

/// The brush as a population (brush.method = "population", brush_population.cpp).
BrushResult run_brush_population(const Config& config, const BrushOptions& options);

}  // namespace rotbeam::detail
