#include "rotbeam/plane.hpp"

#include <algorithm>
#include <cmath>

namespace rotbeam {

double Plane::gap(const Eigen::Vector2d& position, double) const { return position.x() - distance_; }

void Plane::contact_geometry(TipKinematics& k) const {
  k.gap = k.X - distance_;
  k.grad_gap = k.grad_x;
  k.gap_time_partial = k.frame_vx;
  k.gap_rate = k.VX;
  k.gamma = k.bias_ax;
  k.normal_x = 1.0, k.normal_y = 0.0;
  k.tangent_x = 0.0, k.tangent_y = 1.0;
  k.surface_vx = 0.0, k.surface_vy = 0.0;
  k.slip_speed = k.VY;
  k.grad_tangent = k.grad_y;
  k.gamma_tangent = k.bias_ay;
}

double Plane::first_contact_angle(double radius, double theta_from) const {
  if (!(distance_ < radius)) return NAN;
  // r cos θ = d while approaching (r sin θ < 0): θ* = −acos(d/r), then whole turns until ≥ θ_from.
  const double theta_star = -std::acos(distance_ / radius);
  const double turns = std::ceil((theta_from - theta_star) / (2.0 * M_PI));
  return turns > 0.0 ? theta_star + 2.0 * M_PI * turns : theta_star;
}

double Plane::max_gap_on_arc(double radius, double theta_from, double theta_to, double excursion) const {
  if (std::floor(theta_to / (2.0 * M_PI)) * 2.0 * M_PI >= theta_from) return radius - distance_ + excursion;
  return radius * std::max(std::cos(theta_from), std::cos(theta_to)) - distance_ + excursion;
}

double Plane::material_coordinate(const Eigen::Vector2d& position, double) const { return position.y(); }

nlohmann::json Plane::describe() const { return {{"shape", "plane"}, {"distance_m", distance_}}; }

Plane plane_at_depth(const BeamModel& beam, double depth_fraction) {
  return Plane(beam.tip_radius() - depth_fraction * beam.beam_length());
}

}  // namespace rotbeam
