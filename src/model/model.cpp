#include "rotbeam/model.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rotbeam {

double Model::rigid_contact_angle() const { return -std::acos(surface_distance / (hub_radius + length)); }

Model make_model(const PhysicalParameters& p) {
  auto positive = [](double v, const char* what) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw std::invalid_argument(std::string(what) + " must be positive and finite, got " + std::to_string(v));
  };
  positive(p.length_m, "beam length");
  positive(p.diameter_m, "beam diameter");
  positive(p.density_kg_m3, "density");
  positive(p.youngs_modulus_pa, "Young's modulus");
  if (!(p.hub_radius_m >= 0.0) || !std::isfinite(p.hub_radius_m))
    throw std::invalid_argument("hub radius must be >= 0, got " + std::to_string(p.hub_radius_m));
  if (!std::isfinite(p.speed_rpm) || !std::isfinite(p.depth_fraction) || !std::isfinite(p.friction))
    throw std::invalid_argument("speed, depth and friction must be finite");
  Model m;
  m.n = p.modes;
  m.length = p.length_m;
  m.hub_radius = p.hub_radius_m;
  m.omega = p.speed_rpm * M_PI / 30.0;
  const double area = M_PI * p.diameter_m * p.diameter_m / 4.0;
  const double inertia = M_PI * std::pow(p.diameter_m, 4) / 64.0;
  m.mass_per_length = p.density_kg_m3 * area;
  m.bending_stiffness = p.youngs_modulus_pa * inertia;
  m.mass = m.mass_per_length * p.length_m;
  m.surface_distance = p.hub_radius_m + p.length_m - p.depth_fraction * p.length_m;
  m.friction = p.friction;
  m.theta0 = -M_PI / 2.0;
  m.integrals = modal_integrals(p.modes);
  return m;
}

}  // namespace rotbeam
