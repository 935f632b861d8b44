// A brush (docs/brush.md): many filaments on one hub, each run to its periodic steady state on its
// own (filaments do not touch one another in this model), and the force, torque and power on the
// workpiece as the phase-shifted sum of the filaments' momentum deliveries over one revolution.
// Identical filaments are computed once; distinct ones run in parallel on the job runner.
#pragma once

#include "rotbeam/config.hpp"
#include "rotbeam/force_bins.hpp"
#include "rotbeam/outcome.hpp"
#include "rotbeam/stop_token.hpp"

#include <functional>
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
  int group = 0;            // the distinct filament (length, diameter) it is a copy of
};

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
  double first_contact_deg = NAN, last_contact_deg = NAN;  // relative angle of its first and last delivery of momentum
  double along_min_m = NAN, along_max_m = NAN;             // where its tip touched, along the surface
  // The ledger per revolution (means over the orbit) and its largest residual [J].
  double hub_work_j = 0, friction_work_j = 0, surface_work_j = 0, damping_work_j = 0, impact_loss_j = 0,
         energy_change_j = 0;
  double contact_dissipation_j = 0;  // a compliant contact's damping (contact.model = "hertz"), in the ledger
  double ledger_residual_j = 0;
  double wall_time_s = 0;
  std::optional<NumericalFailure> failure;
  std::string error;  // a run that ended without a failure and without a complete revolution, in words
};

/// What the brush puts on the workpiece, and the groups that present it (docs/brush.md).
struct BrushSummary {
  int filaments = 0, distinct_filaments = 0, reaching = 0, steady = 0, not_steady = 0, failed = 0;
  double revolution_period_s = 0;
  double mean_normal_force_n = 0, mean_tangential_force_n = 0;   // over the revolution [N]
  double peak_normal_force_n = 0, peak_tangential_force_n = 0;   // of the binned force [N]
  double peak_normal_at_deg = NAN;                               // the centre of that bin [°]
  double mean_hub_torque_n_m = 0, mean_hub_power_w = 0;
  // The contact zone: the relative angles over which any filament delivers momentum, and the
  // extent along the surface of where tips touch it.
  double contact_zone_from_deg = NAN, contact_zone_to_deg = NAN, contact_zone_deg = 0, contact_zone_width_m = 0;
  // The brush's ledger per revolution, summed over the filaments: hub + friction + surface + damping + impact
  // loss = energy change (0 on a periodic orbit); the residual is the largest filament's, summed.
  double hub_work_j = 0, friction_work_j = 0, surface_work_j = 0, damping_work_j = 0, impact_loss_j = 0,
         energy_change_j = 0;
  double contact_dissipation_j = 0;  // a compliant contact's damping (contact.model = "hertz"), in the ledger
  double ledger_residual_j = 0;
  // Dimensionless groups: depth p = d/L; speed Ω/ω₁ (ω₁ the first bending frequency of the nominal
  // cantilever at rest, 1.87510² √(EI/(ρAL⁴))); force per filament F̄/(3EI·pL/L³) (the mean
  // normal force per filament over the static tip force that bends the nominal cantilever by the depth).
  double depth_ratio = 0, speed_ratio = 0, force_ratio = 0;
  double bin_deg = 0;
  double wall_time_s = 0;
  std::optional<NumericalFailure> failure;  // the first filament's failure (or the interruption), if any
  int failed_filament = -1;                 // its index
  std::string error;                        // a filament whose run ended without a result, in words ("" for none)
  std::vector<std::string> warnings;
};

struct BrushResult {
  std::vector<BrushFilament> filaments;
  std::vector<FilamentSteadyState> distinct;  // by group
  std::vector<ForceBin> workpiece;            // every bin of one revolution of the reference hub angle
  // The force profile across the contact zone: the filaments' deliveries at their own relative angle
  // (0° where a filament points at the surface's deepest point), summed and divided by the number of
  // filaments: the mean filament's force against its angle (impacts counted per filament, summed).
  std::vector<ForceBin> profile;
  BrushSummary summary;
};

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
