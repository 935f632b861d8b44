#include "rotbeam/cylinder.hpp"

#include <algorithm>
#include <cmath>

namespace rotbeam {

Cylinder::Cylinder(double distance_m, double radius_m, double spin_rad_s)
    : distance_(distance_m), radius_(radius_m), motion_{spin_rad_s, Eigen::Vector2d(distance_m + radius_m, 0.0)} {}

GapField Cylinder::field(const Eigen::Vector2d& p) const {
  const double u = p.x() - distance_, y = p.y();
  const double ax = radius_ - u;  // c_x − X, exact where u is
  const double dist = std::hypot(ax, y);
  GapField f;
  f.value = (u * (2.0 * radius_ - u) - y * y) / (radius_ + dist);
  f.gradient = Eigen::Vector2d(ax / dist, -y / dist);
  const Eigen::Vector2d t(-f.gradient.y(), f.gradient.x());
  f.hessian = -(t * t.transpose()) / dist;
  return f;
}

double Cylinder::material_coordinate(const Eigen::Vector2d& p, double t) const {
  // The angle of P − c measured from −X (the direction of the hub), less the material's turn.
  const double psi = std::atan2(-p.y(), motion_.centre.x() - p.x()) - motion_.spin * t;
  return std::remainder(psi, 2.0 * M_PI) * 180.0 / M_PI;
}

SurfaceCoordinate Cylinder::coordinate() const {
  return {"angle around the cylinder", "deg", radius_ * M_PI / 180.0, 360.0};
}

double Cylinder::gap(const Eigen::Vector2d& position, double) const { return field(position).value; }

void Cylinder::contact_geometry(TipKinematics& k) const { fill_contact_geometry(field({k.X, k.Y}), motion_, k); }

double Cylinder::first_contact_angle(double r, double theta_from) const {
  if (!(distance_ < r)) return NAN;
  const double d = distance_, big_r = radius_;
  const double one_minus_cos = (r - d) * (2.0 * big_r + d - r) / (2.0 * r * (d + big_r));
  if (!(one_minus_cos <= 2.0)) return NAN;  // r beyond the far side: the point never leaves the disc
  const double theta_star = -2.0 * std::asin(std::sqrt(0.5 * one_minus_cos));
  const double turns = std::ceil((theta_from - theta_star) / (2.0 * M_PI));
  return turns > 0.0 ? theta_star + 2.0 * M_PI * turns : theta_star;
}

double Cylinder::max_gap_on_arc(double r, double theta_from, double theta_to, double excursion) const {
  const double best = std::floor(theta_to / (2.0 * M_PI)) * 2.0 * M_PI >= theta_from
                          ? 0.0
                          : (std::cos(theta_from) > std::cos(theta_to) ? theta_from : theta_to);
  return gap(Eigen::Vector2d(r * std::cos(best), r * std::sin(best)), 0.0) + excursion;
}

nlohmann::json Cylinder::describe() const {
  return {{"shape", "cylinder"},
          {"distance_m", distance_},
          {"radius_m", radius_},
          {"centre_x_m", distance_ + radius_},
          {"speed_rpm", motion_.spin * 30.0 / M_PI}};
}

}  // namespace rotbeam
