#include "rotbeam/beam_model.hpp"

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

}  // namespace rotbeam
