// The beam model a configuration names (beam.theory): the one place where a theory is chosen.
#pragma once

#include "rotbeam/beam_model.hpp"
#include "rotbeam/beam_parameters.hpp"

#include <memory>

namespace rotbeam {

/// The largest mode count `theory` accepts (kMaxModes, kMaxElasticaModes).
int max_modes(BeamTheory theory);

/// The beam model of p.theory (foreshortening_beam.hpp, elastica_beam.hpp) with θ0 = theta0_rad.
/// Throws std::invalid_argument on non-physical values.
std::shared_ptr<const BeamModel> make_beam_model(const BeamParameters& p,
                                                 double theta0_rad = kDefaultStartAngleDeg * M_PI / 180.0);

}  // namespace rotbeam
