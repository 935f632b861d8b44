#include "rotbeam/beam_model.hpp"

#include <cmath>

namespace rotbeam {

BeamWorkspace::BeamWorkspace(int size)
    : n(size), mass(size, size), mass_llt(size), psi(size), scratch(size), scratch2(size) {}

void acceleration(const BeamModel& beam, const Eigen::Ref<const Eigen::VectorXd>& q,
                  const Eigen::Ref<const Eigen::VectorXd>& qd, const Eigen::VectorXd* generalized_force,
                  BeamWorkspace& ws, Eigen::Ref<Eigen::VectorXd> qdd) {
  beam.evaluate_dynamics(q, qd, ws);
  if (generalized_force)
    qdd = *generalized_force - ws.psi;
  else
    qdd = -ws.psi;
  ws.mass_llt.solveInPlace(qdd);
}

double tip_reach(const BeamModel& beam, const Eigen::Ref<const Eigen::VectorXd>& q) {
  const Eigen::Vector2d r = beam.tip_position(q);
  const double L = beam.beam_length();
  return std::hypot(r.x() - (beam.tip_radius() - L), r.y()) / L;
}

}  // namespace rotbeam
