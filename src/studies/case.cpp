#include "rotbeam/case.hpp"
#include "rotbeam/steady_state.hpp"

#include <stdexcept>

namespace rotbeam {

Case build_case(const Config& config) {
  Case c;
  try {
    auto beam = std::make_shared<ForeshorteningBeam>(make_beam(config.beam));
    c.surface = make_surface(config.surface, *beam);
    c.beam = std::move(beam);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(e.what());
  }
  c.law = config.contact;
  c.options = config.simulation;
  const int n = config.beam.modes;
  c.initial.rigid_start = config.initial.start == "rigid";
  c.initial.q0 = Eigen::VectorXd::Zero(n);
  c.initial.qd0 = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n && i < static_cast<int>(config.initial.modal_displacement.size()); ++i)
    c.initial.q0[i] = config.initial.modal_displacement[i];
  for (int i = 0; i < n && i < static_cast<int>(config.initial.modal_velocity.size()); ++i)
    c.initial.qd0[i] = config.initial.modal_velocity[i];
  return c;
}

PassResult run_case(const Case& c, const PassControl& control) {
  return run_to_steady_state(c.system(), c.initial, c.options, control);
}

FirstImpactResult run_first_impact(const Case& c, const StopToken* stop) {
  return first_impact(c.system(), c.initial, c.options.end_angle_deg, c.options.free_step_s, stop);
}

}  // namespace rotbeam
