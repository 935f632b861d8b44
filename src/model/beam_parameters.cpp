#include "rotbeam/beam_parameters.hpp"

#include "rotbeam/units.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rotbeam {

const char* beam_theory_name(BeamTheory theory) {
  return theory == BeamTheory::elastica ? "elastica" : "foreshortening";
}

const char* beam_axial_name(BeamAxial axial) {
  return axial == BeamAxial::extensible ? "extensible" : "inextensible";
}

int coordinate_count(const BeamParameters& p) { return p.modes + (p.axial == BeamAxial::extensible ? 1 : 0); }

double mass_per_length(const BeamParameters& p) { return p.density_kg_m3 * M_PI * p.diameter_m * p.diameter_m / 4.0; }

double bending_stiffness(const BeamParameters& p) { return p.youngs_modulus_pa * M_PI * std::pow(p.diameter_m, 4) / 64.0; }

void check_beam_parameters(const BeamParameters& p, double theta0_rad, int max_modes) {
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
  if (!std::isfinite(p.speed_rpm) || !std::isfinite(theta0_rad))
    throw std::invalid_argument("speed and start angle must be finite");
  if (p.modes < 1 || p.modes > max_modes)
    throw std::invalid_argument("modes must be in 1.." + std::to_string(max_modes) + ", got " + std::to_string(p.modes));
}

BeamConstants beam_constants(const BeamParameters& p, double theta0_rad, int max_modes) {
  check_beam_parameters(p, theta0_rad, max_modes);
  BeamConstants c;
  c.n = p.modes;
  c.length = p.length_m;
  c.hub_radius = p.hub_radius_m;
  c.omega = rad_per_s_from_rpm(p.speed_rpm);
  c.theta0 = theta0_rad;
  c.centrifugal = p.centrifugal;
  c.coriolis = p.coriolis;
  c.mass_per_length = mass_per_length(p);
  c.bending_stiffness = bending_stiffness(p);
  c.mass = c.mass_per_length * p.length_m;
  return c;
}

}  // namespace rotbeam
