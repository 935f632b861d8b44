// The surface seam (docs/model.md §1, §4, §11): a rigid surface turns the tip's motion into the gap C, its
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

/// What a surface's material coordinate measures (Surface::material_coordinate): the wear profile's
/// abscissa (docs/wear.md).
struct SurfaceCoordinate {
  const char* name;         // "position along the plane", "angle around the cylinder", …
  const char* unit;         // "m" or "deg"
  double metres_per_unit;   // surface length per unit of the coordinate [m/unit] (the nominal radius's arc for an angle)
  double period;            // the coordinate's period [unit] (0: not periodic)
};

class Surface {
public:
  virtual ~Surface() = default;
  /// Gap C at the global tip position R = (X, Y) at time t [m]: < 0 clear, 0 touching; its gradient
  /// in space is the unit normal on the surface (C = 0), so the multiplier is the normal force.
  virtual double gap(const Eigen::Vector2d& position, double t) const = 0;
  /// Fills the contact-geometry fields of `tip` (gap … gamma_tangent) from its motion fields.
  virtual void contact_geometry(TipKinematics& tip) const = 0;
  /// The first beam angle θ ≥ θ_from [rad] at which a point at distance `radius` from the hub centre
  /// on the undeformed filament reaches the surface while approaching it, or NaN if it never does.
  virtual double first_contact_angle(double radius, double theta_from) const = 0;
  /// An upper bound [m] on the gap of every point within `excursion` [m] of the point at distance
  /// `radius` from the hub centre on the undeformed filament, over the beam angles [theta_from,
  /// theta_to] [rad] (at the times the hub has them); its sign is what the early end of a pass reads
  /// (simulation.end_when_clear): < 0 means that no such point touches the surface.
  virtual double max_gap_on_arc(double radius, double theta_from, double theta_to, double excursion) const = 0;
  /// The beam angle [rad] (mod 2π) at which the undeformed filament points at the surface's deepest
  /// point: 0° of the per-revolution angles (docs/model.md §11).
  virtual double deepest_angle() const = 0;
  /// The coordinate along the surface of the surface's material point at the global point `position`
  /// [m] at time t [s]: where on the part the tip touches, in coordinate()'s unit (a spinning surface's
  /// material turns under the contact). The wear profile bins the contact's load–distance over it.
  virtual double material_coordinate(const Eigen::Vector2d& position, double t) const = 0;
  virtual SurfaceCoordinate coordinate() const = 0;
  /// The shape and its parameters for the outputs (summary.json `surface`) and the plots.
  virtual nlohmann::json describe() const = 0;
};

enum class SurfaceShape { plane, cylinder, casing };
const char* surface_shape_name(SurfaceShape shape);

/// Inputs of the surface of a case ([surface] section; friction belongs to the contact law).
struct SurfaceParameters {
  SurfaceShape shape = SurfaceShape::plane;  // surface.shape
  double depth_fraction = 0.02;  // p: the undeformed tip reaches p·L beyond the surface at its deepest (docs/model.md §11); plane, cylinder
  double radius_m = 0.1;         // cylinder: R [m]
  double speed_rpm = 0;          // cylinder: its spin about its own axis (counter-clockwise > 0, the hub's sense) [rpm]
  double clearance_m = 0;        // casing: c0, its radius is r_h + L + c0 (negative: interference) [m]
  int lobes = 0;                 // casing: k lobes (0: concentric)
  double lobe_amplitude_m = 0;   // casing: A [m]
  std::string lobe_law = "cosine";  // casing: "cosine" or "benchmark" (casing.hpp)
};

/// The surface of a case for a beam (plane.hpp, cylinder.hpp, casing.hpp), placed from the beam's
/// r_h + L. Throws std::invalid_argument on values outside the shape's range.
std::shared_ptr<const Surface> make_surface(const SurfaceParameters& p, const BeamModel& beam);

}  // namespace rotbeam
