// The [brush] section of a configuration (docs/brush.md): how many filaments, how they are set
// around the hub, and how their lengths and diameters scatter. Every other key describes the
// nominal filament, as for one.
#pragma once

#include <cstdint>

namespace rotbeam {

/// How a brush's filaments are computed (docs/brush.md): each distinct filament run on its own, or
/// the brush as a population, its sums interpolated from representative filaments.
enum class BrushMethod { filaments, population };

struct BrushSettings {
  int filaments = 1;              // brush.filaments: around the circumference, equally spaced in phase
  int rows = 1;                   // brush.rows: axial rows (copies in this planar model unless offset)
  double row_phase_deg = 0;       // brush.row_phase_deg: phase offset of row r is r·row_phase_deg [°]
  double phase_jitter_deg = 0;    // brush.phase_jitter_deg: standard deviation of each filament's phase [°]
  double length_scatter = 0;      // brush.length_scatter: relative standard deviation of L
  double diameter_scatter = 0;    // brush.diameter_scatter: relative standard deviation of D
  std::uint64_t seed = 1;         // brush.seed: the scatter's random stream
  BrushMethod method = BrushMethod::filaments;  // brush.method
  double population_tolerance = 2e-3;  // brush.population_tolerance: relative error the population aims at
  int population_max_runs = 96;        // brush.population_max_runs: representative filaments run at most
};

}  // namespace rotbeam
