// The key table (config_keys.hpp) and what is derived from it alone: a value's check, the words
// that describe a key, Config::to_json, config_keys() and describe_config_keys().
#include "config_keys.hpp"

#include <stdexcept>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>

namespace rotbeam::config_detail {

namespace {

using Kind = Form::Kind;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The forms of the table's rows. A number's range: [lo, hi] (closed), (lo, hi] (above), (lo, hi) (inside).
Form closed(double lo, double hi) { return {Kind::number, lo, hi, false, false, 0, {}}; }
Form above(double lo, double hi) { return {Kind::number, lo, hi, true, false, 0, {}}; }
Form inside(double lo, double hi) { return {Kind::number, lo, hi, true, true, 0, {}}; }
Form integers(double lo, double hi) { return {Kind::integer, lo, hi, false, false, 0, {}}; }
Form boolean() { return {Kind::boolean, 0, 0, false, false, 0, {}}; }
Form words(std::vector<std::string> accepted) { return {Kind::word, 0, 0, false, false, 0, std::move(accepted)}; }
// An array of numbers, each within [-bound, bound] and at least lo.
Form numbers(double lo, double bound) { return {Kind::numbers, lo, bound, false, false, 0, {}}; }

Check one(Form form) { return Check{{std::move(form)}, "", "", ""}; }

bool always(const Config&) { return true; }
bool hertz(const Config& c) { return c.contact.model == ContactModel::hertz; }
bool cylinder(const Config& c) { return c.surface.shape == SurfaceShape::cylinder; }
bool casing(const Config& c) { return c.surface.shape == SurfaceShape::casing; }
bool brush(const Config& c) { return c.brush.has_value(); }

// A brush key's settings: the first brush key set makes the case a brush (docs/brush.md).
BrushSettings& brush_of(Config& c) {
  if (!c.brush) c.brush.emplace();
  return *c.brush;
}
const BrushSettings& brush_of(const Config& c) { return *c.brush; }

using Written = bool (*)(const Config&);

// A key whose value is a struct member as it stands; `ref` gives the member of a Config (const or not).
template <class Ref>
Key plain(std::string name, std::string unit, Check check, std::string doc, Ref ref, Written written = always,
          std::string unset = "") {
  using T = std::decay_t<decltype(ref(std::declval<Config&>()))>;
  return Key{std::move(name),
             std::move(unit),
             std::move(check),
             std::move(doc),
             std::move(unset),
             [ref](const Config& c) { return Value(ref(c)); },
             [ref](Config& c, const Value& v) { ref(c) = v.get<T>(); },
             written};
}

// A key whose value is one of `names`' words, stored as the value paired with it.
template <class T, class Ref>
Key named(std::string name, std::vector<std::pair<std::string, T>> names, std::string doc, Ref ref,
          Written written = always) {
  std::vector<std::string> accepted;
  for (const auto& [word, value] : names) accepted.push_back(word);
  return Key{std::move(name),
             "",
             one(words(std::move(accepted))),
             std::move(doc),
             "",
             [ref, names](const Config& c) {
               for (const auto& [word, value] : names)
                 if (ref(c) == value) return Value(word);
               return Value(names.front().first);
             },
             [ref, names](Config& c, const Value& v) {
               for (const auto& [word, value] : names)
                 if (v == word) ref(c) = value;
             },
             written};
}

// beam.modes's refusal: the thesis model's range, and the elastica's beside it.
std::string modes_range() {
  return "must be in 1.." + std::to_string(kMaxModes) + " (1.." + std::to_string(kMaxElasticaModes) +
         " with beam.theory = \"elastica\")";
}

// Ranges wide enough for any filament or blade, narrow enough that the arithmetic stays finite (a
// diameter of 5e-324 m has a zero area; a radius of 1e300 m overflows the energies). The step keys'
// floors keep a step far above the resolution of t at a pass's times (t + h == t is still checked at
// every step: step_underflow); no floor bounds a pass's cost, so `rotbeam run` announces a pass
// estimated above 1e9 steps (estimate_steps, case.hpp).
std::vector<Key> make_table() {
  std::vector<Key> t;
  t.push_back(plain("beam.length_m", "m", one(above(0, 100)), "the filament's length L",
                    [](auto& c) -> auto& { return c.beam.length_m; }));
  t.push_back(plain("beam.diameter_m", "m", one(closed(1e-7, 1)), "the filament's diameter D (circular section)",
                    [](auto& c) -> auto& { return c.beam.diameter_m; }));
  t.push_back(plain("beam.density_kg_m3", "kg/m^3", one(closed(1e-3, 1e6)), "the filament's density rho",
                    [](auto& c) -> auto& { return c.beam.density_kg_m3; }));
  t.push_back(plain("beam.youngs_modulus_pa", "Pa", one(closed(1e3, 1e15)), "the filament's Young's modulus E",
                    [](auto& c) -> auto& { return c.beam.youngs_modulus_pa; }));
  // Up to the elastica's limit here; the foreshortening model's lower one is checked with beam.theory.
  t.push_back(plain("beam.modes", "", Check{{integers(1, kMaxElasticaModes)}, "", modes_range(), ""},
                    "the number of assumed modes n", [](auto& c) -> auto& { return c.beam.modes; }));
  t.push_back(named<BeamTheory>("beam.theory", {{"foreshortening", BeamTheory::foreshortening}, {"elastica", BeamTheory::elastica}},
                    "the thesis's quadratic foreshortening, or the geometrically exact planar elastica",
                    [](auto& c) -> auto& { return c.beam.theory; },
                    [](const Config& c) { return c.beam.theory != BeamTheory::foreshortening; }));
  t.push_back(named<BeamAxial>("beam.axial", {{"inextensible", BeamAxial::inextensible}, {"extensible", BeamAxial::extensible}},
                    "the thesis's inextensible filament, or one with the wire's axial stiffness EA (one more "
                    "coordinate, the tip's stretch; bounded forces where the filament's axis meets the surface)",
                    [](auto& c) -> auto& { return c.beam.axial; },
                    [](const Config& c) { return c.beam.axial != BeamAxial::inextensible; }));
  // One ratio for every mode, or one per mode; up to 10 (far past critical damping, 1).
  t.push_back(Key{"beam.damping_ratio", "",
                  Check{{closed(0, 10), numbers(0, 10)}, "must be a number or an array of beam.modes numbers in [0, 10]", "", ""},
                  "modal damping ratios of the linearised modes at the hub speed: one for every mode or n", "",
                  [](const Config& c) {
                    const std::vector<double>& z = c.beam.damping_ratio;
                    return z.empty() ? Value(0.0) : z.size() == 1 ? Value(z[0]) : Value(z);
                  },
                  [](Config& c, const Value& v) {
                    c.beam.damping_ratio = v.is_array() ? v.get<std::vector<double>>() : std::vector<double>{v.get<double>()};
                  },
                  always});
  // The rotation switches are written where they differ from the thesis's (older folders resume).
  const Written switched = [](const Config& c) { return !c.beam.centrifugal || !c.beam.coriolis; };
  t.push_back(plain("model.centrifugal", "", one(boolean()),
                    "keep the omega^2 terms of the kinetic energy (centrifugal stiffening, spin softening)",
                    [](auto& c) -> auto& { return c.beam.centrifugal; }, switched));
  t.push_back(plain("model.coriolis", "", one(boolean()), "keep the terms linear in omega (the Coriolis coupling)",
                    [](auto& c) -> auto& { return c.beam.coriolis; }, switched));
  t.push_back(plain("hub.radius_m", "m", one(closed(0, 100)), "the hub's radius r_h",
                    [](auto& c) -> auto& { return c.beam.hub_radius_m; }));
  // Below 1e-3 rpm (a turn in 17 hours) a pass lasts days of simulated time: the steps and times
  // leave the ranges the integration is built for (1e-9 rpm ended in step underflow).
  t.push_back(plain("hub.speed_rpm", "rpm", one(closed(1e-3, 1e6)), "the hub's spin",
                    [](auto& c) -> auto& { return c.beam.speed_rpm; }));
  // A plane's section is as it always was (older folders resume); other shapes add their keys.
  t.push_back(plain("surface.depth_fraction", "", one(inside(0, 1)),
                    "p: the undeformed tip reaches p L into the surface at its deepest (plane, cylinder)",
                    [](auto& c) -> auto& { return c.surface.depth_fraction; },
                    [](const Config& c) { return !casing(c); }));
  t.push_back(plain("surface.friction", "", one(closed(0, 1e3)), "the Coulomb friction coefficient mu",
                    [](auto& c) -> auto& { return c.contact.friction.mu; }));
  t.push_back(named<SurfaceShape>("surface.shape", {{"plane", SurfaceShape::plane}, {"cylinder", SurfaceShape::cylinder}, {"casing", SurfaceShape::casing}},
                    "the surface: the thesis's plane, a round workpiece, or a casing about the hub",
                    [](auto& c) -> auto& { return c.surface.shape; },
                    [](const Config& c) { return c.surface.shape != SurfaceShape::plane; }));
  // A cylinder of 1e9 m is a plane to every digit the gap keeps; the rub and workpiece speeds share
  // the hub's range.
  t.push_back(plain("surface.radius_m", "m", one(above(0, 1e9)), "cylinder: the workpiece's radius R",
                    [](auto& c) -> auto& { return c.surface.radius_m; }, cylinder,
                    "none (a cylinder needs it)"));
  t.push_back(plain("surface.speed_rpm", "rpm", one(closed(-1e6, 1e6)),
                    "cylinder: its spin about its own axis (counter-clockwise > 0, the hub's sense)",
                    [](auto& c) -> auto& { return c.surface.speed_rpm; }, cylinder));
  t.push_back(plain("surface.clearance_m", "m", one(closed(-100, 100)),
                    "casing: c0, its radius is r_h + L + c0 (< 0: interference)",
                    [](auto& c) -> auto& { return c.surface.clearance_m; }, casing));
  t.push_back(plain("surface.lobes", "", one(integers(0, 1000)), "casing: k lobes (0: concentric)",
                    [](auto& c) -> auto& { return c.surface.lobes; }, casing));
  const Written lobed = [](const Config& c) { return casing(c) && c.surface.lobes > 0; };
  t.push_back(plain("surface.lobe_amplitude_m", "m", one(closed(0, 100)), "casing: A, the lobes' amplitude",
                    [](auto& c) -> auto& { return c.surface.lobe_amplitude_m; }, lobed));
  t.push_back(plain("surface.lobe_law", "", one(words({"cosine", "benchmark"})),
                    "casing: c0 - A cos k phi, or the two-lobed rub benchmark's law",
                    [](auto& c) -> auto& { return c.surface.lobe_law; }, lobed));
  // One word among numbers: "must be one of \"yigit\"" left the numbers out.
  t.push_back(Key{"impact.restitution", "",
                  Check{{words({"yigit"}), closed(0, 1)}, "must be \"yigit\" or a number in [0, 1]", "", ""},
                  "the coefficient of restitution e: Yigit's e = 0.501 v^(-1/4), or a constant", "",
                  [](const Config& c) {
                    const ImpactLaw& impact = c.contact.impact;
                    return impact.model == RestitutionModel::yigit ? Value("yigit") : Value(impact.constant);
                  },
                  [](Config& c, const Value& v) {
                    ImpactLaw& impact = c.contact.impact;
                    impact.model = v.is_string() ? RestitutionModel::yigit : RestitutionModel::constant;
                    if (v.is_number()) impact.constant = v.get<double>();
                  },
                  always});
  t.push_back(plain("impact.restitution_cap", "", one(closed(0, 1)), "the upper bound on e",
                    [](auto& c) -> auto& { return c.contact.impact.cap; }));
  t.push_back(named<ImpactFriction>("impact.friction", {{"none", ImpactFriction::none}, {"coulomb", ImpactFriction::coulomb}},
                    "friction during an impact: none (the thesis), or Coulomb's law with Stronge's restitution",
                    [](auto& c) -> auto& { return c.contact.impact.friction; }));
  t.push_back(plain("impact.plastic_below_m_s", "m/s", one(closed(0, 1e6)),
                    "the normal approach speed below which an impact is plastic (e = 0)",
                    [](auto& c) -> auto& { return c.contact.impact.plastic_below_m_s; }));
  // The compliant contact law (docs/contact.md): its keys are written, and accepted, under it only
  // (config_checks.cpp); a rigid case's configuration is as it always was.
  t.push_back(named<ContactModel>("contact.model", {{"rigid", ContactModel::rigid}, {"hertz", ContactModel::hertz}},
                    "the thesis's rigid contact, or compliant Hertz contact with Hunt-Crossley damping",
                    [](auto& c) -> auto& { return c.contact.model; }, hertz));
  t.push_back(plain("contact.tip_radius_m", "m", one(above(0, 1)), "hertz: R, the rounded tip's radius",
                    [](auto& c) -> auto& { return c.contact.hertz.tip_radius_m; },
                    [](const Config& c) { return hertz(c) && c.contact.hertz.tip_radius_m > 0.0; }, "D/2"));
  // The micro-slip's time constant m_eff v_ε/(μF_n) sets the steps, about 4/v_ε [s/m] over the base
  // pass (0.46 s at 1e-4, 32 s at 1e-6): 1e-7 and below ran for hours while the result no longer
  // changes (last separation to 1e-6 between 1e-5 and 1e-6 m/s). docs/contact.md.
  t.push_back(plain("contact.friction_regularization_m_s", "m/s", one(closed(1e-6, 10)),
                    "hertz: the slip speed below which the friction is a micro-slip",
                    [](auto& c) -> auto& { return c.contact.hertz.friction_regularization_m_s; }, hertz));
  t.push_back(plain("contact.stiffness_factor", "", one(closed(1e-6, 1e12)),
                    "hertz: multiplies the contact stiffness (studies of the rigid limit)",
                    [](auto& c) -> auto& { return c.contact.hertz.stiffness_factor; }, hertz));
  t.push_back(plain("surface.youngs_modulus_pa", "Pa", one(closed(1e3, 1e15)), "hertz: the surface's Young's modulus",
                    [](auto& c) -> auto& { return c.contact.hertz.surface_youngs_modulus_pa; }, hertz));
  t.push_back(plain("surface.poisson", "", one(inside(-1, 0.5)), "hertz: the surface's Poisson's ratio",
                    [](auto& c) -> auto& { return c.contact.hertz.surface_poisson; }, hertz));
  t.push_back(plain("beam.poisson", "", one(inside(-1, 0.5)), "hertz: the wire's Poisson's ratio",
                    [](auto& c) -> auto& { return c.contact.hertz.wire_poisson; }, hertz));
  t.push_back(plain("initial.start", "", one(words({"rigid", "flexible"})),
                    "rigid: q = 0 at the geometric impact; flexible: integrate from theta0 = -90 deg",
                    [](auto& c) -> auto& { return c.initial.start; }));
  t.push_back(plain("initial.modal_velocity", "m/s", one(numbers(-1e4, 1e4)),
                    "the modal velocities at the start, n values (non-zero: a flexible start)",
                    [](auto& c) -> auto& { return c.initial.modal_velocity; }, always, "zeros"));
  t.push_back(plain("initial.modal_displacement", "m", one(numbers(-10, 10)),
                    "the modal displacements at the start, n values (non-zero: a flexible start)",
                    [](auto& c) -> auto& { return c.initial.modal_displacement; }, always, "zeros"));
  t.push_back(named<Scheme>("simulation.scheme", {{"adaptive", Scheme::adaptive}, {"thesis", Scheme::thesis}},
                    "error-controlled, event-driven steps, or the thesis's fixed steps",
                    [](auto& c) -> auto& { return c.simulation.scheme; }));
  t.push_back(plain("simulation.end_angle_deg", "deg", one(above(-90, 270)), "the hub angle at which one pass stops",
                    [](auto& c) -> auto& { return c.simulation.end_angle_deg; }));
  t.push_back(plain("simulation.revolutions", "", one(integers(1, 1e7)),
                    "run this many whole revolutions from theta0 = -90 deg", [](auto& c) -> auto& { return c.simulation.revolutions; },
                    always, "none (one pass)"));
  t.push_back(plain("simulation.until_steady", "", one(boolean()), "stop once the section state repeats",
                    [](auto& c) -> auto& { return c.simulation.until_steady; }));
  t.push_back(plain("simulation.steady_tolerance", "", one(inside(0, 1)),
                    "the relative section distance that counts as steady",
                    [](auto& c) -> auto& { return c.simulation.steady_tolerance; }));
  t.push_back(plain("simulation.multipliers", "", one(boolean()), "compute the steady orbit's Floquet multipliers",
                    [](auto& c) -> auto& { return c.simulation.multipliers; }));
  t.push_back(named<SteadyMethod>("simulation.steady_method", {{"brute_force", SteadyMethod::brute_force}, {"shooting", SteadyMethod::shooting}},
                    "how until_steady searches: revolution after revolution, or Newton on the revolution map",
                    [](auto& c) -> auto& { return c.simulation.steady_method; }));
  t.push_back(named<JacobianMethod>("simulation.jacobian", {{"variational", JacobianMethod::variational}, {"differences", JacobianMethod::differences}},
                    "the revolution map's Jacobian (Newton, multipliers, continuation): the variational equations with saltation matrices, or central differences of the map",
                    [](auto& c) -> auto& { return c.simulation.jacobian; }));
  t.push_back(plain("simulation.rtol", "", one(inside(0, 1)), "the adaptive scheme's relative tolerance",
                    [](auto& c) -> auto& { return c.simulation.rtol; }));
  // atol bounds the error of q [m], q̇ [m/s] and the contact integrals: above 1e-3 it bounds nothing.
  t.push_back(plain("simulation.atol", "", one(above(0, 1e-3)), "the adaptive scheme's absolute tolerance",
                    [](auto& c) -> auto& { return c.simulation.atol; }));
  t.push_back(plain("simulation.max_step_s", "s", one(closed(1e-11, 1e-2)), "the adaptive scheme's largest step",
                    [](auto& c) -> auto& { return c.simulation.max_step_s; }));
  t.push_back(plain("simulation.end_when_clear", "", one(boolean()),
                    "end one pass early once the tip provably cannot reach the surface before the end angle",
                    [](auto& c) -> auto& { return c.simulation.end_when_clear; }));
  t.push_back(Key{"simulation.integrating_factor", "", Check{{boolean(), words({"auto"})}, "must be true, false or \"auto\"", "", ""},
                  "adaptive scheme: propagate the linear modal oscillation exactly (auto: when undamped)", "",
                  [](const Config& c) {
                    const FactorUse use = c.simulation.integrating_factor;
                    return use == FactorUse::automatic ? Value("auto") : Value(use == FactorUse::always);
                  },
                  [](Config& c, const Value& v) {
                    c.simulation.integrating_factor =
                        v.is_string() ? FactorUse::automatic : v.get<bool>() ? FactorUse::always : FactorUse::never;
                  },
                  always});
  t.push_back(plain("simulation.free_step_s", "s", one(closed(1e-11, 1e-3)), "thesis scheme: the RK5 step in free flight",
                    [](auto& c) -> auto& { return c.simulation.free_step_s; }));
  t.push_back(plain("simulation.contact_step_s", "s", one(closed(1e-12, 1e-4)),
                    "thesis scheme: the predictor-corrector step in contact",
                    [](auto& c) -> auto& { return c.simulation.contact_step_s; }));
  t.push_back(plain("simulation.fine_contact_step_s", "s", one(closed(1e-13, 1e-4)),
                    "thesis scheme: the step while 0 < |lambda| < fine_below_n",
                    [](auto& c) -> auto& { return c.simulation.fine_contact_step_s; }));
  t.push_back(plain("simulation.fine_below_n", "N", one(closed(0, 1e6)), "thesis scheme: |lambda| below which the fine step is used",
                    [](auto& c) -> auto& { return c.simulation.fine_below_n; }));
  t.push_back(plain("simulation.corrector_tolerance", "", one(inside(0, 1)),
                    "thesis scheme: the relative change of lambda that ends the corrector",
                    [](auto& c) -> auto& { return c.simulation.corrector_tolerance; }));
  t.push_back(plain("simulation.corrector_max_iterations", "", one(integers(1, 10000)),
                    "thesis scheme: corrector iterations before a non-convergence diagnostic",
                    [](auto& c) -> auto& { return c.simulation.corrector_max_iterations; }));
  t.push_back(plain("simulation.max_impacts", "", one(integers(1, 1e8)),
                    "impacts in one pass (or revolution) before an \"impacts accumulate\" diagnostic",
                    [](auto& c) -> auto& { return c.simulation.max_impacts; }));
  t.push_back(plain("simulation.deflection_warning_ratio", "", one(above(0, 100)), "warn when max |y_t|/L exceeds this",
                    [](auto& c) -> auto& { return c.simulation.deflection_warning_ratio; }));
  t.push_back(plain("simulation.deflection_limit_is_error", "", one(boolean()),
                    "stop with a validity failure when max |y_t|/L passes deflection_warning_ratio",
                    [](auto& c) -> auto& { return c.simulation.deflection_limit_is_error; }));
  t.push_back(plain("output.interval_s", "s", one(closed(0, 1e30)), "the history's sampling interval (0: every step)",
                    [](auto& c) -> auto& { return c.simulation.output_interval_s; }));
  // Below 1e-9 s a near-surface stretch of a millisecond would hold a million rows.
  Form near_interval = closed(0, 1);
  near_interval.zero_or_at_least = 1e-9;
  t.push_back(plain("output.near_surface_interval_s", "s",
                    Check{{near_interval}, "", "", "must be 0 (a row at every accepted step) or at least 1e-9 s"},
                    "the sampling interval near the surface (0: every step)",
                    [](auto& c) -> auto& { return c.simulation.near_surface_interval_s; }));
  t.push_back(plain("output.near_surface_gap_m", "m", one(closed(0, 1)),
                    "the distance from the surface within which near_surface_interval_s applies (0: off)",
                    [](auto& c) -> auto& { return c.simulation.near_surface_gap_m; }));
  t.push_back(plain("output.bin_deg", "deg", one(closed(0.01, 90)), "the width of the hub-angle bins of the force",
                    [](auto& c) -> auto& { return c.simulation.bin_deg; }));
  // The last K revolutions' history and events, or "all" (stored as 0).
  t.push_back(Key{"output.history_revolutions", "",
                  Check{{words({"all"}), integers(1, 1e7)}, "must be a whole number of revolutions (at least 1) or \"all\"", "", ""},
                  "the last revolutions whose history and events are kept", "",
                  [](const Config& c) {
                    const int k = c.simulation.history_revolutions;
                    return k == 0 ? Value("all") : Value(k);
                  },
                  [](Config& c, const Value& v) { c.simulation.history_revolutions = v.is_string() ? 0 : v.get<int>(); },
                  always});
  // Wear and frictional heat (docs/wear.md): derived from the ledger's sliding_load and frictional_heat.
  t.push_back(plain("wear.surface_coefficient", "", one(closed(0, 1)),
                    "Archard's wear coefficient k of the surface's material",
                    [](auto& c) -> auto& { return c.wear.surface_coefficient; }));
  t.push_back(plain("wear.surface_hardness_pa", "Pa", one(above(0, 1e13)), "the hardness H of the surface's material",
                    [](auto& c) -> auto& { return c.wear.surface_hardness_pa; }));
  t.push_back(plain("wear.filament_coefficient", "", one(closed(0, 1)), "Archard's wear coefficient k of the filament",
                    [](auto& c) -> auto& { return c.wear.filament_coefficient; }));
  t.push_back(plain("wear.filament_hardness_pa", "Pa", one(above(0, 1e13)), "the hardness H of the filament",
                    [](auto& c) -> auto& { return c.wear.filament_hardness_pa; }));
  t.push_back(plain("wear.heat_to_filament", "", one(closed(0, 1)),
                    "the share of the frictional heat that flows into the filament",
                    [](auto& c) -> auto& { return c.wear.heat_to_filament; }));
  t.push_back(plain("wear.track_width_m", "m", one(closed(0, 10)),
                    "the worn track's width across the plane of motion (0: the filament's diameter)",
                    [](auto& c) -> auto& { return c.wear.track_width_m; }));
  t.push_back(plain("wear.profile_bins", "", one(integers(1, 100000)),
                    "bins of the wear profile over the span of the surface the contact touched",
                    [](auto& c) -> auto& { return c.simulation.wear_profile_bins; }));
  // A brush (docs/brush.md). Up to kMaxBrushFilaments filaments in all; the scatters are relative
  // standard deviations, at most 0.3 so that the ±3σ draws kept stay positive.
  t.push_back(plain("brush.filaments", "", one(integers(1, kMaxBrushFilaments)),
                    "a brush: filaments around the circumference, equally spaced in phase",
                    [](auto& c) -> auto& { return brush_of(c).filaments; }, brush));
  t.push_back(plain("brush.rows", "", one(integers(1, 1000)), "a brush: axial rows of filaments",
                    [](auto& c) -> auto& { return brush_of(c).rows; }, brush));
  t.push_back(plain("brush.row_phase_deg", "deg", one(closed(-360, 360)), "a brush: row r sits r times this ahead of row 0",
                    [](auto& c) -> auto& { return brush_of(c).row_phase_deg; }, brush));
  t.push_back(plain("brush.phase_jitter_deg", "deg", one(closed(0, 180)),
                    "a brush: the standard deviation of each filament's phase",
                    [](auto& c) -> auto& { return brush_of(c).phase_jitter_deg; }, brush));
  t.push_back(plain("brush.length_scatter", "", one(closed(0, 0.3)),
                    "a brush: the relative standard deviation of each filament's length",
                    [](auto& c) -> auto& { return brush_of(c).length_scatter; }, brush));
  t.push_back(plain("brush.diameter_scatter", "", one(closed(0, 0.3)),
                    "a brush: the relative standard deviation of each filament's diameter",
                    [](auto& c) -> auto& { return brush_of(c).diameter_scatter; }, brush));
  // Every seed of mt19937_64, 0 … 2^64 − 1 (read exactly: config.cpp).
  const std::string whole = "must be a whole number in 0..18446744073709551615";
  t.push_back(plain("brush.seed", "", Check{{integers(0, std::ldexp(1.0, 64))}, whole, whole, ""}, "a brush: the scatter's random stream",
                    [](auto& c) -> auto& { return brush_of(c).seed; }, brush));
  t.push_back(named<BrushMethod>("brush.method", {{"filaments", BrushMethod::filaments}, {"population", BrushMethod::population}},
                    "a brush: run every distinct filament, or interpolate the brush's sums from representative filaments",
                    [](auto& c) -> auto& { return brush_of(c).method; }, brush));
  t.push_back(plain("brush.population_tolerance", "", one(inside(0, 1)),
                    "a brush by population: the relative error of the mean force and torque it refines to",
                    [](auto& c) -> auto& { return brush_of(c).population_tolerance; }, brush));
  t.push_back(plain("brush.population_max_runs", "", one(integers(15, 100000)),
                    "a brush by population: the most representative filaments it runs",
                    [](auto& c) -> auto& { return brush_of(c).population_max_runs; }, brush));
  t.push_back(plain("compat.thesis_forces", "", one(boolean()),
                    "report the normal force as |lambda| |grad C| and friction as mu |lambda| |grad C|, as the thesis did",
                    [](auto& c) -> auto& { return c.contact.friction.thesis_forces; }));
  t.push_back(plain("compat.thesis_dcdt", "", one(boolean()), "in the corrector, dC/dt as the thesis's eqn 6.3",
                    [](auto& c) -> auto& { return c.simulation.thesis_dcdt; }));
  t.push_back(named<RestitutionSpeed>("compat.restitution_speed", {{"normal", RestitutionSpeed::normal}, {"full", RestitutionSpeed::full}},
                    "e from the normal approach speed (thesis text) or the full tip speed (its Appendix B)",
                    [](auto& c) -> auto& { return c.contact.impact.speed; }));
  // Plausible ranges: the wires, hubs and speeds of brushes, brush seals and rotating blades.
  const auto plausible = [&t](const std::string& name, double lo, double hi) {
    for (Key& k : t)
      if (k.name == name) {
        k.plausible_lo = lo, k.plausible_hi = hi;
        return;
      }
    throw std::logic_error("plausible range for " + name + ": no such key");
  };
  plausible("beam.length_m", 1e-3, 2.0);
  plausible("beam.diameter_m", 1e-5, 2e-2);
  plausible("hub.radius_m", 0.0, 2.0);
  plausible("beam.density_kg_m3", 500.0, 25000.0);
  plausible("beam.youngs_modulus_pa", 1e8, 1e12);
  plausible("hub.speed_rpm", 1e-3, 1e5);  // slow speeds are legitimate (a slow-motion study): only the top
  return t;
}

// "[lo, hi)" of a number form ("inf" for no upper end).
std::string range_text(const Form& f) {
  return std::string(f.lo_open ? "(" : "[") + format_number(f.lo) + ", " +
         (std::isinf(f.hi) ? std::string("inf") : format_number(f.hi)) + (f.hi_open ? ")" : "]");
}

std::string integer_text(double v) {
  if (v >= 18446744073709551615.0) return std::to_string(std::numeric_limits<std::uint64_t>::max());  // 2^64 − 1
  if (v >= 9223372036854775807.0) return std::to_string(static_cast<std::uint64_t>(v));
  return std::to_string(static_cast<std::int64_t>(v));
}

std::string quoted_words(const Form& f) {
  std::string list;
  for (const std::string& w : f.words) list += (list.empty() ? "\"" : ", \"") + w + "\"";
  return list;
}

// The refusal of a value of none of the forms' types (or a word not among the accepted).
std::string mismatch(const Check& check) {
  if (!check.mismatch.empty()) return check.mismatch;
  const Form& f = check.forms.front();
  switch (f.kind) {
    case Kind::number: return "must be a number";
    case Kind::integer: return "must be an integer";
    case Kind::boolean: return "must be true or false";
    case Kind::word: return "must be one of " + quoted_words(f);
    case Kind::numbers: return "must be an array of numbers";
  }
  return "";
}

bool has_type(const Form& f, const Value& v) {
  switch (f.kind) {
    case Kind::number: return v.is_number();
    case Kind::integer: return v.is_number_integer();
    case Kind::boolean: return v.is_boolean();
    case Kind::word: return v.is_string();
    case Kind::numbers: return v.is_array();
  }
  return false;
}

}  // namespace

const std::vector<Key>& key_table() {
  static const std::vector<Key> table = make_table();
  return table;
}

const Key* find_key(const std::string& name) {
  for (const Key& k : key_table())
    if (k.name == name) return &k;
  return nullptr;
}

const Config& defaults() {
  static const Config config = [] {
    Config c;
    c.brush.emplace();
    return c;
  }();
  return config;
}

std::optional<std::string> refusal(const Key& key, const Value& v) {
  const Check& check = key.check;
  const auto form = std::find_if(check.forms.begin(), check.forms.end(), [&](const Form& f) { return has_type(f, v); });
  if (form == check.forms.end()) return mismatch(check);
  const Form& f = *form;
  switch (f.kind) {
    case Kind::number: {
      const double x = v.get<double>();
      if (!std::isfinite(x)) return "must be finite";
      const bool ok = (f.lo_open ? x > f.lo : x >= f.lo) && (f.hi_open ? x < f.hi : x <= f.hi);
      if (!ok) return check.out_of_range.empty() ? "must be in " + range_text(f) : check.out_of_range;
      if (x > 0.0 && x < f.zero_or_at_least) return check.below_floor;
      return std::nullopt;
    }
    case Kind::integer: {
      // Beyond 2^63 − 1 an integer is unsigned (brush.seed takes every 64-bit seed): compared as such.
      const double x = v.is_number_unsigned() ? static_cast<double>(v.get<std::uint64_t>())
                                              : static_cast<double>(v.get<std::int64_t>());
      const bool inside = v.is_number_unsigned() ? x >= f.lo && x <= f.hi
                                                 : v.get<std::int64_t>() >= f.lo && v.get<std::int64_t>() <= f.hi;
      if (!inside)
        return check.out_of_range.empty() ? "must be in " + integer_text(f.lo) + ".." + integer_text(f.hi) : check.out_of_range;
      return std::nullopt;
    }
    case Kind::boolean: return std::nullopt;
    case Kind::word:
      if (std::find(f.words.begin(), f.words.end(), v.get<std::string>()) == f.words.end()) return mismatch(check);
      return std::nullopt;
    case Kind::numbers: {
      const std::string bound = format_number(f.hi);
      for (const Value& x : v) {
        if (!x.is_number()) return "must be an array of numbers";
        if (!std::isfinite(x.get<double>())) return "must hold finite numbers";
        if (std::abs(x.get<double>()) > f.hi) return "must hold numbers in [-" + bound + ", " + bound + "]";
      }
      for (const Value& x : v)
        if (x.get<double>() < f.lo) return "must hold numbers in [" + format_number(f.lo) + ", " + bound + "]";
      return std::nullopt;
    }
  }
  return std::nullopt;
}

std::string type_text(const Key& key) {
  std::string out;
  for (const Form& f : key.check.forms) {
    if (!out.empty()) out += " or ";
    switch (f.kind) {
      case Kind::number: out += "number"; break;
      case Kind::integer: out += "integer"; break;
      case Kind::boolean: out += "boolean"; break;
      case Kind::word: out += "string"; break;
      case Kind::numbers: out += "array of numbers"; break;
    }
  }
  return out;
}

std::string allowed_text(const Key& key) {
  // A refusal of its own says the range in words ("must be in 1..40 (1..80 with …)").
  const std::string& own = key.check.out_of_range;
  for (const char* lead : {"must be in ", "must be "})
    if (own.rfind(lead, 0) == 0) return own.substr(std::string(lead).size());
  std::string out;
  for (const Form& f : key.check.forms) {
    if (!out.empty()) out += " or ";
    switch (f.kind) {
      case Kind::number:
        out += f.zero_or_at_least > 0.0 ? "0 or [" + format_number(f.zero_or_at_least) + ", " + format_number(f.hi) + "]"
                                        : range_text(f);
        break;
      case Kind::integer: out += integer_text(f.lo) + ".." + integer_text(f.hi); break;
      case Kind::boolean: out += "true, false"; break;
      case Kind::word: out += quoted_words(f); break;
      case Kind::numbers: out += "numbers in [" + format_number(f.lo) + ", " + format_number(f.hi) + "]"; break;
    }
  }
  return out;
}

std::string format_number(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string render(const Value& v) {
  if (v.is_string()) {
    std::string quoted;
    for (char c : v.get<std::string>()) {
      if (c == '"' || c == '\\') quoted += '\\';
      quoted += c;
    }
    std::string s = printable(quoted);
    if (s.size() > 80) s = s.substr(0, 60) + "… (" + std::to_string(s.size()) + " characters)";
    return '"' + s + '"';
  }
  if (v.is_number_unsigned()) return std::to_string(v.get<std::uint64_t>());
  if (v.is_number_integer()) return std::to_string(v.get<std::int64_t>());
  if (v.is_number_float()) {
    const double x = v.get<double>();
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    std::string s = format_number(x);
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // a float written 5.0 is not the integer 5
    return s;
  }
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_array()) return render_list(v.size(), [&](std::size_t i) { return render(v[i]); });
  return "{…}";
}

std::string render_list(std::size_t size, const std::function<std::string(std::size_t)>& item) {
  // A long array is shown by its first values and its length, so a message stays one readable line.
  constexpr std::size_t kShown = 8;
  std::string out = "[";
  for (std::size_t i = 0; i < size && i < kShown; ++i) {
    if (i) out += ", ";
    out += item(i);
  }
  if (size > kShown) out += ", … (" + std::to_string(size) + " values)";
  return out + "]";
}

[[noreturn]] void refuse(const std::string& key, const std::string& shown, const std::string& why) {
  throw ConfigError(printable(key) + " = " + shown + ": " + why);
}

}  // namespace rotbeam::config_detail

namespace rotbeam {

using namespace config_detail;

nlohmann::json Config::to_json() const {
  nlohmann::json j = nlohmann::json::object();
  for (const Key& k : key_table()) {
    if (!k.written(*this)) continue;
    const auto dot = k.name.find('.');
    j[k.name.substr(0, dot)][k.name.substr(dot + 1)] = k.get(*this);
  }
  return j;
}

const std::vector<std::string>& config_keys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> names;
    for (const Key& k : key_table()) names.push_back(k.name);
    return names;
  }();
  return keys;
}

nlohmann::ordered_json describe_config_keys() {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const Key& k : key_table())
    out.push_back({{"name", k.name},
                   {"type", type_text(k)},
                   {"unit", k.unit},
                   {"default", nlohmann::ordered_json(k.get(defaults()))},
                   {"unset", k.unset.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(k.unset)},
                   {"allowed", allowed_text(k)},
                   {"doc", k.doc}});
  return out;
}

}  // namespace rotbeam
