// The surface seam (SPEC §1, §4, §11): a rigid surface turns the tip's motion into the gap C, its
// gradient ∇C, ∂C/∂t, Ċ, γ, the normal and tangent at the contact point, the surface's own velocity
// there and the tangential slip. Nothing outside a Surface knows its shape: the contact
// algorithms, the steppers, the outputs and the plots see only what it fills in TipKinematics and
// what it says of itself in describe(). The flat plane of the thesis is the first shape (plane.hpp).
#pragma once

#include "rotbeam/beam_model.hpp"
#include "rotbeam/tip_kinematics.hpp"

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace rotbeam {

class Surface {
public:
  virtual ~Surface() = default;
  /// Gap C at the global tip position R = (X, Y) at time t [m]: < 0 clear, 0 touching. A signed
  /// distance: |C(R) − C(R')| ≤ |R − R'| (the excursion test of simulation.end_when_clear relies on it).
  virtual double gap(const Eigen::Vector2d& position, double t) const = 0;
  /// Fills the contact-geometry fields of `tip` (gap … gamma_tangent) from its motion fields.
  virtual void contact_geometry(TipKinematics& tip) const = 0;
  /// The first beam angle θ ≥ θ_from [rad] at which a point at distance `radius` from the hub centre
  /// on the undeformed filament reaches the surface while approaching it, or NaN if it never does.
  virtual double first_contact_angle(double radius, double theta_from) const = 0;
  /// The largest gap [m] of the point at distance `radius` from the hub centre on the undeformed
  /// filament over the beam angles [theta_from, theta_to] [rad] (at the times the hub has them).
  virtual double max_gap_on_arc(double radius, double theta_from, double theta_to) const = 0;
  /// The beam angle [rad] (mod 2π) at which the undeformed filament points at the surface's deepest
  /// point: 0° of the per-revolution angles (SPEC §11).
  virtual double deepest_angle() const = 0;
  /// The shape and its parameters for the outputs (summary.json `surface`) and the plots.
  virtual nlohmann::json describe() const = 0;
};

/// Inputs of the surface of a case ([surface] section; friction belongs to the contact law).
struct SurfaceParameters {
  double depth_fraction = 0.02;  // p: the undeformed tip reaches p·L beyond the surface at its deepest (SPEC §11)
};

/// The surface of a case for a beam: today the plane at d = r_h + L − p·L. Throws
/// std::invalid_argument on values outside the shape's range.
std::shared_ptr<const Surface> make_surface(const SurfaceParameters& p, const BeamModel& beam);

}  // namespace rotbeam
