// Case configuration (SPEC §9): one TOML file plus `--set section.key=value` overrides.
// Unknown keys, wrong types, non-finite and out-of-range values raise ConfigError with a one-line
// message naming the key and the value. The defaults reproduce the thesis's base case.
#pragma once

#include "rotbeam/first_impact.hpp"
#include "rotbeam/impact.hpp"
#include "rotbeam/model.hpp"
#include "rotbeam/pass.hpp"

#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace rotbeam {

class ConfigError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct Config {
  PhysicalParameters physical;             // [beam], [hub], [surface]
  ImpactLaw impact;                        // [impact], compat.restitution_speed
  std::string start = "rigid";             // initial.start as resolved ("rigid" | "flexible")
  std::vector<double> modal_velocity;      // initial.modal_velocity [m/s], n values
  std::vector<double> modal_displacement;  // initial.modal_displacement [m], n values
  std::string scheme = "adaptive";         // simulation.scheme
  double end_angle_deg = 90.0;             // simulation.end_angle_deg
  double rtol = 1e-9, atol = 1e-12;        // simulation.rtol / atol (adaptive scheme)
  double max_step_s = 2e-5;                // simulation.max_step_s (adaptive scheme)
  double free_step_s = 1e-6;               // simulation.free_step_s (thesis scheme, free flight)
  double contact_step_s = 1e-7;            // simulation.contact_step_s
  double fine_contact_step_s = 1e-8;       // simulation.fine_contact_step_s
  double fine_below_n = 1e-4;              // simulation.fine_below_n
  double corrector_tolerance = 1e-5;       // simulation.corrector_tolerance
  int corrector_max_iterations = 50;       // simulation.corrector_max_iterations
  int max_impacts = 10000;                 // simulation.max_impacts
  double deflection_warning_ratio = 0.1;   // simulation.deflection_warning_ratio
  bool deflection_limit_is_error = false;  // simulation.deflection_limit_is_error
  double output_interval_s = 1e-5;         // output.interval_s
  bool thesis_forces = false;              // compat.thesis_forces
  bool thesis_dcdt = false;                // compat.thesis_dcdt

  /// The initial conditions this configuration describes.
  InitialConditions initial_conditions() const;
  /// Options of a whole pass.
  PassOptions pass_options() const;
  /// Runs the configured pass with the configured scheme.
  PassResult run_pass() const;
  /// Friction as configured (surface.friction, compat.thesis_forces).
  FrictionModel friction_model() const;
  /// End angle in radians.
  double end_angle_rad() const;
  /// The resolved configuration as a JSON object with the TOML's sections and keys.
  nlohmann::json to_json() const;
};

/// Reads the TOML file at `path` (if given), applies the `section.key=value` overrides in order,
/// validates, and returns the resolved configuration. Throws ConfigError.
Config load_config(const std::optional<std::string>& path, const std::vector<std::string>& overrides);

/// Same, from TOML text (for tests and the Python layer).
Config load_config_string(const std::string& toml_text, const std::vector<std::string>& overrides);

/// Every accepted key, "section.key", in documentation order.
const std::vector<std::string>& config_keys();

}  // namespace rotbeam
