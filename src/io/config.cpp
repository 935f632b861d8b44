#include "rotbeam/config.hpp"

#include "rotbeam/beam_factory.hpp"
#include "rotbeam/kinematics.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <cerrno>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <system_error>

namespace rotbeam {

namespace {

// The shortest text that reads back as v (1e-11, not 9.9999999999999994e-12).
std::string format_number(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

// A computed quantity in a message: six significant digits (a given value is shown as given).
std::string computed_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// A short, single-line rendering of a TOML node for error messages, with numbers in their shortest
// round-trip form (what the user typed: -0.0635, not -0.063500000000000001).
std::string render(const toml::node& node) {
  if (node.is_string()) {
    const std::string given = *node.value<std::string>();
    std::string quoted;
    for (char c : given) {
      if (c == '"' || c == '\\') quoted += '\\';
      quoted += c;
    }
    std::string s = printable(quoted);
    if (s.size() > 80) s = s.substr(0, 60) + "… (" + std::to_string(s.size()) + " characters)";
    return '"' + s + '"';
  }
  if (node.is_integer()) return std::to_string(*node.value<int64_t>());
  if (node.is_floating_point()) {
    const double v = *node.value<double>();
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[64];
    const auto res = std::to_chars(buf, buf + sizeof buf, v);
    std::string s(buf, res.ptr);
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // a float written 5.0 is not the integer 5
    return s;
  }
  if (node.is_boolean()) return *node.value<bool>() ? "true" : "false";
  if (const toml::array* arr = node.as_array()) {
    // A long array is shown by its first values and its length, so a message stays one readable line.
    constexpr std::size_t kShown = 8;
    std::string out = "[";
    for (std::size_t i = 0; i < arr->size() && i < kShown; ++i) out += (i ? ", " : "") + render((*arr)[i]);
    if (arr->size() > kShown) out += ", … (" + std::to_string(arr->size()) + " values)";
    return out + "]";
  }
  if (node.is_table()) return "{…}";
  std::ostringstream s;
  node.visit([&](auto&& v) { s << v; });
  return s.str();
}

[[noreturn]] void fail(const std::string& key, const toml::node& node, const std::string& why) {
  throw ConfigError(printable(key) + " = " + render(node) + ": " + why);
}

double as_number(const std::string& key, const toml::node& node) {
  if (!node.is_number()) fail(key, node, "must be a number");
  const double v = *node.value<double>();
  if (!std::isfinite(v)) fail(key, node, "must be finite");
  return v;
}

double number_in(const std::string& key, const toml::node& node, double lo, double hi, bool lo_open, bool hi_open) {
  const double v = as_number(key, node);
  const bool ok_lo = lo_open ? v > lo : v >= lo;
  const bool ok_hi = hi_open ? v < hi : v <= hi;
  if (!ok_lo || !ok_hi) {
    std::string range = std::string(lo_open ? "(" : "[") + format_number(lo) + ", " +
                        (std::isinf(hi) ? std::string("inf") : format_number(hi)) + (hi_open ? ")" : "]");
    fail(key, node, "must be in " + range);
  }
  return v;
}

std::string one_of(const std::string& key, const toml::node& node, std::initializer_list<const char*> choices) {
  std::string list;
  for (const char* c : choices) list += (list.empty() ? "\"" : ", \"") + std::string(c) + "\"";
  if (!node.is_string()) fail(key, node, "must be one of " + list);
  const std::string v = *node.value<std::string>();
  for (const char* c : choices)
    if (v == c) return v;
  fail(key, node, "must be one of " + list);
}

int integer_in(const std::string& key, const toml::node& node, int64_t lo, int64_t hi) {
  if (!node.is_integer()) fail(key, node, "must be an integer");
  const int64_t v = *node.value<int64_t>();
  if (v < lo || v > hi) fail(key, node, "must be in " + std::to_string(lo) + ".." + std::to_string(hi));
  return static_cast<int>(v);
}

bool boolean(const std::string& key, const toml::node& node) {
  if (!node.is_boolean()) fail(key, node, "must be true or false");
  return *node.value<bool>();
}

std::vector<double> number_array(const std::string& key, const toml::node& node, double bound) {
  const toml::array* arr = node.as_array();
  if (!arr) fail(key, node, "must be an array of numbers");
  std::vector<double> out;
  for (const toml::node& el : *arr) {
    if (!el.is_number()) fail(key, node, "must be an array of numbers");
    const double v = *el.value<double>();
    if (!std::isfinite(v)) fail(key, node, "must hold finite numbers");
    if (std::abs(v) > bound) fail(key, node, "must hold numbers in [-" + format_number(bound) + ", " + format_number(bound) + "]");
    out.push_back(v);
  }
  return out;
}

// beam.modes's range: the thesis model's, and the elastica's (beam.theory) beside it.
std::string modes_range() {
  return "must be in 1.." + std::to_string(kMaxModes) + " (1.." + std::to_string(kMaxElasticaModes) +
         " with beam.theory = \"elastica\")";
}

struct Parsed {
  Config config;
  bool start_given = false;
  const toml::node* velocity_node = nullptr;
  const toml::node* displacement_node = nullptr;
  const toml::node* modes_node = nullptr;
  const toml::node* depth_node = nullptr;
  const toml::node* end_angle_node = nullptr;
  const toml::node* damping_node = nullptr;
  const toml::node* revolutions_node = nullptr;
  const toml::node* method_node = nullptr;
  const toml::node* end_when_clear_node = nullptr;
  const toml::node* until_steady_node = nullptr;
  const toml::node* steady_tolerance_node = nullptr;
  const toml::node* multipliers_node = nullptr;
  // The adaptive scheme's own keys (refused with the thesis's fixed steps unless at their defaults).
  const toml::node* rtol_node = nullptr;
  const toml::node* atol_node = nullptr;
  const toml::node* max_step_node = nullptr;
  const toml::node* factor_node = nullptr;
  const toml::node* filaments_node = nullptr;
  const toml::node* rows_node = nullptr;
};

// brush.KEY: the first brush key met makes the case a brush (docs/brush.md).
BrushSettings& brush_of(Parsed& p) {
  if (!p.config.brush) p.config.brush.emplace();
  return *p.config.brush;
}

using Setter = std::function<void(Parsed&, const std::string&, const toml::node&)>;

const std::vector<std::pair<std::string, Setter>>& schema() {
  static const std::vector<std::pair<std::string, Setter>> keys = {
      // Physical ranges wide enough for any filament or blade, narrow enough that the arithmetic stays
      // finite (a diameter of 5e-324 m has a zero area; a radius of 1e300 m overflows the energies).
      {"beam.length_m", [](Parsed& p, auto& k, auto& n) { p.config.beam.length_m = number_in(k, n, 0.0, 100.0, true, false); }},
      {"beam.diameter_m", [](Parsed& p, auto& k, auto& n) { p.config.beam.diameter_m = number_in(k, n, 1e-7, 1.0, false, false); }},
      {"beam.density_kg_m3", [](Parsed& p, auto& k, auto& n) { p.config.beam.density_kg_m3 = number_in(k, n, 1e-3, 1e6, false, false); }},
      {"beam.youngs_modulus_pa", [](Parsed& p, auto& k, auto& n) { p.config.beam.youngs_modulus_pa = number_in(k, n, 1e3, 1e15, false, false); }},
      {"beam.modes",
       [](Parsed& p, auto& k, auto& n) {
         // Up to the elastica's limit here; the foreshortening model's lower one is checked with beam.theory.
         if (!n.is_integer()) fail(k, n, "must be an integer");
         const int64_t v = *n.template value<int64_t>();
         if (v < 1 || v > kMaxElasticaModes) fail(k, n, modes_range());
         p.config.beam.modes = static_cast<int>(v);
         p.modes_node = &n;
       }},
      {"beam.theory",
       [](Parsed& p, auto& k, auto& n) {
         p.config.beam.theory = one_of(k, n, {"foreshortening", "elastica"}) == "elastica" ? BeamTheory::elastica
                                                                                          : BeamTheory::foreshortening;
       }},
      {"beam.damping_ratio",
       [](Parsed& p, auto& k, auto& n) {
         // One ratio for every mode, or one per mode; up to 10 (far past critical damping, 1).
         if (n.is_number()) {
           p.config.beam.damping_ratio = {number_in(k, n, 0.0, 10.0, false, false)};
         } else if (n.is_array()) {
           p.config.beam.damping_ratio = number_array(k, n, 10.0);
           for (double z : p.config.beam.damping_ratio)
             if (z < 0.0) fail(k, n, "must hold numbers in [0, 10]");
         } else {
           fail(k, n, "must be a number or an array of beam.modes numbers in [0, 10]");
         }
         p.damping_node = &n;
       }},
      {"model.centrifugal", [](Parsed& p, auto& k, auto& n) { p.config.beam.centrifugal = boolean(k, n); }},
      {"model.coriolis", [](Parsed& p, auto& k, auto& n) { p.config.beam.coriolis = boolean(k, n); }},
      {"hub.radius_m", [](Parsed& p, auto& k, auto& n) { p.config.beam.hub_radius_m = number_in(k, n, 0.0, 100.0, false, false); }},
      // Below 1e-3 rpm (a turn in 17 hours) a pass lasts days of simulated time: the steps and
      // times leave the ranges the integration is built for (1e-9 rpm ended in step underflow).
      {"hub.speed_rpm", [](Parsed& p, auto& k, auto& n) { p.config.beam.speed_rpm = number_in(k, n, 1e-3, 1e6, false, false); }},
      {"surface.depth_fraction",
       [](Parsed& p, auto& k, auto& n) {
         p.config.surface.depth_fraction = number_in(k, n, 0.0, 1.0, true, true);
         p.depth_node = &n;
       }},
      {"surface.friction", [](Parsed& p, auto& k, auto& n) { p.config.contact.friction.mu = number_in(k, n, 0.0, 1e3, false, false); }},
      {"surface.shape",
       [](Parsed& p, auto& k, auto& n) {
         const std::string v = one_of(k, n, {"plane", "cylinder", "casing"});
         p.config.surface.shape = v == "cylinder" ? SurfaceShape::cylinder
                                  : v == "casing" ? SurfaceShape::casing
                                                  : SurfaceShape::plane;
       }},
      // A cylinder of 1e9 m is a plane to every digit the gap keeps; the rub and workpiece speeds
      // share the hub's range.
      {"surface.radius_m", [](Parsed& p, auto& k, auto& n) { p.config.surface.radius_m = number_in(k, n, 0.0, 1e9, true, false); }},
      {"surface.speed_rpm", [](Parsed& p, auto& k, auto& n) { p.config.surface.speed_rpm = number_in(k, n, -1e6, 1e6, false, false); }},
      {"surface.clearance_m", [](Parsed& p, auto& k, auto& n) { p.config.surface.clearance_m = number_in(k, n, -100.0, 100.0, false, false); }},
      {"surface.lobes", [](Parsed& p, auto& k, auto& n) { p.config.surface.lobes = integer_in(k, n, 0, 1000); }},
      {"surface.lobe_amplitude_m",
       [](Parsed& p, auto& k, auto& n) { p.config.surface.lobe_amplitude_m = number_in(k, n, 0.0, 100.0, false, false); }},
      {"surface.lobe_law",
       [](Parsed& p, auto& k, auto& n) { p.config.surface.lobe_law = one_of(k, n, {"cosine", "benchmark"}); }},
      {"impact.restitution",
       [](Parsed& p, auto& k, auto& n) {
         if (n.is_string()) {
           // One word among numbers: "must be one of \"yigit\"" left the numbers out.
           if (*n.template value<std::string>() != "yigit") fail(k, n, "must be \"yigit\" or a number in [0, 1]");
           p.config.contact.impact.model = RestitutionModel::yigit;
         } else if (n.is_number()) {
           p.config.contact.impact.model = RestitutionModel::constant;
           p.config.contact.impact.constant = number_in(k, n, 0.0, 1.0, false, false);
         } else {
           fail(k, n, "must be \"yigit\" or a number in [0, 1]");
         }
       }},
      {"impact.restitution_cap", [](Parsed& p, auto& k, auto& n) { p.config.contact.impact.cap = number_in(k, n, 0.0, 1.0, false, false); }},
      {"impact.friction",
       [](Parsed& p, auto& k, auto& n) {
         p.config.contact.impact.friction =
             one_of(k, n, {"none", "coulomb"}) == "coulomb" ? ImpactFriction::coulomb : ImpactFriction::none;
       }},
      {"impact.plastic_below_m_s", [](Parsed& p, auto& k, auto& n) { p.config.contact.impact.plastic_below_m_s = number_in(k, n, 0.0, 1e6, false, false); }},
      // The compliant contact law (docs/contact.md); its keys are checked together in check_contact.
      {"contact.model",
       [](Parsed& p, auto& k, auto& n) {
         p.config.contact.model = one_of(k, n, {"rigid", "hertz"}) == "hertz" ? ContactModel::hertz : ContactModel::rigid;
       }},
      {"contact.tip_radius_m", [](Parsed& p, auto& k, auto& n) { p.config.contact.hertz.tip_radius_m = number_in(k, n, 0.0, 1.0, true, false); }},
      {"contact.friction_regularization_m_s",
       [](Parsed& p, auto& k, auto& n) { p.config.contact.hertz.friction_regularization_m_s = number_in(k, n, 0.0, 10.0, true, false); }},
      {"contact.stiffness_factor",
       [](Parsed& p, auto& k, auto& n) { p.config.contact.hertz.stiffness_factor = number_in(k, n, 1e-6, 1e12, false, false); }},
      {"surface.youngs_modulus_pa",
       [](Parsed& p, auto& k, auto& n) { p.config.contact.hertz.surface_youngs_modulus_pa = number_in(k, n, 1e3, 1e15, false, false); }},
      {"surface.poisson", [](Parsed& p, auto& k, auto& n) { p.config.contact.hertz.surface_poisson = number_in(k, n, -1.0, 0.5, true, true); }},
      {"beam.poisson", [](Parsed& p, auto& k, auto& n) { p.config.contact.hertz.wire_poisson = number_in(k, n, -1.0, 0.5, true, true); }},
      {"initial.start",
       [](Parsed& p, auto& k, auto& n) {
         p.config.initial.start = one_of(k, n, {"rigid", "flexible"});
         p.start_given = true;
       }},
      {"initial.modal_velocity",
       [](Parsed& p, auto& k, auto& n) {
         p.config.initial.modal_velocity = number_array(k, n, 1e4);
         p.velocity_node = &n;
       }},
      {"initial.modal_displacement",
       [](Parsed& p, auto& k, auto& n) {
         p.config.initial.modal_displacement = number_array(k, n, 10.0);
         p.displacement_node = &n;
       }},
      {"simulation.scheme",
       [](Parsed& p, auto& k, auto& n) {
         p.config.simulation.scheme = one_of(k, n, {"adaptive", "thesis"}) == "thesis" ? Scheme::thesis : Scheme::adaptive;
       }},
      {"simulation.end_angle_deg",
       [](Parsed& p, auto& k, auto& n) {
         p.config.simulation.end_angle_deg = number_in(k, n, -90.0, 270.0, true, false);
         p.end_angle_node = &n;
       }},
      {"simulation.revolutions",
       [](Parsed& p, auto& k, auto& n) {
         p.config.simulation.revolutions = integer_in(k, n, 1, 10000000);
         p.revolutions_node = &n;
       }},
      {"simulation.until_steady",
       [](Parsed& p, auto& k, auto& n) {
         p.config.simulation.until_steady = boolean(k, n);
         p.until_steady_node = &n;
       }},
      {"simulation.steady_tolerance",
       [](Parsed& p, auto& k, auto& n) {
         p.config.simulation.steady_tolerance = number_in(k, n, 0.0, 1.0, true, true);
         p.steady_tolerance_node = &n;
       }},
      {"simulation.multipliers",
       [](Parsed& p, auto& k, auto& n) {
         p.config.simulation.multipliers = boolean(k, n);
         p.multipliers_node = &n;
       }},
      {"simulation.steady_method",
       [](Parsed& p, auto& k, auto& n) {
         p.config.simulation.steady_method =
             one_of(k, n, {"brute_force", "shooting"}) == "shooting" ? SteadyMethod::shooting : SteadyMethod::brute_force;
         p.method_node = &n;
       }},
      {"simulation.rtol",
       [](Parsed& p, auto& k, auto& n) {
         p.config.simulation.rtol = number_in(k, n, 0.0, 1.0, true, true);
         p.rtol_node = &n;
       }},
      // atol bounds the error of q [m], q̇ [m/s] and the contact integrals: above 1e-3 it bounds nothing.
      {"simulation.atol",
       [](Parsed& p, auto& k, auto& n) {
         p.config.simulation.atol = number_in(k, n, 0.0, 1e-3, true, false);
         p.atol_node = &n;
       }},
      // The step keys' floors (here and free_step_s, contact_step_s, fine_contact_step_s below) keep
      // a step far above the resolution of t at a pass's times (t + h == t is still checked at every
      // step: step_underflow). No floor can bound a pass's cost, the integrated time over the step:
      // at the slowest accepted speed (1e-3 rpm, a half turn in 30 000 s) the ceilings alone give
      // 3e6 steps and the floor 1e-11 s 3e15; at 550 rpm the half turn's 0.055 s takes 5.5e9 steps
      // of 1e-11 s. So `rotbeam run` announces a pass estimated above 1e9 steps before it starts
      // (estimate_steps, case.hpp) and its progress line shows the time left.
      {"simulation.max_step_s",
       [](Parsed& p, auto& k, auto& n) {
         p.config.simulation.max_step_s = number_in(k, n, 1e-11, 1e-2, false, false);
         p.max_step_node = &n;
       }},
      {"simulation.end_when_clear",
       [](Parsed& p, auto& k, auto& n) {
         p.config.simulation.end_when_clear = boolean(k, n);
         p.end_when_clear_node = &n;
       }},
      {"simulation.integrating_factor",
       [](Parsed& p, auto& k, auto& n) {
         if (n.is_boolean())
           p.config.simulation.integrating_factor = *n.template value<bool>() ? FactorUse::always : FactorUse::never;
         else if (n.is_string() && *n.template value<std::string>() == "auto")
           p.config.simulation.integrating_factor = FactorUse::automatic;
         else
           fail(k, n, "must be true, false or \"auto\"");
         p.factor_node = &n;
       }},
      {"simulation.free_step_s", [](Parsed& p, auto& k, auto& n) { p.config.simulation.free_step_s = number_in(k, n, 1e-11, 1e-3, false, false); }},
      {"simulation.contact_step_s", [](Parsed& p, auto& k, auto& n) { p.config.simulation.contact_step_s = number_in(k, n, 1e-12, 1e-4, false, false); }},
      {"simulation.fine_contact_step_s", [](Parsed& p, auto& k, auto& n) { p.config.simulation.fine_contact_step_s = number_in(k, n, 1e-13, 1e-4, false, false); }},
      {"simulation.fine_below_n", [](Parsed& p, auto& k, auto& n) { p.config.simulation.fine_below_n = number_in(k, n, 0.0, 1e6, false, false); }},
      {"simulation.corrector_tolerance", [](Parsed& p, auto& k, auto& n) { p.config.simulation.corrector_tolerance = number_in(k, n, 0.0, 1.0, true, true); }},
      {"simulation.corrector_max_iterations",
       [](Parsed& p, auto& k, auto& n) { p.config.simulation.corrector_max_iterations = integer_in(k, n, 1, 10000); }},
      {"simulation.max_impacts", [](Parsed& p, auto& k, auto& n) { p.config.simulation.max_impacts = integer_in(k, n, 1, 100000000); }},
      {"simulation.deflection_warning_ratio", [](Parsed& p, auto& k, auto& n) { p.config.simulation.deflection_warning_ratio = number_in(k, n, 0.0, 100.0, true, false); }},
      {"simulation.deflection_limit_is_error", [](Parsed& p, auto& k, auto& n) { p.config.simulation.deflection_limit_is_error = boolean(k, n); }},
      {"output.interval_s", [](Parsed& p, auto& k, auto& n) { p.config.simulation.output_interval_s = number_in(k, n, 0.0, 1e30, false, false); }},
      {"output.near_surface_interval_s",
       [](Parsed& p, auto& k, auto& n) {
         // Below 1e-9 s a near-surface stretch of a millisecond would hold a million rows.
         const double v = number_in(k, n, 0.0, 1.0, false, false);
         if (v > 0.0 && v < 1e-9) fail(k, n, "must be 0 (a row at every accepted step) or at least 1e-9 s");
         p.config.simulation.near_surface_interval_s = v;
       }},
      {"output.near_surface_gap_m", [](Parsed& p, auto& k, auto& n) { p.config.simulation.near_surface_gap_m = number_in(k, n, 0.0, 1.0, false, false); }},
      {"output.bin_deg", [](Parsed& p, auto& k, auto& n) { p.config.simulation.bin_deg = number_in(k, n, 0.01, 90.0, false, false); }},
      {"output.history_revolutions",
       [](Parsed& p, auto& k, auto& n) {
         // The last K revolutions' history and events, or "all" (stored as 0).
         if (n.is_string()) {
           if (*n.template value<std::string>() != "all")
             fail(k, n, "must be a whole number of revolutions (at least 1) or \"all\"");
           p.config.simulation.history_revolutions = 0;
         } else if (n.is_integer()) {
           p.config.simulation.history_revolutions = integer_in(k, n, 1, 10000000);
         } else {
           fail(k, n, "must be a whole number of revolutions (at least 1) or \"all\"");
         }
       }},
      // A brush (docs/brush.md). Up to kMaxBrushFilaments filaments in all; the scatters are relative
      // standard deviations, at most 0.3 so that the ±3σ draws kept stay positive.
      {"brush.filaments",
       [](Parsed& p, auto& k, auto& n) {
         brush_of(p).filaments = integer_in(k, n, 1, kMaxBrushFilaments);
         p.filaments_node = &n;
       }},
      {"brush.rows",
       [](Parsed& p, auto& k, auto& n) {
         brush_of(p).rows = integer_in(k, n, 1, 1000);
         p.rows_node = &n;
       }},
      {"brush.row_phase_deg", [](Parsed& p, auto& k, auto& n) { brush_of(p).row_phase_deg = number_in(k, n, -360.0, 360.0, false, false); }},
      {"brush.phase_jitter_deg", [](Parsed& p, auto& k, auto& n) { brush_of(p).phase_jitter_deg = number_in(k, n, 0.0, 180.0, false, false); }},
      {"brush.length_scatter", [](Parsed& p, auto& k, auto& n) { brush_of(p).length_scatter = number_in(k, n, 0.0, 0.3, false, false); }},
      {"brush.diameter_scatter", [](Parsed& p, auto& k, auto& n) { brush_of(p).diameter_scatter = number_in(k, n, 0.0, 0.3, false, false); }},
      {"brush.seed",
       [](Parsed& p, auto& k, auto& n) {
         if (!n.is_integer() || *n.template value<int64_t>() < 0) fail(k, n, "must be a whole number >= 0");
         brush_of(p).seed = static_cast<std::uint64_t>(*n.template value<int64_t>());
       }},
      {"compat.thesis_forces", [](Parsed& p, auto& k, auto& n) { p.config.contact.friction.thesis_forces = boolean(k, n); }},
      {"compat.thesis_dcdt", [](Parsed& p, auto& k, auto& n) { p.config.simulation.thesis_dcdt = boolean(k, n); }},
      {"compat.restitution_speed",
       [](Parsed& p, auto& k, auto& n) {
         p.config.contact.impact.speed = one_of(k, n, {"normal", "full"}) == "full" ? RestitutionSpeed::full : RestitutionSpeed::normal;
       }},
  };
  return keys;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string suggestion(const std::string& key) {
  std::string best;
  std::size_t best_d = 4;
  for (const auto& [k, setter] : schema()) {
    const std::size_t d = edit_distance(key, k);
    if (d < best_d) best_d = d, best = k;
  }
  if (best.empty())  // a truncated name: "hub.speed" for "hub.speed_rpm"
    for (const auto& [k, setter] : schema())
      if (key.size() >= 3 && k.rfind(key, 0) == 0) return " (did you mean " + k + "?)";
  return best.empty() ? std::string() : " (did you mean " + best + "?)";
}

void apply_value(toml::table& root, const std::string& key, const std::string& text, const std::string& what);

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

void apply_override(toml::table& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || trimmed(assignment.substr(0, eq)).empty())
    throw ConfigError("--set " + printable(assignment) + ": expected section.key=value");
  apply_value(root, trimmed(assignment.substr(0, eq)), trimmed(assignment.substr(eq + 1)), "--set " + printable(assignment));
}

// Whether `text` is a TOML decimal integer (sign, digits, single underscores between digits) that
// is beyond the 64-bit range TOML reads.
bool wide_integer(const std::string& text) {
  std::string digits;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if ((c == '+' || c == '-') && i == 0) {
      if (c == '-') digits += c;
    } else if (c >= '0' && c <= '9') {
      digits += c;
    } else if (!(c == '_' && i > 0 && i + 1 < text.size() && std::isdigit(static_cast<unsigned char>(text[i - 1])) &&
                 std::isdigit(static_cast<unsigned char>(text[i + 1])))) {
      return false;
    }
  }
  if (digits.empty() || digits == "-") return false;
  int64_t v = 0;
  return std::from_chars(digits.data(), digits.data() + digits.size(), v).ec == std::errc::result_out_of_range;
}

// Sets `key` to the TOML value `text` (a bare word is a string). `what` names the override in errors.
void apply_value(toml::table& root, const std::string& key, const std::string& text, const std::string& what) {
  const auto dot = key.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == key.size() || key.find('.', dot + 1) != std::string::npos)
    throw ConfigError(what + ": the key must be section.key");
  const std::string section = key.substr(0, dot), name = key.substr(dot + 1);
  if (std::none_of(schema().begin(), schema().end(), [&](const auto& s) { return s.first == key; }))
    throw ConfigError((what.rfind("--set ", 0) == 0 ? "--set " : "") + printable(key) + ": unknown key" + suggestion(key));
  // One value on one line: a line break would let the text hold further assignments.
  if (text.find_first_of("\n\r") != std::string::npos)
    throw ConfigError(what + ": the value holds a line break (give one value on one line)");
  toml::table value_table;
  bool parsed_ok = false;
  if (!text.empty()) {
    try {
      value_table = toml::parse("value = " + text);
      parsed_ok = value_table.size() == 1 && value_table.contains("value");
    } catch (const toml::parse_error&) {
      parsed_ok = false;
    }
  }
  if (!root.contains(section)) root.insert(section, toml::table{});
  toml::table* sec = root[section].as_table();
  if (!sec) fail(section, *root.get(section), "unknown top-level key; expected a [section]" + suggestion(section));
  if (!parsed_ok && wide_integer(text)) {
    // An integer beyond the 64 bits TOML reads ("2**80" from Python) is a number, not a word: the
    // key's own check is asked with the nearest 64-bit integer and its answer given with the value
    // as written (it was "beam.modes = \"1208925819614629174706176\": must be an integer"). A key
    // that takes a number that large gets it as a float.
    const toml::value<int64_t> nearest(text[0] == '-' ? std::numeric_limits<int64_t>::min()
                                                      : std::numeric_limits<int64_t>::max());
    const auto setter = std::find_if(schema().begin(), schema().end(), [&](const auto& s) { return s.first == key; });
    try {
      Parsed scratch;
      setter->second(scratch, key, nearest);
    } catch (const ConfigError& e) {
      const std::string said = e.what(), shown = printable(key) + " = " + render(nearest) + ": ";
      if (said.rfind(shown, 0) != 0) throw;
      throw ConfigError(printable(key) + " = " + text + ": " + said.substr(shown.size()));
    }
    std::string digits;
    std::copy_if(text.begin(), text.end(), std::back_inserter(digits), [](char c) { return c != '_'; });
    sec->insert_or_assign(name, std::strtod(digits.c_str(), nullptr));
    return;
  }
  if (parsed_ok)
    value_table["value"].node()->visit([&](auto&& v) { sec->insert_or_assign(name, v); });
  else
    sec->insert_or_assign(name, text);  // a bare word is a string
}

Config validate(toml::table& root);

Config resolve(toml::table& root, const std::vector<std::string>& overrides) {
  for (const std::string& o : overrides) apply_override(root, o);
  return validate(root);
}

Config resolve(toml::table& root, const std::vector<std::pair<std::string, std::string>>& values) {
  for (const auto& [key, text] : values) apply_value(root, key, text, printable(key) + " = " + printable(text));
  return validate(root);
}

// The [surface] keys each shape takes (surface.hpp): a key of another shape is an error, not ignored.
// The compliant law's keys (docs/contact.md): refused under the rigid law, which has no use for
// them; under hertz the adaptive scheme, the physical forces and a positive restitution are needed.
void check_contact(const toml::table& root, const Config& c) {
  const auto node_of = [&](const char* key) { return root.at_path(key).node(); };
  if (c.contact.model == ContactModel::rigid) {
    for (const char* key : {"contact.tip_radius_m", "contact.friction_regularization_m_s", "contact.stiffness_factor",
                            "surface.youngs_modulus_pa",
                            "surface.poisson", "beam.poisson"})
      if (const toml::node* node = node_of(key)) fail(key, *node, "applies to contact.model = \"hertz\"; this case's is \"rigid\"");
    return;
  }
  const toml::node& model = *node_of("contact.model");
  if (c.simulation.scheme == Scheme::thesis)
    fail("contact.model", model, "needs simulation.scheme = \"adaptive\" (the thesis's scheme has no compliant contact)");
  if (c.contact.friction.thesis_forces)
    fail("contact.model", model, "uses the physical forces: it cannot be combined with compat.thesis_forces = true");
  const ImpactLaw& impact = c.contact.impact;
  const std::string why = "must be at least " + format_number(kMinCompliantRestitution) +
                          " with contact.model = \"hertz\" (Hunt–Crossley damping for e → 0 grows without bound "
                          "and below 0.05 its rebound is lost to rounding)";
  if (impact.model == RestitutionModel::constant && !(impact.constant >= kMinCompliantRestitution)) {
    const toml::node* node = node_of("impact.restitution");
    fail("impact.restitution", node ? *node : model, why);
  }
  if (!(impact.cap >= kMinCompliantRestitution))
    fail("impact.restitution_cap", *node_of("impact.restitution_cap"), why);
}

void check_surface(const toml::table& root, const Config& c) {
  const SurfaceParameters& sp = c.surface;
  const std::string shape = surface_shape_name(sp.shape);
  const auto node_of = [&](const char* key) { return root.at_path(key).node(); };
  const auto refuse = [&](const char* key, const char* belongs) {
    if (const toml::node* node = node_of(key))
      fail(key, *node, std::string("applies to ") + belongs + "; this case's surface.shape is \"" + shape + "\"");
  };
  const double L = c.beam.length_m;
  switch (sp.shape) {
    case SurfaceShape::plane:
      for (const char* key : {"surface.radius_m", "surface.speed_rpm"}) refuse(key, "surface.shape = \"cylinder\"");
      for (const char* key : {"surface.clearance_m", "surface.lobes", "surface.lobe_amplitude_m", "surface.lobe_law"})
        refuse(key, "surface.shape = \"casing\"");
      break;
    case SurfaceShape::cylinder:
      for (const char* key : {"surface.clearance_m", "surface.lobes", "surface.lobe_amplitude_m", "surface.lobe_law"})
        refuse(key, "surface.shape = \"casing\"");
      if (!node_of("surface.radius_m"))
        throw ConfigError("surface.shape = \"cylinder\" needs surface.radius_m, the workpiece's radius in m");
      // A workpiece no wider than the depth lies wholly within the tip's reach: the filament's body would
      // sweep through it while the tip's circle passes beyond it.
      if (!(2.0 * sp.radius_m > sp.depth_fraction * L))
        fail("surface.radius_m", *node_of("surface.radius_m"),
             "the workpiece is " + format_number(2.0 * sp.radius_m) + " m across, within the tip's reach p·L = " +
                 format_number(sp.depth_fraction * L) + " m: the filament would pass through it (make it wider than the depth)");
      break;
    case SurfaceShape::casing: {
      refuse("surface.depth_fraction", "a plane or a cylinder; a casing is placed by surface.clearance_m");
      for (const char* key : {"surface.radius_m", "surface.speed_rpm"}) refuse(key, "surface.shape = \"cylinder\"");
      if (sp.lobes == 0)
        for (const char* key : {"surface.lobe_amplitude_m", "surface.lobe_law"})
          if (const toml::node* node = node_of(key))
            fail(key, *node, "needs surface.lobes >= 1: without lobes the casing is a circle about the hub");
      if (sp.lobe_law == "benchmark" && sp.lobes != 2)
        fail("surface.lobe_law", *node_of("surface.lobe_law"),
             "the benchmark's law has two lobes: it needs surface.lobes = 2, got " + std::to_string(sp.lobes));
      // The casing must stay outside the hub: its smallest radius r_h + L + c0 − A (2A for the benchmark)
      // above r_h.
      const double deepest = sp.clearance_m - (sp.lobe_law == "benchmark" ? 2.0 : 1.0) * (sp.lobes ? sp.lobe_amplitude_m : 0.0);
      if (!(deepest > -L)) {
        const char* key = node_of("surface.lobe_amplitude_m") && sp.lobes ? "surface.lobe_amplitude_m" : "surface.clearance_m";
        const std::string what = "the casing's smallest radius r_h + L − " + format_number(-deepest) +
                                 " m reaches the hub (beam.length_m = " + format_number(L) + ")";
        if (const toml::node* node = node_of(key)) fail(key, *node, what);
        throw ConfigError(std::string(key) + ": " + what);
      }
      break;
    }
  }
}

Config validate(toml::table& root) {
  Parsed p;
  std::map<std::string, const Setter*> by_key;
  for (const auto& [k, s] : schema()) by_key[k] = &s;
  // Walk the table in schema order so dependent checks see their inputs; reject unknown names first.
  for (auto&& [section_key, section_node] : root) {
    const std::string section(section_key.str());
    const toml::table* sec = section_node.as_table();
    if (!sec) fail(section, section_node, "unknown top-level key; expected a [section]" + suggestion(section));
    for (auto&& [name_key, value] : *sec) {
      const std::string key = section + "." + std::string(name_key.str());
      // An empty key name is shown quoted (it read `hub. = 5`).
      if (!by_key.count(key))
        fail(name_key.str().empty() ? section + ".\"\"" : key, value, "unknown key" + suggestion(key));
    }
  }
  for (const auto& [k, setter] : schema()) {
    const auto dot = k.find('.');
    const toml::node* node = root.at_path(k).node();
    (void)dot;
    if (node) setter(p, k, *node);
  }
  Config& c = p.config;
  const int n = c.beam.modes;
  InitialSettings& ini = c.initial;
  auto check_length = [&](std::vector<double>& v, const toml::node* node, const char* key) {
    if (!node) {
      v.assign(n, 0.0);
      return;
    }
    if (static_cast<int>(v.size()) != n)
      fail(key, *node, "must have beam.modes = " + std::to_string(n) + " values, got " + std::to_string(v.size()));
  };
  if (p.modes_node && n > max_modes(c.beam.theory)) fail("beam.modes", *p.modes_node, modes_range());
  if (p.damping_node && c.beam.damping_ratio.size() != 1 && static_cast<int>(c.beam.damping_ratio.size()) != n)
    fail("beam.damping_ratio", *p.damping_node,
         "must be one number or beam.modes = " + std::to_string(n) + " values, got " +
             std::to_string(c.beam.damping_ratio.size()));
  check_length(ini.modal_velocity, p.velocity_node, "initial.modal_velocity");
  check_length(ini.modal_displacement, p.displacement_node, "initial.modal_displacement");
  const bool disturbed = std::any_of(ini.modal_velocity.begin(), ini.modal_velocity.end(), [](double v) { return v != 0.0; }) ||
                         std::any_of(ini.modal_displacement.begin(), ini.modal_displacement.end(), [](double v) { return v != 0.0; });
  if (disturbed) {
    if (p.start_given && ini.start == "rigid")
      throw ConfigError("initial.start = \"rigid\" contradicts a non-zero initial.modal_velocity or "
                        "initial.modal_displacement (a rigid start has q = q̇ = 0)");
    ini.start = "flexible";
  }
  if (!(c.beam.diameter_m < c.beam.length_m)) {
    const toml::node* node = root.at_path("beam.diameter_m").node();
    const std::string what = "must be below beam.length_m = " + format_number(c.beam.length_m) + " (a filament, not a disc)";
    if (node) fail("beam.diameter_m", *node, what);
    throw ConfigError("beam.diameter_m = " + format_number(c.beam.diameter_m) + ": " + what);
  }
  check_surface(root, c);
  check_contact(root, c);
  PassOptions& sim = c.simulation;
  if (p.revolutions_node && p.end_angle_node)
    fail("simulation.end_angle_deg", *p.end_angle_node,
         "cannot be given with simulation.revolutions = " + std::to_string(sim.revolutions) +
             " (a run ends after whole revolutions or at an angle, not both)");
  if (p.revolutions_node && sim.end_when_clear)
    fail("simulation.end_when_clear", *p.end_when_clear_node,
         "ends one pass early; with simulation.revolutions = " + std::to_string(sim.revolutions) +
             " every revolution's free flight is the point");
  // A run to the steady state ends there or after simulation.revolutions: an end angle was ignored
  // without a word, and end_when_clear ended the section map's one-revolution runs early, so that
  // the Floquet multipliers were silently not computed.
  if (sim.until_steady && p.end_angle_node)
    fail("simulation.end_angle_deg", *p.end_angle_node,
         "cannot be given with simulation.until_steady = true (the run ends at the steady state or after "
         "simulation.revolutions, not at an angle)");
  if (sim.until_steady && sim.end_when_clear)
    fail("simulation.end_when_clear", *p.end_when_clear_node,
         "ends one pass early; with simulation.until_steady = true every revolution's free flight is the point");
  if (sim.steady_method == SteadyMethod::shooting && !sim.until_steady)
    fail("simulation.steady_method", *p.method_node,
         "shooting searches for the steady state: it needs simulation.until_steady = true");
  if (c.brush && c.surface.shape == SurfaceShape::casing) {
    const toml::node* node = root.at_path("surface.shape").node();
    fail("surface.shape", *node,
         "a brush works a plane or a cylinder in this version (its filaments' scatter moves their depth, which a "
         "casing does not have)");
  }
  if (c.brush) {
    // Every filament of a brush runs to its periodic steady state.
    if (p.until_steady_node && !sim.until_steady)
      fail("simulation.until_steady", *p.until_steady_node,
           "a brush's filaments run to their periodic steady state: leave it out or set it true");
    sim.until_steady = true;
    const long long total = static_cast<long long>(c.brush->filaments) * c.brush->rows;
    if (total > kMaxBrushFilaments)
      fail("brush.rows", p.rows_node ? *p.rows_node : *p.filaments_node,
           "brush.filaments × brush.rows = " + std::to_string(total) + " filaments, more than " +
               std::to_string(kMaxBrushFilaments));
  }
  // The steady-state search's own keys, given a value other than their default, would change
  // nothing without it (as shooting, above): refused. Their defaults, as in a file that lists every
  // key, are accepted.
  const PassOptions defaults;
  if (!sim.until_steady && p.multipliers_node && sim.multipliers != defaults.multipliers)
    fail("simulation.multipliers", *p.multipliers_node,
         "the Floquet multipliers are those of the steady orbit: it needs simulation.until_steady = true");
  if (!sim.until_steady && p.steady_tolerance_node && sim.steady_tolerance != defaults.steady_tolerance)
    fail("simulation.steady_tolerance", *p.steady_tolerance_node,
         "the steady state's tolerance: it needs simulation.until_steady = true");
  // The adaptive scheme's tolerances, step cap and integrating factor change nothing under the
  // thesis's fixed steps (they were accepted and ignored): refused there unless at their defaults.
  if (sim.scheme == Scheme::thesis) {
    const std::string why = "the adaptive scheme's; simulation.scheme = \"thesis\" takes fixed steps "
                            "(simulation.free_step_s, simulation.contact_step_s)";
    if (p.rtol_node && sim.rtol != defaults.rtol) fail("simulation.rtol", *p.rtol_node, why);
    if (p.atol_node && sim.atol != defaults.atol) fail("simulation.atol", *p.atol_node, why);
    if (p.max_step_node && sim.max_step_s != defaults.max_step_s) fail("simulation.max_step_s", *p.max_step_node, why);
    if (p.factor_node && sim.integrating_factor != defaults.integrating_factor)
      fail("simulation.integrating_factor", *p.factor_node, why);
  }
  if (sim.until_steady && !p.revolutions_node) sim.revolutions = kDefaultSteadyRevolutionCap;
  if (c.beam.theory == BeamTheory::elastica && sim.deflection_limit_is_error)
    fail("simulation.deflection_limit_is_error", *root.at_path("simulation.deflection_limit_is_error").node(),
         "the deflection limit is the quadratic foreshortening model's; the elastica (beam.theory = \"elastica\") "
         "is exact at any deflection");
  // The start the configuration describes must be possible (checked through the beam and surface).
  std::shared_ptr<const BeamModel> beam_model;
  try {
    beam_model = make_beam_model(c.beam);
  } catch (const std::invalid_argument& e) {
    if (p.damping_node) fail("beam.damping_ratio", *p.damping_node, e.what());
    throw ConfigError(e.what());
  }
  const BeamModel& beam = *beam_model;
  const std::shared_ptr<const Surface> surface = make_surface(c.surface, beam);
  if (sim.revolutions > 0) sim.end_angle_deg = beam.theta(0.0) * 180.0 / M_PI + 360.0 * sim.revolutions;
  if (ini.start == "flexible") {
    // A flexible start must begin clear of the surface.
    const Eigen::VectorXd q0 = Eigen::Map<const Eigen::VectorXd>(ini.modal_displacement.data(), n);
    // ... and inside the geometry the model can represent (SPEC §10).
    const double reach = tip_reach(beam, q0);
    if (!(reach <= kReachLimit)) {
      const std::string what = "the initial shape puts the tip " + computed_number(reach) +
                               " L from its clamp, farther than a filament of length L can reach";
      if (p.displacement_node) fail("initial.modal_displacement", *p.displacement_node, what);
      throw ConfigError(what);
    }
    const double c0 = gap(beam, *surface, 0.0, q0);
    if (c0 >= 0.0) {
      const std::string what = "the initial shape already reaches the surface (gap " + computed_number(c0) + " m >= 0)";
      if (p.displacement_node) fail("initial.modal_displacement", *p.displacement_node, what);
      // The straight filament: the surface's place is what puts it there.
      const bool casing = c.surface.shape == SurfaceShape::casing;
      const char* key = casing ? "surface.clearance_m" : "surface.depth_fraction";
      if (const toml::node* node = casing ? root.at_path(key).node() : p.depth_node) fail(key, *node, what);
      throw ConfigError(std::string(key) + " = " + format_number(casing ? c.surface.clearance_m : c.surface.depth_fraction) +
                        ": " + what);
    }
  } else {
    // A rigid start must begin clear of the surface and reach it before the end angle. The key that
    // places the surface: the depth (plane, cylinder) or the casing's clearance.
    const bool casing = c.surface.shape == SurfaceShape::casing;
    const char* place_key = casing ? "surface.clearance_m" : "surface.depth_fraction";
    const toml::node* place_node = casing ? root.at_path(place_key).node() : p.depth_node;
    const double place_value = casing ? c.surface.clearance_m : c.surface.depth_fraction;
    const auto refuse_place = [&](const std::string& what) {
      if (place_node) fail(place_key, *place_node, what);
      throw ConfigError(std::string(place_key) + " = " + format_number(place_value) + ": " + what);
    };
    const double c0 = gap(beam, *surface, 0.0, Eigen::VectorXd::Zero(n));
    if (c0 >= 0.0)
      refuse_place("the undeformed tip starts inside the surface (gap " + computed_number(c0) +
                   " m >= 0 at the start angle): a rigid start needs it clear (or start flexible, with an "
                   "initial.modal_displacement that bends the tip clear)");
    const double theta_star = surface->first_contact_angle(beam.tip_radius(), beam.theta(0.0)) * 180.0 / M_PI;
    if (std::isnan(theta_star))
      refuse_place(casing ? "the undeformed tip never reaches the casing: its clearance stays positive all round"
                          : "the undeformed tip never reaches the surface: the depth is below what the tip's "
                            "position resolves in double precision");
    if (!(theta_star < c.simulation.end_angle_deg)) {
      const std::string what = "the rigid tip reaches the surface only at " + computed_number(theta_star) +
                               " deg, after the end angle " + format_number(c.simulation.end_angle_deg) + " deg";
      if (p.end_angle_node) fail("simulation.end_angle_deg", *p.end_angle_node, what);
      refuse_place(what);
    }
  }
  return c;
}

}  // namespace

