// The thesis's flat rigid surface X = d (docs/model.md §1, §4): C = X_t − d, ∇C = ∂X_t/∂q,
// ∂C/∂t = −ωY_t, Ċ = V_X, γ = the X part of the tip's bias acceleration; normal +X, tangent +Y,
// slip V_t = V_Y (the plane is at rest).
#pragma once

#include "rotbeam/surface.hpp"

namespace rotbeam {

class Plane final : public Surface {
public:
  /// The plane X = d at distance d [m] from the hub centre.
  explicit Plane(double distance_m) : distance_(distance_m) {}
  double distance() const { return distance_; }

  double gap(const Eigen::Vector2d& position, double t) const override;
  void contact_geometry(TipKinematics& tip) const override;
  /// θ* = −acos(d/r) + 2πk, the first such angle ≥ θ_from (NaN when d ≥ r: never reached).
  double first_contact_angle(double radius, double theta_from) const override;
  /// r cos θ − d + δ: r − d + δ when [θ_from, θ_to] holds a whole turn 2πk, else at its larger end (the
  /// gap is a signed distance).
  double max_gap_on_arc(double radius, double theta_from, double theta_to, double excursion) const override;
  /// The plane x = d is deepest along +X: θ = 0.
  double deepest_angle() const override { return 0.0; }
  /// Y, the position along the plane [m] (0 at its point nearest the hub).
  double material_coordinate(const Eigen::Vector2d& position, double t) const override;
  SurfaceCoordinate coordinate() const override { return {"position along the plane", "m", 1.0, 0.0}; }
  nlohmann::json describe() const override;

private:
  double distance_;
};

/// The plane that the undeformed tip (at r_h + L) penetrates by p·L at its deepest: d = r_h + L − p·L.
Plane plane_at_depth(const BeamModel& beam, double depth_fraction);

}  // namespace rotbeam
