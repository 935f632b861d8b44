// A brush (docs/brush.md): many filaments on one hub, each run to its periodic steady state on its
// own (filaments do not touch one another in this model), and the force, torque and power on the
// workpiece as the phase-shifted sum of the filaments' momentum deliveries over one revolution.
// Identical filaments are computed once; distinct ones run in parallel on the job runner.
#pragma once

#include "rotbeam/brush_result.hpp"
#include "rotbeam/config.hpp"
#include "rotbeam/stop_token.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rotbeam {

/// The filaments a configuration with [brush] describes, in index order: phases 360°·k/filaments +
/// r·row_phase_deg + jitter·N(0,1); L = L0(1 + length_scatter·N(0,1)), D likewise, each standard
/// normal draw truncated to ±3 (redrawn beyond). Three draws per filament, always in that order,
/// from Boost's mt19937_64 seeded with brush.seed, so a seed gives the same brush on every platform
/// and one scatter's value does not change another's draws. Throws ConfigError without [brush].
std::vector<BrushFilament> brush_filaments(const Config& config);

/// The validated configuration of each distinct filament (by group; a default Config for one that
/// does not reach the surface): the nominal one with its length, diameter and depth, no history, no
/// multipliers. Throws ConfigError naming the filament when a drawn one is invalid (a diameter
/// beyond its length).
std::vector<Config> brush_filament_configs(const Config& config, const std::vector<BrushFilament>& filaments);

struct BrushProgress {
  int total = 0, finished = 0;  // distinct filaments that reach the surface
  double elapsed_s = 0, eta_s = 0;
};

struct BrushOptions {
  int threads = 0;  // 0: all cores
  const StopToken* stop = nullptr;
  std::function<void(const BrushProgress&)> on_progress;  // after each distinct filament (under a lock)
};

/// Runs every distinct filament of `config` (which has [brush]) to its periodic steady state and sums
/// the brush. Never throws for numerical trouble: a filament's failure is kept in its record and the
/// summary (the sums then hold the other filaments). Throws ConfigError without [brush], and when a
/// drawn filament's configuration is invalid (before anything runs, naming the filament).
BrushResult run_brush(const Config& config, const BrushOptions& options = {});

}  // namespace rotbeam