std::string printable(const std::string& s) {
  std::string out;
  const auto escape = [&out](const char* format, unsigned value) {
    char buf[12];
    std::snprintf(buf, sizeof buf, format, value);
    out += buf;
  };
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      if (c < 0x20 || c == 0x7f) escape("\\u%04x", c);
      else out += static_cast<char>(c);
      ++i;
      continue;
    }
    // A UTF-8 sequence: its length from the lead byte, its continuation bytes checked, the
    // shortest form and the Unicode range required; anything else is a byte shown as \xNN.
    const std::size_t len = (c & 0xe0) == 0xc0 ? 2 : (c & 0xf0) == 0xe0 ? 3 : (c & 0xf8) == 0xf0 ? 4 : 0;
    unsigned cp = len == 2 ? (c & 0x1fu) : len == 3 ? (c & 0x0fu) : (c & 0x07u);
    bool valid = len != 0 && i + len <= s.size();
    for (std::size_t k = 1; valid && k < len; ++k) {
      const auto b = static_cast<unsigned char>(s[i + k]);
      valid = (b & 0xc0) == 0x80;
      cp = (cp << 6) | (b & 0x3fu);
    }
    if (valid)
      valid = (len == 2 && cp >= 0x80) || (len == 3 && cp >= 0x800 && (cp < 0xd800 || cp > 0xdfff)) ||
              (len == 4 && cp >= 0x10000 && cp <= 0x10ffff);
    if (!valid) {
      escape("\\x%02x", c);
      ++i;
      continue;
    }
    // C1 controls, and the marks, embeddings, overrides and isolates that reorder a terminal's line.
    const bool hidden = cp <= 0x9f || cp == 0x061c || cp == 0x200e || cp == 0x200f || (cp >= 0x202a && cp <= 0x202e) ||
                        (cp >= 0x2066 && cp <= 0x2069);
    if (hidden) escape("\\u%04x", cp);
    else out.append(s, i, len);
    i += len;
  }
  return out;
}


