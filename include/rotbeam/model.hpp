// The immutable model of one case: beam, hub, surface, and the shared modal integrals (SPEC §1–§3).
// Everything here is fixed for a run; the state (t, q, q̇) and the scratch space live elsewhere.
#pragma once

#include "rotbeam/modal_integrals.hpp"

#include <memory>

namespace rotbeam {

/// Physical inputs of a case, SI units (defaults: thesis Table 5-1, 550 rpm, p = 2 %, μ = 0.4, 5 modes).
struct PhysicalParameters {
  double length_m = 0.0635;         // L
  double diameter_m = 5.08e-4;      // D (circular section)
  double density_kg_m3 = 7800.0;    // ρ
  double youngs_modulus_pa = 2.2e11;// E
  int modes = 5;                    // n
  double hub_radius_m = 0.0635;     // r_h
  double speed_rpm = 550.0;         // hub spin
  double depth_fraction = 0.02;     // p: d = r_h + L − p·L
  double friction = 0.4;            // μ
};

struct Model {
  int n = 0;                 // number of assumed modes
  double length = 0;         // L [m]
  double hub_radius = 0;     // r_h [m]
  double omega = 0;          // ω [rad/s]
  double mass_per_length = 0;// ρA [kg/m]
  double bending_stiffness = 0; // EI [N m²]
  double mass = 0;           // m = ρAL [kg]
  double surface_distance = 0;  // d [m], surface at X = d
  double friction = 0;       // μ
  double theta0 = 0;         // beam angle at t = 0 [rad] (−π/2, SPEC §1)
  std::shared_ptr<const ModalIntegrals> integrals;

  /// θ(t) = θ0 + ω t [rad].
  double theta(double t) const { return theta0 + omega * t; }
  /// Time at which the beam angle is θ [s].
  double time_at(double theta_rad) const { return (theta_rad - theta0) / omega; }
  /// Angle at which the undeformed (rigid) tip first reaches the surface: cos θ* = d/(r_h + L), θ* < 0.
  double rigid_contact_angle() const;
};

/// Builds the model (throws std::invalid_argument on non-physical values).
Model make_model(const PhysicalParameters& p);

}  // namespace rotbeam
