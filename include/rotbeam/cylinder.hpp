// A round workpiece (issue "Beyond the flat plane"; docs/model.md §11): a circle of radius R whose axis is
// parallel to the hub's, centred on +X at c = (d + R, 0) so that its nearest point to the hub is at
// distance d = r_h + L − pL, where the undeformed tip reaches p·L into it (the plane's meaning of
// depth). It may spin about its own axis at Ω_s (either sense), which enters only the friction law
// through the surface's own velocity Ω_s k × (P − c): a circle turning about its centre does not move.
// The gap is the signed distance g = R − |P − c|, computed without cancellation as
//   g = (u(2R − u) − Y²) / (R + |P − c|),  u = X − d,
// so that a radius of 1e6 m keeps every digit of the plane's gap u − Y²/(2R) + …; ∇g = (c − P)/|P − c|,
// H = −t tᵀ/|P − c| (gap_field.hpp fills the rest).
#pragma once

#include "rotbeam/gap_field.hpp"
#include "rotbeam/surface.hpp"

namespace rotbeam {

class Cylinder final : public Surface {
public:
  /// Nearest point at distance `distance_m` [m] from the hub centre along +X, radius `radius_m` [m],
  /// spinning at `spin_rad_s` [rad/s] about its axis (counter-clockwise > 0, the hub's sense).
  Cylinder(double distance_m, double radius_m, double spin_rad_s);
  double distance() const { return distance_; }
  double radius() const { return radius_; }

  /// g, ∇g and H at the global point P [m].
  GapField field(const Eigen::Vector2d& position) const;
  double gap(const Eigen::Vector2d& position, double t) const override;
  void contact_geometry(TipKinematics& tip) const override;
  /// The point at distance r meets the circle at 1 − cos θ* = (r − d)(2R + d − r)/(2r(d + R)), θ* < 0
  /// (approaching), then whole turns until ≥ θ_from; NaN when r ≤ d.
  double first_contact_angle(double radius, double theta_from) const override;
  /// The gap of the point at distance r grows with cos θ: its value at the arc's largest cos θ, plus
  /// the excursion (the gap is a signed distance).
  double max_gap_on_arc(double radius, double theta_from, double theta_to, double excursion) const override;
  double deepest_angle() const override { return 0.0; }
  /// The angle around the cylinder's axis [deg] of its material point under P, in (−180°, 180°], 0° at
  /// the point nearest the hub at t = 0, counter-clockwise positive; a spinning cylinder's material
  /// turns by Ω_s t.
  double material_coordinate(const Eigen::Vector2d& position, double t) const override;
  SurfaceCoordinate coordinate() const override;
  nlohmann::json describe() const override;

private:
  double distance_, radius_;
  SurfaceMotion motion_;
};

}  // namespace rotbeam