nlohmann::json Config::to_json() const {
  const ImpactLaw& impact = contact.impact;
  const PassOptions& sim = simulation;
  nlohmann::json j;
  j["beam"] = {{"length_m", beam.length_m},
               {"diameter_m", beam.diameter_m},
               {"density_kg_m3", beam.density_kg_m3},
               {"youngs_modulus_pa", beam.youngs_modulus_pa},
               {"modes", beam.modes},
               {"damping_ratio", beam.damping_ratio.empty() ? nlohmann::json(0.0)
                                 : beam.damping_ratio.size() == 1 ? nlohmann::json(beam.damping_ratio[0])
                                                                  : nlohmann::json(beam.damping_ratio)}};
  // The theory and the rotation switches appear where they differ from the thesis's (older folders resume).
  if (beam.theory != BeamTheory::foreshortening) j["beam"]["theory"] = beam_theory_name(beam.theory);
  if (!beam.centrifugal || !beam.coriolis) j["model"] = {{"centrifugal", beam.centrifugal}, {"coriolis", beam.coriolis}};
  j["hub"] = {{"radius_m", beam.hub_radius_m}, {"speed_rpm", beam.speed_rpm}};
  // A plane's section is as it always was (older folders resume); other shapes add their keys.
  switch (surface.shape) {
    case SurfaceShape::plane:
      j["surface"] = {{"depth_fraction", surface.depth_fraction}, {"friction", contact.friction.mu}};
      break;
    case SurfaceShape::cylinder:
      j["surface"] = {{"shape", "cylinder"},
                      {"depth_fraction", surface.depth_fraction},
                      {"radius_m", surface.radius_m},
                      {"speed_rpm", surface.speed_rpm},
                      {"friction", contact.friction.mu}};
      break;
    case SurfaceShape::casing:
      j["surface"] = {{"shape", "casing"}, {"clearance_m", surface.clearance_m}, {"lobes", surface.lobes},
                      {"friction", contact.friction.mu}};
      if (surface.lobes > 0) {
        j["surface"]["lobe_amplitude_m"] = surface.lobe_amplitude_m;
        j["surface"]["lobe_law"] = surface.lobe_law;
      }
      break;
  }
  j["impact"] = {{"restitution_cap", impact.cap},
                 {"plastic_below_m_s", impact.plastic_below_m_s},
                 {"friction", impact.friction == ImpactFriction::coulomb ? "coulomb" : "none"}};
  if (impact.model == RestitutionModel::yigit)
    j["impact"]["restitution"] = "yigit";
  else
    j["impact"]["restitution"] = impact.constant;
  if (contact.model == ContactModel::hertz) {  // a rigid case's configuration is as it always was
    const HertzContact& h = contact.hertz;
    j["contact"] = {{"model", "hertz"},
                    {"friction_regularization_m_s", h.friction_regularization_m_s},
                    {"stiffness_factor", h.stiffness_factor}};
    if (h.tip_radius_m > 0.0) j["contact"]["tip_radius_m"] = h.tip_radius_m;
    j["surface"]["youngs_modulus_pa"] = h.surface_youngs_modulus_pa;
    j["surface"]["poisson"] = h.surface_poisson;
    j["beam"]["poisson"] = h.wire_poisson;
  }
  j["initial"] = {{"start", initial.start},
                  {"modal_velocity", initial.modal_velocity},
                  {"modal_displacement", initial.modal_displacement}};
  j["simulation"] = {{"scheme", scheme_name(sim.scheme)},
                     {"end_angle_deg", sim.end_angle_deg},
                     {"rtol", sim.rtol},
                     {"atol", sim.atol},
                     {"max_step_s", sim.max_step_s},
                     {"integrating_factor", sim.integrating_factor == FactorUse::automatic
                                                ? nlohmann::json("auto")
                                                : nlohmann::json(sim.integrating_factor == FactorUse::always)},
                     {"end_when_clear", sim.end_when_clear},
                     {"free_step_s", sim.free_step_s},
                     {"contact_step_s", sim.contact_step_s},
                     {"fine_contact_step_s", sim.fine_contact_step_s},
                     {"fine_below_n", sim.fine_below_n},
                     {"corrector_tolerance", sim.corrector_tolerance},
                     {"corrector_max_iterations", sim.corrector_max_iterations},
                     {"max_impacts", sim.max_impacts},
                     {"deflection_warning_ratio", sim.deflection_warning_ratio},
                     {"deflection_limit_is_error", sim.deflection_limit_is_error},
                     {"revolutions", sim.revolutions},
                     {"until_steady", sim.until_steady},
                     {"steady_tolerance", sim.steady_tolerance},
                     {"steady_method", steady_method_name(sim.steady_method)},
                     {"multipliers", sim.multipliers}};
  j["output"] = {{"interval_s", sim.output_interval_s},
                 {"near_surface_interval_s", sim.near_surface_interval_s},
                 {"near_surface_gap_m", sim.near_surface_gap_m},
                 {"bin_deg", sim.bin_deg},
                 {"history_revolutions",
                  sim.history_revolutions == 0 ? nlohmann::json("all") : nlohmann::json(sim.history_revolutions)}};
  if (brush)
    j["brush"] = {{"filaments", brush->filaments},
                  {"rows", brush->rows},
                  {"row_phase_deg", brush->row_phase_deg},
                  {"phase_jitter_deg", brush->phase_jitter_deg},
                  {"length_scatter", brush->length_scatter},
                  {"diameter_scatter", brush->diameter_scatter},
                  {"seed", brush->seed}};
  j["compat"] = {{"thesis_forces", contact.friction.thesis_forces},
                 {"thesis_dcdt", sim.thesis_dcdt},
                 {"restitution_speed", impact.speed == RestitutionSpeed::full ? "full" : "normal"}};
  return j;
}

