// A case ready to run (the simulation layer's entry point): the beam model, the surface, the
// contact law, the initial conditions and the pass options built from a configuration, then run
// as a whole pass or to its first impact.
#pragma once

#include "rotbeam/config.hpp"
#include "rotbeam/first_impact.hpp"
#include "rotbeam/pass.hpp"

#include <memory>

namespace rotbeam {

struct Case {
  std::shared_ptr<const BeamModel> beam;
  std::shared_ptr<const Surface> surface;
  ContactLaw law;
  InitialConditions initial;
  PassOptions options;
  /// The mechanical system (references into this case: keep the case alive while it is used).
  System system() const { return {*beam, *surface, law}; }
};

/// Builds the case a (validated) configuration describes. Throws ConfigError naming the key when
/// a value is outside what the model can build.
Case build_case(const Config& config);

/// Runs the case's pass (PassControl: where rows and events go, and the stop token); with
/// simulation.until_steady, to its periodic steady state (run_to_steady_state, steady_state.hpp).
PassResult run_case(const Case& c, const PassControl& control = {});

/// Runs the case to its first impact (the thesis's RK5 with simulation.free_step_s).
FirstImpactResult run_first_impact(const Case& c, const StopToken* stop = nullptr);

}  // namespace rotbeam
