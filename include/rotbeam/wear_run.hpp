// Wear over hours of operation (`rotbeam wear`, docs/wear.md): the slow-time loop. At each slow step
// the filament's periodic steady state is found (simulation.until_steady), its wear per revolution
// turned into rates per hour, and the filament shortened by its tip's wear over the step; the surface
// stays where it is in space (its worn depth, nanometres to micrometres per hour, is reported and
// accumulated along it, not fed back into its shape). Explicit Euler in operating time; docs/wear.md
// gives its error against halved steps.
#pragma once

#include "rotbeam/config.hpp"
#include "rotbeam/stop_token.hpp"
#include "rotbeam/wear.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rotbeam {

struct WearRunOptions {
  double hours = 10;  // operating time [h]
  int steps = 10;     // slow-time steps over it
  const StopToken* stop = nullptr;
  std::function<void(int step, int steps, double length_m)> on_step;  // before each steady-state search
};

/// The state of one slow step: the filament's length when it starts and its steady state's wear per
/// revolution, as rates per hour of operation.
struct WearStep {
  int step = 0;                      // 0, 1, …
  double time_h = 0;                 // operating time at the step's start [h]
  double duration_h = 0;             // its length in operating time (0 for the last record; shorter for
                                     // a step cut where the filament stops reaching the surface) [h]
  double length_m = 0;               // the filament's free length L at the step's start [m]
  bool reaches = true;               // the undeformed tip still reaches the surface
  bool ran = false;                  // its steady-state search finished (the quantities below are its)
  bool steady = false;               // its steady state was reached within simulation.revolutions
  int period_revolutions = 0;
  int revolutions_run = 0;
  double section_distance = NAN;     // the section distance over the orbit's period at the search's end
  double impacts_per_revolution = 0; // the orbit's mean
  double mean_normal_force_n = 0;    // normal impulse per revolution over its duration [N]
  double mean_hub_torque_n_m = 0;
  double mean_hub_power_w = 0;
  WearAmounts per_revolution;        // wear and heat per revolution
  double removal_rate_m3_h = 0;      // the surface's worn volume per hour [m³/h]
  double length_rate_m_h = 0;        // the filament's length lost per hour [m/h]
  double heat_rate_w = 0;            // the frictional heat per second [W]
  double length_lost_m = 0;          // over the step: length_rate × duration [m]
  double volume_removed_m3 = 0;      // over the step [m³]
  std::vector<WearBin> profile;      // per revolution (spread round a spinning cylinder)
  double wall_time_s = 0;
};

struct WearRun {
  std::vector<WearStep> steps;
  std::vector<WearBin> removed_profile;  // the surface's load–distance and heat over the whole run, along it
  double length_lost_m = 0;              // Σ steps
  double volume_removed_m3 = 0;          // Σ steps
  double heat_j = 0;                     // Σ steps
  SurfaceCoordinate coordinate{};
  double track_width_m = 0;
  bool stopped_early = false;            // the filament no longer reaches, a run failed or a stop was asked
  std::string note;                      // why it stopped early, or ""
  std::vector<std::string> warnings;     // steps too long for explicit Euler
  std::optional<NumericalFailure> failure;
};

/// Runs `config` (one filament, not a brush) over options.hours of operation in options.steps steps.
/// Throws ConfigError for a brush or bad options; numerical failures end the run with what it computed.
WearRun run_wear(const Config& config, const WearRunOptions& options);

/// The configuration of the filament at free length `length_m` with its surface where `base` has it in
/// space (plane and cylinder: the same nearest distance; casing: the same radius), validated.
Config worn_config(const Config& base, double length_m);

}  // namespace rotbeam
