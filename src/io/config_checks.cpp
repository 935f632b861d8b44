// The checks of a configuration across its keys and of the start it describes (config_checks.hpp).
#include "config_checks.hpp"

#include "rotbeam/beam_factory.hpp"
#include "rotbeam/kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

namespace rotbeam::config_detail {

namespace {

// A computed quantity in a message: six significant digits (a given value is shown as given).
std::string computed_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

bool was_given(const GivenValues& given, const std::string& key) { return given.count(key) != 0; }

// Refuses `key` showing its value as given, or as `value` when it was not given (a default).
[[noreturn]] void refuse_value(const GivenValues& given, const std::string& key, double value, const std::string& why) {
  const auto it = given.find(key);
  if (it != given.end()) refuse(key, it->second, why);
  throw ConfigError(key + " = " + format_number(value) + ": " + why);
}

// The [surface] keys each shape takes (surface.hpp): a key of another shape is an error, not ignored.
void check_surface(const Config& c, const GivenValues& given) {
  const SurfaceParameters& sp = c.surface;
  const std::string shape = surface_shape_name(sp.shape);
  const auto refuse_other = [&](const char* key, const char* belongs) {
    if (was_given(given, key))
      refuse(key, given.at(key), std::string("applies to ") + belongs + "; this case's surface.shape is \"" + shape + "\"");
  };
  const double L = c.beam.length_m;
  switch (sp.shape) {
    case SurfaceShape::plane:
      for (const char* key : {"surface.radius_m", "surface.speed_rpm"}) refuse_other(key, "surface.shape = \"cylinder\"");
      for (const char* key : {"surface.clearance_m", "surface.lobes", "surface.lobe_amplitude_m", "surface.lobe_law"})
        refuse_other(key, "surface.shape = \"casing\"");
      break;
    case SurfaceShape::cylinder:
      for (const char* key : {"surface.clearance_m", "surface.lobes", "surface.lobe_amplitude_m", "surface.lobe_law"})
        refuse_other(key, "surface.shape = \"casing\"");
      if (!was_given(given, "surface.radius_m"))
        throw ConfigError("surface.shape = \"cylinder\" needs surface.radius_m, the workpiece's radius in m");
      // A workpiece no wider than the depth lies wholly within the tip's reach: the filament's body would
      // sweep through it while the tip's circle passes beyond it.
      if (!(2.0 * sp.radius_m > sp.depth_fraction * L))
        refuse("surface.radius_m", given.at("surface.radius_m"),
               "the workpiece is " + format_number(2.0 * sp.radius_m) + " m across, within the tip's reach p·L = " +
                   format_number(sp.depth_fraction * L) + " m: the filament would pass through it (make it wider than the depth)");
      break;
    case SurfaceShape::casing: {
      refuse_other("surface.depth_fraction", "a plane or a cylinder; a casing is placed by surface.clearance_m");
      for (const char* key : {"surface.radius_m", "surface.speed_rpm"}) refuse_other(key, "surface.shape = \"cylinder\"");
      if (sp.lobes == 0)
        for (const char* key : {"surface.lobe_amplitude_m", "surface.lobe_law"})
          if (was_given(given, key))
            refuse(key, given.at(key), "needs surface.lobes >= 1: without lobes the casing is a circle about the hub");
      if (was_given(given, "surface.lobe_law") && sp.lobe_law == "benchmark" && sp.lobes != 2)
        refuse("surface.lobe_law", given.at("surface.lobe_law"),
               "the benchmark's law has two lobes: it needs surface.lobes = 2, got " + std::to_string(sp.lobes));
      // The casing must stay outside the hub: its smallest radius r_h + L + c0 − A (2A for the benchmark)
      // above r_h.
      const double deepest = sp.clearance_m - (sp.lobe_law == "benchmark" ? 2.0 : 1.0) * (sp.lobes ? sp.lobe_amplitude_m : 0.0);
      if (!(deepest > -L)) {
        const std::string key =
            was_given(given, "surface.lobe_amplitude_m") && sp.lobes ? "surface.lobe_amplitude_m" : "surface.clearance_m";
        const std::string what = "the casing's smallest radius r_h + L − " + format_number(-deepest) +
                                 " m reaches the hub (beam.length_m = " + format_number(L) + ")";
        if (was_given(given, key)) refuse(key, given.at(key), what);
        throw ConfigError(key + ": " + what);
      }
      break;
    }
  }
}

// The compliant law's keys (docs/contact.md): refused under the rigid law, which has no use for
// them; under hertz the adaptive scheme, the physical forces and a positive restitution are needed.
void check_contact(const Config& c, const GivenValues& given) {
  if (c.contact.model == ContactModel::rigid) {
    for (const char* key : {"contact.tip_radius_m", "contact.friction_regularization_m_s", "contact.stiffness_factor",
                            "surface.youngs_modulus_pa", "surface.poisson", "beam.poisson"})
      if (was_given(given, key)) refuse(key, given.at(key), "applies to contact.model = \"hertz\"; this case's is \"rigid\"");
    return;
  }
  const std::string& model = given.at("contact.model");
  if (c.simulation.scheme == Scheme::thesis)
    refuse("contact.model", model, "needs simulation.scheme = \"adaptive\" (the thesis's scheme has no compliant contact)");
  if (c.contact.friction.thesis_forces)
    refuse("contact.model", model, "uses the physical forces: it cannot be combined with compat.thesis_forces = true");
  const ImpactLaw& impact = c.contact.impact;
  const std::string why = "must be at least " + format_number(kMinCompliantRestitution) +
                          " with contact.model = \"hertz\" (Hunt–Crossley damping for e → 0 grows without bound "
                          "and below 0.05 its rebound is lost to rounding)";
  if (impact.model == RestitutionModel::constant && !(impact.constant >= kMinCompliantRestitution))
    refuse("impact.restitution", was_given(given, "impact.restitution") ? given.at("impact.restitution") : model, why);
  if (!(impact.cap >= kMinCompliantRestitution)) refuse("impact.restitution_cap", given.at("impact.restitution_cap"), why);
}

// The initial arrays: beam.modes values each when given, zeros when not; a non-zero one makes the
// start flexible.
void check_initial(Config& c, const GivenValues& given) {
  const int n = c.beam.modes;
  InitialSettings& ini = c.initial;
  const auto check_length = [&](std::vector<double>& v, const char* key) {
    if (!was_given(given, key)) {
      v.assign(n, 0.0);
      return;
    }
    if (static_cast<int>(v.size()) != n)
      refuse(key, given.at(key), "must have beam.modes = " + std::to_string(n) + " values, got " + std::to_string(v.size()));
  };
  check_length(ini.modal_velocity, "initial.modal_velocity");
  check_length(ini.modal_displacement, "initial.modal_displacement");
  const auto nonzero = [](const std::vector<double>& v) { return std::any_of(v.begin(), v.end(), [](double x) { return x != 0.0; }); };
  if (nonzero(ini.modal_velocity) || nonzero(ini.modal_displacement)) {
    if (was_given(given, "initial.start") && ini.start == "rigid")
      throw ConfigError("initial.start = \"rigid\" contradicts a non-zero initial.modal_velocity or "
                        "initial.modal_displacement (a rigid start has q = q̇ = 0)");
    ini.start = "flexible";
  }
}

// How the run ends (at an angle, after revolutions, at the steady state), a brush's run, and the
// keys of a search or a scheme not in use.
void check_run(Config& c, const GivenValues& given) {
  PassOptions& sim = c.simulation;
  const bool revolutions_given = was_given(given, "simulation.revolutions");
  const bool end_angle_given = was_given(given, "simulation.end_angle_deg");
  if (revolutions_given && end_angle_given)
    refuse("simulation.end_angle_deg", given.at("simulation.end_angle_deg"),
           "cannot be given with simulation.revolutions = " + std::to_string(sim.revolutions) +
               " (a run ends after whole revolutions or at an angle, not both)");
  if (revolutions_given && sim.end_when_clear)
    refuse("simulation.end_when_clear", given.at("simulation.end_when_clear"),
           "ends one pass early; with simulation.revolutions = " + std::to_string(sim.revolutions) +
               " every revolution's free flight is the point");
  // A run to the steady state ends there or after simulation.revolutions: an end angle was ignored
  // without a word, and end_when_clear ended the section map's one-revolution runs early, so that
  // the Floquet multipliers were silently not computed.
  if (sim.until_steady && end_angle_given)
    refuse("simulation.end_angle_deg", given.at("simulation.end_angle_deg"),
           "cannot be given with simulation.until_steady = true (the run ends at the steady state or after "
           "simulation.revolutions, not at an angle)");
  if (sim.until_steady && sim.end_when_clear)
    refuse("simulation.end_when_clear", given.at("simulation.end_when_clear"),
           "ends one pass early; with simulation.until_steady = true every revolution's free flight is the point");
  if (c.brush && c.surface.shape == SurfaceShape::casing)
    refuse("surface.shape", given.at("surface.shape"),
           "a brush works a plane or a cylinder in this version (its filaments' scatter moves their depth, which a "
           "casing does not have)");
  if (c.brush) {
    // Every filament of a brush runs to its periodic steady state.
    if (was_given(given, "simulation.until_steady") && !sim.until_steady)
      refuse("simulation.until_steady", given.at("simulation.until_steady"),
             "a brush's filaments run to their periodic steady state: leave it out or set it true");
    sim.until_steady = true;
    const long long total = static_cast<long long>(c.brush->filaments) * c.brush->rows;
    if (total > kMaxBrushFilaments)
      refuse("brush.rows", given.at(was_given(given, "brush.rows") ? "brush.rows" : "brush.filaments"),
             "brush.filaments × brush.rows = " + std::to_string(total) + " filaments, more than " +
                 std::to_string(kMaxBrushFilaments));
  }
  // After the brush's until_steady is set: a brush's filaments search with either method.
  if (sim.steady_method == SteadyMethod::shooting && !sim.until_steady)
    refuse("simulation.steady_method", given.at("simulation.steady_method"),
           "shooting searches for the steady state: it needs simulation.until_steady = true");
  // The steady-state search's own keys, given a value other than their default, would change
  // nothing without it (as shooting, above): refused. Their defaults, as in a file that lists every
  // key, are accepted.
  const PassOptions defaults;
  const auto given_changed = [&](const char* key, bool changed) { return was_given(given, key) && changed; };
  if (!sim.until_steady && given_changed("simulation.multipliers", sim.multipliers != defaults.multipliers))
    refuse("simulation.multipliers", given.at("simulation.multipliers"),
           "the Floquet multipliers are those of the steady orbit: it needs simulation.until_steady = true");
  if (!sim.until_steady && given_changed("simulation.steady_tolerance", sim.steady_tolerance != defaults.steady_tolerance))
    refuse("simulation.steady_tolerance", given.at("simulation.steady_tolerance"),
           "the steady state's tolerance: it needs simulation.until_steady = true");
  // The adaptive scheme's tolerances, step cap and integrating factor change nothing under the
  // thesis's fixed steps (they were accepted and ignored): refused there unless at their defaults.
  if (sim.scheme == Scheme::thesis) {
    const std::string why = "the adaptive scheme's; simulation.scheme = \"thesis\" takes fixed steps "
                            "(simulation.free_step_s, simulation.contact_step_s)";
    const std::pair<const char*, bool> adaptive_keys[] = {
        {"simulation.rtol", sim.rtol != defaults.rtol},
        {"simulation.atol", sim.atol != defaults.atol},
        {"simulation.max_step_s", sim.max_step_s != defaults.max_step_s},
        {"simulation.integrating_factor", sim.integrating_factor != defaults.integrating_factor}};
    for (const auto& [key, changed] : adaptive_keys)
      if (given_changed(key, changed)) refuse(key, given.at(key), why);
  }
  if (sim.until_steady && !revolutions_given) sim.revolutions = kDefaultSteadyRevolutionCap;
  if (c.beam.theory == BeamTheory::elastica && sim.deflection_limit_is_error)
    refuse("simulation.deflection_limit_is_error", given.at("simulation.deflection_limit_is_error"),
           "the deflection limit is the quadratic foreshortening model's; the elastica (beam.theory = \"elastica\") "
           "is exact at any deflection");
}

}  // namespace

void check_combinations(Config& c, const GivenValues& given) {
  const int n = c.beam.modes;
  if (was_given(given, "beam.modes") && n > max_modes(c.beam.theory))
    refuse("beam.modes", given.at("beam.modes"), find_key("beam.modes")->check.out_of_range);
  const std::vector<double>& damping = c.beam.damping_ratio;
  if (was_given(given, "beam.damping_ratio") && damping.size() != 1 && static_cast<int>(damping.size()) != n)
    refuse("beam.damping_ratio", given.at("beam.damping_ratio"),
           "must be one number or beam.modes = " + std::to_string(n) + " values, got " + std::to_string(damping.size()));
  check_initial(c, given);
  if (!(c.beam.diameter_m < c.beam.length_m))
    refuse_value(given, "beam.diameter_m", c.beam.diameter_m,
                 "must be below beam.length_m = " + format_number(c.beam.length_m) + " (a filament, not a disc)");
  check_surface(c, given);
  check_contact(c, given);
  check_run(c, given);
}

void check_start(Config& c, const GivenValues& given) {
  std::shared_ptr<const BeamModel> beam_model;
  try {
    beam_model = make_beam_model(c.beam);
  } catch (const std::invalid_argument& e) {
    if (was_given(given, "beam.damping_ratio")) refuse("beam.damping_ratio", given.at("beam.damping_ratio"), e.what());
    throw ConfigError(e.what());
  }
  const BeamModel& beam = *beam_model;
  const std::shared_ptr<const Surface> surface = make_surface(c.surface, beam);
  PassOptions& sim = c.simulation;
  if (sim.revolutions > 0) sim.end_angle_deg = beam.theta(0.0) * 180.0 / M_PI + 360.0 * sim.revolutions;
  const int n = c.beam.modes;
  // The filament's rest state (its stretch when extensible), with the bending modes of initial.* below.
  Eigen::VectorXd rest = Eigen::VectorXd::Zero(beam.modes());
  beam.rest_state(rest);
  // The key that places the surface: the depth (plane, cylinder) or the casing's clearance.
  const bool casing = c.surface.shape == SurfaceShape::casing;
  const std::string place_key = casing ? "surface.clearance_m" : "surface.depth_fraction";
  const double place_value = casing ? c.surface.clearance_m : c.surface.depth_fraction;
  if (c.initial.start == "flexible") {
    // A flexible start must begin clear of the surface ...
    Eigen::VectorXd q0 = rest;
    q0.head(n) = Eigen::Map<const Eigen::VectorXd>(c.initial.modal_displacement.data(), n);
    // ... and inside the geometry the model can represent (docs/model.md, validity).
    const double reach = tip_reach(beam, q0);
    const bool displaced = was_given(given, "initial.modal_displacement");
    if (!(reach <= kReachLimit)) {
      const std::string what = "the initial shape puts the tip " + computed_number(reach) +
                               " L from its clamp, farther than a filament of length L can reach";
      if (displaced) refuse("initial.modal_displacement", given.at("initial.modal_displacement"), what);
      throw ConfigError(what);
    }
    const double c0 = gap(beam, *surface, 0.0, q0);
    if (c0 >= 0.0) {
      const std::string what = "the initial shape already reaches the surface (gap " + computed_number(c0) + " m >= 0)";
      if (displaced) refuse("initial.modal_displacement", given.at("initial.modal_displacement"), what);
      // The straight filament: the surface's place is what puts it there.
      refuse_value(given, place_key, place_value, what);
    }
    return;
  }
  // A rigid start must begin clear of the surface and reach it before the end angle.
  const double c0 = gap(beam, *surface, 0.0, rest);
  if (c0 >= 0.0)
    refuse_value(given, place_key, place_value,
                 "the undeformed tip starts inside the surface (gap " + computed_number(c0) +
                     " m >= 0 at the start angle): a rigid start needs it clear (or start flexible, with an "
                     "initial.modal_displacement that bends the tip clear)");
  const double theta_star = surface->first_contact_angle(beam.tip_radius(), beam.theta(0.0)) * 180.0 / M_PI;
  if (std::isnan(theta_star))
    refuse_value(given, place_key, place_value,
                 casing ? "the undeformed tip never reaches the casing: its clearance stays positive all round"
                        : "the undeformed tip never reaches the surface: the depth is below what the tip's "
                          "position resolves in double precision");
  if (!(theta_star < sim.end_angle_deg)) {
    const std::string what = "the rigid tip reaches the surface only at " + computed_number(theta_star) +
                             " deg, after the end angle " + format_number(sim.end_angle_deg) + " deg";
    if (was_given(given, "simulation.end_angle_deg")) refuse("simulation.end_angle_deg", given.at("simulation.end_angle_deg"), what);
    refuse_value(given, place_key, place_value, what);
  }
}

}  // namespace rotbeam::config_detail
