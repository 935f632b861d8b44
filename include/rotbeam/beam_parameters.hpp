// The filament on its hub as a configuration describes it (docs/model.md §1, §9, §11): its material and
// section, the hub, the number of assumed modes, the beam theory and the rotation terms kept.
// Every beam model is built from these (beam_factory.hpp).
#pragma once

#include <string>
#include <vector>

namespace rotbeam {

/// beam.theory: the thesis's quadratic foreshortening (docs/model.md §2–§3) or the geometrically exact
/// planar elastica (docs/model.md §11).
enum class BeamTheory { foreshortening, elastica };

/// "foreshortening" / "elastica".
const char* beam_theory_name(BeamTheory theory);

/// beam.axial: the thesis's inextensible filament, or one with the wire's axial compliance EA (one
/// more coordinate, the tip's stretch: docs/model.md §12).
enum class BeamAxial { inextensible, extensible };

/// "inextensible" / "extensible".
const char* beam_axial_name(BeamAxial axial);

/// Inputs of the filament on its hub, SI units (defaults: thesis Table 5-1, 550 rpm, 5 modes).
struct BeamParameters {
  double length_m = 0.0635;          // L
  double diameter_m = 5.08e-4;       // D (circular section)
  double density_kg_m3 = 7800.0;     // ρ
  double youngs_modulus_pa = 2.2e11; // E
  int modes = 5;                     // n
  double hub_radius_m = 0.0635;      // r_h
  double speed_rpm = 550.0;          // hub spin
  // Modal damping ratios ζ_i of the linearised modes at the hub speed (docs/model.md §11): empty for none,
  // one value for every mode, or n values (mode order: ascending frequency).
  std::vector<double> damping_ratio;
  BeamTheory theory = BeamTheory::foreshortening;  // beam.theory
  BeamAxial axial = BeamAxial::inextensible;       // beam.axial
  // The rotation terms of the filament's kinetic energy T = T2 + T1 + T0 (docs/model.md "Switches
  // for the rotation terms"): model.centrifugal keeps T0 = ½ω²∫(x² + y²)dm (centrifugal stiffening
  // and spin softening), model.coriolis keeps T1 = ω∫(xẏ − yẋ)dm (the gyroscopic coupling). The
  // hub's rotation of the frame, and so the contact's kinematics, is kept either way.
  bool centrifugal = true;
  bool coriolis = true;
};

/// The generalised coordinates of the filament p describes: its modes, and the stretch when
/// extensible (the columns q1…, qd1… of the outputs).
int coordinate_count(const BeamParameters& p);

/// ρA [kg/m] and EI [N m²] of the circular section.
double mass_per_length(const BeamParameters& p);
double bending_stiffness(const BeamParameters& p);

/// Throws std::invalid_argument unless L, D, ρ and E are positive and finite, r_h ≥ 0, the speed
/// and θ0 [rad] finite, and the modes in 1..max_modes (a beam model's own limit).
void check_beam_parameters(const BeamParameters& p, double theta0_rad, int max_modes);

/// What every beam model keeps of its parameters, in SI units.
struct BeamConstants {
  int n = 0;                     // number of assumed modes
  double length = 0;             // L [m]
  double hub_radius = 0;         // r_h [m]
  double omega = 0;              // ω [rad/s]
  double theta0 = 0;             // beam angle at t = 0 [rad]
  double mass_per_length = 0;    // ρA [kg/m]
  double bending_stiffness = 0;  // EI [N m²]
  double mass = 0;               // m = ρAL [kg]
  // The rotation terms kept (BeamParameters): without model.centrifugal the ω² terms are dropped,
  // without model.coriolis the terms linear in ω.
  bool centrifugal = true, coriolis = true;
};

/// The constants of `p` at θ0 = theta0_rad, checked (check_beam_parameters with max_modes).
BeamConstants beam_constants(const BeamParameters& p, double theta0_rad, int max_modes);

}  // namespace rotbeam
