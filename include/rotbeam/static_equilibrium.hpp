// The static equilibrium of the filament in the hub frame under a dead load P at its tip, normal
// to the undeformed filament (along the hub frame's y, the sense of rotation for P > 0), at rest or
// spinning (docs/model.md "Static equilibrium"; `rotbeam static`):
//
//   Ψ(q, 0) = P ∂y_t/∂q,
//
// Ψ(q, 0) holding the bending and (when kept) the centrifugal forces of the beam model. The large
// deflection of a cantilever under a tip load is how brush stiffness was first modelled (Stango,
// Heinrich & Shia 1989); at 0 rpm the elastica's answer is the Bisshopp–Drucker elastica.
#pragma once

#include "rotbeam/beam_model.hpp"
#include "rotbeam/stop_token.hpp"

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

namespace rotbeam {

struct StaticEquilibrium {
  Eigen::VectorXd q;          // modal coordinates [m]
  double tip_x = 0, tip_y = 0;  // tip in the hub frame, x from the hub centre along the undeformed filament [m]
  double residual = 0;        // |Ψ(q, 0) − P ∂y_t/∂q|∞ at the answer [N]
  int iterations = 0;         // Newton iterations, all load steps together
  int load_steps = 0;         // load increments taken (the load is applied in steps where Newton needs them)
  double reach = 0;           // the tip's distance from its clamp in units of L (tip_reach)
  double load_scale = 0;      // the linear theory's load for a tip deflection of L (3EI/L² at rest) [N]
};

/// Solves for the equilibrium under tip load `tip_load_n` [N] by Newton's method on q with a
/// forward-difference Jacobian and a backtracking line search, following the load from the straight
/// filament in increments (at most the linear load scale at first, then at most the load reached;
/// halved where an increment fails). Converged when a Newton step moves q by less than 1e-13 L (or
/// by less than 1e-9 L and no longer shrinking: the round-off floor). Throws std::runtime_error naming the load reached when no
/// equilibrium is found, and when `stop` is requested.
StaticEquilibrium static_equilibrium(const BeamModel& beam, double tip_load_n, const StopToken* stop = nullptr);

/// What a user must be told about the equilibrium under `tip_load_n`: a load that bends the filament
/// more sharply near its clamp than the modes resolve (PL²/EI above n²); the tip farther than L from
/// its clamp (the foreshortening model outside its geometry), or, for a model that is not
/// geometrically exact, |y_t|/L above `deflection_warning_ratio` (simulation.deflection_warning_ratio).
/// One line each. `load_parameter`: PL²/EI, from the filament's EI (bending_stiffness), the value a
/// caller prints beside the warnings; NaN: estimated as 3P/s.load_scale (the modes' linear load for
/// a deflection of L, which spin and the mode count move away from 3EI/L²).
std::vector<std::string> static_warnings(const BeamModel& beam, const StaticEquilibrium& s, double tip_load_n,
                                         double deflection_warning_ratio,
                                         double load_parameter = std::numeric_limits<double>::quiet_NaN());

}  // namespace rotbeam
