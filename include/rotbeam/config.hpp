// Case configuration (docs/model.md §9): one TOML file plus `--set section.key=value` overrides.
// Unknown keys, wrong types, non-finite and out-of-range values raise ConfigError with a one-line
// message naming the key and the value. This layer only reads and validates; building the case
// and running it is the simulation layer's (case.hpp). The defaults are those of the structs the
// configuration reads into (each defined once) and reproduce the thesis's base case.
#pragma once

#include "rotbeam/brush_settings.hpp"
#include "rotbeam/contact_law.hpp"
#include "rotbeam/foreshortening_beam.hpp"
#include "rotbeam/pass_options.hpp"
#include "rotbeam/surface.hpp"
#include "rotbeam/wear.hpp"

#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace rotbeam {

/// The most filaments a brush may have (brush.filaments × brush.rows).
inline constexpr int kMaxBrushFilaments = 100000;

class ConfigError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// A user's text (a key, a value, a path, a sweep case's label) as a message shows it: control
/// characters (C0, DEL, C1), bidirectional marks, embeddings, overrides and isolates as \uXXXX and
/// bytes that are not UTF-8 as \xNN, so that a message stays one line and reads as given.
std::string printable(const std::string& s);

/// [initial] as resolved.
struct InitialSettings {
  std::string start = "rigid";             // initial.start ("rigid" | "flexible")
  std::vector<double> modal_velocity;      // initial.modal_velocity [m/s], n values
  std::vector<double> modal_displacement;  // initial.modal_displacement [m], n values
};

struct Config {
  BeamParameters beam;         // [beam], [hub]
  SurfaceParameters surface;   // surface.depth_fraction
  ContactSettings contact;     // surface.friction, [impact], [contact], compat.thesis_forces, compat.restitution_speed
  InitialSettings initial;     // [initial]
  PassOptions simulation;      // [simulation], output.interval_s, compat.thesis_dcdt
  WearSettings wear;           // [wear] (docs/wear.md); wear.profile_bins is simulation's
  std::optional<BrushSettings> brush;  // [brush]: present when the case is a brush (docs/brush.md)

  /// The resolved configuration as a JSON object with the TOML's sections and keys.
  nlohmann::json to_json() const;
};

/// Reads the TOML file at `path` (if given), applies the `section.key=value` overrides in order,
/// validates (values, and that the described start is possible: the initial shape clear of the
/// surface, a rigid start reaching it before the end angle), and returns the configuration.
/// Throws ConfigError.
Config load_config(const std::optional<std::string>& path, const std::vector<std::string>& overrides);

/// Same, with the overrides as (key, TOML value) pairs: the keys are taken whole, never split at
/// a `=` (the Python layer's dicts). A bare word is a string, as with --set.
Config load_config_values(const std::optional<std::string>& path,
                          const std::vector<std::pair<std::string, std::string>>& values);

/// Same as load_config_values, from the TOML text of a file that `name` names in messages as its
/// path would be named (a sweep's cases on another machine, where the path may not exist).
Config load_config_text_values(const std::string& toml_text, const std::string& name,
                               const std::vector<std::pair<std::string, std::string>>& values);

/// Same, from TOML text (for tests and the Python layer).
Config load_config_string(const std::string& toml_text, const std::vector<std::string>& overrides);

/// `config` (changed in code, as a brush changes its nominal filament for each filament) checked
/// as a file is: each key that its to_json writes is checked against the key table as if the file
/// had given that value, then the keys across each other and the start, with the same messages as
/// load_config. Returns it completed as load_config would (its derived values set). Throws ConfigError.
Config revalidate(const Config& config);

/// Every accepted key, "section.key", in documentation order.
const std::vector<std::string>& config_keys();

/// Every key as `rotbeam keys --json` lists it, in documentation order: an array of objects with,
/// in this order, "name", "type", "unit" ("" for none), "default" (as to_json writes it, from the structs'
/// defaults), "unset" (what leaving the key out means where that default is a placeholder, else
/// null), "allowed" (the accepted values in words) and "doc" (one line).
nlohmann::ordered_json describe_config_keys();

/// One line per key whose value lies outside the range brushes, seals and rotating blades use (the
/// key table's plausible range): "KEY = VALUE UNIT is outside the usual [LO, HI] UNIT …". The value is
/// accepted; the command line prints these as warnings.
std::vector<std::string> plausibility_warnings(const Config& config);

/// Throws ConfigError "<flag> KEY: unknown key (did you mean …?)" unless KEY is a configuration key.
void require_known_key(const std::string& key, const std::string& flag);

}  // namespace rotbeam
