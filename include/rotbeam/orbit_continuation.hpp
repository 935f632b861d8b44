// Continuation of a filament's periodic orbits in one configuration key (docs/continuation.md): the
// fixed points of the m-revolution section map (steady_state.hpp's SectionMap) followed from `from`
// to `to` by continuation.hpp's pseudo-arclength, with their multipliers, special points and the
// metrics of one period. `rotbeam continue` and rotbeam.continue_orbits run it.
#pragma once

#include "rotbeam/config.hpp"
#include "rotbeam/continuation.hpp"

#include <functional>
#include <string>
#include <vector>

namespace rotbeam {

/// A natural frequency that equals a multiple of the rotation frequency (an engine-order crossing of
/// the Campbell diagram): f_mode(Ω) = order · Ω / 60 at speed Ω [rpm].
struct EngineOrderCrossing {
  int order = 0;
  int mode = 0;  // 1-based, ascending frequency
  double speed_rpm = 0;
  double frequency_hz = 0;
};

struct OrbitContinuationOptions {
  std::string parameter;  // the configuration key continued (any numeric key; not one that changes the modes)
  double from = 0, to = 0;
  int period = 0;         // revolutions per orbit; 0: the period of the steady state found at `from` (else 1)
  double tolerance = 0;   // the points' relative residual; 0: the configuration's simulation.steady_tolerance
  ContinuationSettings settings;  // (its tolerance is replaced by the one above)
};

struct OrbitContinuation {
  ContinuationResult result;
  OrbitContinuationOptions options;
  int period = 1;                 // the first branch's
  int modes = 0;
  std::string start_note;         // how the start at `from` was found
  Config config_from;             // the configuration at `from`
  std::vector<EngineOrderCrossing> crossings;  // when the parameter is hub.speed_rpm: within the range
  double wall_time_s = 0;
};

/// The configuration at a value of the parameter, given as a TOML literal (the shortest decimal of the
/// value). Throws ConfigError naming the key when the value is refused.
using ConfigAtValue = std::function<Config(const std::string& literal)>;

/// Continues the orbits: the steady state at `from` (shooting from the configuration's start, at most
/// 100 revolutions) is the first point. Throws ConfigError naming the key for an
/// unknown or non-numeric key, a brush, a key that changes the mode count, or an empty range.
/// Numerical trouble ends a branch and is described in the result (never thrown).
OrbitContinuation continue_orbits(const ConfigAtValue& config_at, const OrbitContinuationOptions& options,
                                  const std::function<void(const ContinuationProgress&)>& on_point = {});

/// The input checks of continue_orbits alone (before any work): the key, the range, the period, a
/// brush, a key that changes the mode count. Throws ConfigError naming the option or key.
void check_orbit_continuation(const ConfigAtValue& config_at, const OrbitContinuationOptions& options);

/// The engine-order crossings of orders 1 … max_order of the beam of `base` over [lo, hi] rpm (its
/// natural frequencies on a grid of 241 speeds, crossings located by linear interpolation).
std::vector<EngineOrderCrossing> engine_order_crossings(const BeamParameters& base, double lo_rpm, double hi_rpm,
                                                        int max_order = 12);

/// The shortest decimal that reads back as v (a TOML literal for a parameter value).
std::string parameter_literal(double v);

}  // namespace rotbeam