Config load_config_string(const std::string& toml_text, const std::vector<std::string>& overrides) {
  toml::table root;
  try {
    root = toml::parse(toml_text);
  } catch (const toml::parse_error& e) {
    throw ConfigError("TOML syntax error at line " + std::to_string(e.source().begin.line) + ", column " +
                      std::to_string(e.source().begin.column) + ": " + std::string(e.description()));
  }
  return resolve(root, overrides);
}

namespace {
toml::table read_file(const std::optional<std::string>& path) {
  toml::table root;
  if (!path) return root;
  namespace fs = std::filesystem;
  // The path as given, with "" for the empty one and its control characters escaped.
  const std::string shown = path->empty() ? "\"\"" : printable(*path);
  std::error_code ec;
  const fs::file_status st = fs::status(*path, ec);
  // status() reports what is not there as not_found; anything else (a loop of symbolic links, a
  // component that is not a folder, no permission) in the system's words.
  if (st.type() == fs::file_type::none && ec)
    throw ConfigError(shown + ": cannot read the configuration file (" + ec.message() + ")");
  if (!fs::exists(st)) throw ConfigError(shown + ": no such configuration file");
  if (fs::is_directory(st)) throw ConfigError(shown + ": is a folder, not a configuration file");
  if (!fs::is_regular_file(st)) throw ConfigError(shown + ": is not a regular file (a device, a pipe or a socket)");
  std::ifstream probe(*path);
  if (!probe) throw ConfigError(shown + ": cannot read the configuration file (" + std::generic_category().message(errno) + ")");
  try {
    // Read whole here, not by toml++'s parse_file, which sizes the file first: a file under /proc
    // reports size 0 and read as "could not be opened for reading".
    const std::string text((std::istreambuf_iterator<char>(probe)), std::istreambuf_iterator<char>());
    if (probe.bad()) throw ConfigError(shown + ": cannot read the configuration file");
    root = toml::parse(text, *path);
  } catch (const toml::parse_error& e) {
    throw ConfigError(shown + ":" + std::to_string(e.source().begin.line) + ":" +
                      std::to_string(e.source().begin.column) + ": TOML syntax error: " + printable(std::string(e.description())));
  }
  return root;
}
}  // namespace

