// The checks of a configuration across its keys (config_checks.cpp), after each key's own value has
// been checked against the key table: they read the Config and which keys were given, and refuse
// with the same one-line messages as the table's checks, naming the key that was given.
#pragma once

#include "config_keys.hpp"

namespace rotbeam::config_detail {

/// Checks the keys against each other (each surface and contact key belongs to its shape and law,
/// the initial arrays have beam.modes values, a run ends at an angle or after revolutions, a brush's
/// limits, the keys of a scheme or a search not in use left at their defaults) and completes the
/// values that follow from others: zero initial arrays, a flexible start for a disturbed one, a
/// brush's run to the steady state, the cap on the revolutions of that search.
void check_combinations(Config& c, const GivenValues& given);

/// Checks the start the configuration describes through its beam model and surface: the model can
/// be built (its modes and damping), a flexible start's shape is within reach and clear of the
/// surface, a rigid start begins clear of the surface and reaches it before the end angle. Sets the
/// end angle of a run over revolutions.
void check_start(Config& c, const GivenValues& given);

}  // namespace rotbeam::config_detail