Config load_config(const std::optional<std::string>& path, const std::vector<std::string>& overrides) {
  toml::table root = read_file(path);
  return resolve(root, overrides);
}

Config load_config_values(const std::optional<std::string>& path,
                          const std::vector<std::pair<std::string, std::string>>& values) {
  toml::table root = read_file(path);
  return resolve(root, values);
}

Config load_config_text_values(const std::string& toml_text, const std::string& name,
                               const std::vector<std::pair<std::string, std::string>>& values) {
  toml::table root;
  try {
    root = toml::parse(toml_text, name);
  } catch (const toml::parse_error& e) {
    throw ConfigError((name.empty() ? std::string("\"\"") : printable(name)) + ":" +
                      std::to_string(e.source().begin.line) + ":" + std::to_string(e.source().begin.column) +
                      ": TOML syntax error: " + printable(std::string(e.description())));
  }
  return resolve(root, values);
}

namespace {
// A JSON value of Config::to_json as the TOML node it was read from.
void insert_json(toml::table& table, const std::string& key, const nlohmann::json& v) {
  if (v.is_object()) {
    toml::table sub;
    for (auto it = v.begin(); it != v.end(); ++it) insert_json(sub, it.key(), it.value());
    table.insert_or_assign(key, std::move(sub));
  } else if (v.is_array()) {
    toml::array a;
    for (const auto& x : v) a.push_back(x.get<double>());
    table.insert_or_assign(key, std::move(a));
  } else if (v.is_boolean()) {
    table.insert_or_assign(key, v.get<bool>());
  } else if (v.is_number_integer()) {
    table.insert_or_assign(key, v.get<int64_t>());
  } else if (v.is_number()) {
    table.insert_or_assign(key, v.get<double>());
  } else {
    table.insert_or_assign(key, v.get<std::string>());
  }
}
}  // namespace

Config revalidate(const Config& config) {
  nlohmann::json j = config.to_json();
  // Derived values the file would not hold: the end angle of a run over revolutions.
  if (config.simulation.revolutions > 0)
    j["simulation"].erase("end_angle_deg");
  else
    j["simulation"].erase("revolutions");
  toml::table root;
  for (auto it = j.begin(); it != j.end(); ++it) insert_json(root, it.key(), it.value());
  return validate(root);
}

void require_known_key(const std::string& key, const std::string& flag) {
  if (std::none_of(schema().begin(), schema().end(), [&](const auto& s) { return s.first == key; }))
    throw ConfigError(flag + " " + printable(key) + ": unknown key" + suggestion(key));
}

const std::vector<std::string>& config_keys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> k;
    for (const auto& [name, setter] : schema()) k.push_back(name);
    return k;
  }();
  return keys;
}

}  // namespace rotbeam
