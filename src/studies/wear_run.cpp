#include "rotbeam/wear_run.hpp"

#include "rotbeam/case.hpp"
#include "rotbeam/pass.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace rotbeam {

Config worn_config(const Config& base, double length_m) {
  Config c = base;
  const double L0 = base.beam.length_m;
  c.beam.length_m = length_m;
  if (base.surface.shape == SurfaceShape::casing) {
    // The casing's radius r_h + L + c0 stays: the clearance grows by what the filament lost.
    c.surface.clearance_m = base.surface.clearance_m + (L0 - length_m);
  } else {
    // The nearest distance d = r_h + L − pL stays: p' L' = p L − (L − L').
    c.surface.depth_fraction = (base.surface.depth_fraction * L0 - (L0 - length_m)) / length_m;
  }
  return revalidate(c);
}

namespace {

// A number as a message shows it: the shortest form that reads back ("-1", "0.0635").
std::string shown(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  for (int p = 1; p <= 17; ++p) {
    char shorter[32];
    std::snprintf(shorter, sizeof shorter, "%.*g", p, v);
    if (std::strtod(shorter, nullptr) == v) return shorter;
  }
  return buf;
}

double clock_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The shortest free length whose undeformed filament still reaches the surface of `base`, which stays
// in place: a plane or a cylinder while p L − (L0 − L) > 0; a casing while its deepest clearance
// c0 + (L0 − L) − A (2A under the benchmark's law) stays below 0.
double shortest_reaching_length(const Config& base) {
  const SurfaceParameters& sp = base.surface;
  if (sp.shape == SurfaceShape::casing) {
    const double deepest = sp.clearance_m - (sp.lobe_law == "benchmark" ? 2.0 : 1.0) * (sp.lobes ? sp.lobe_amplitude_m : 0.0);
    return base.beam.length_m + deepest;
  }
  return base.beam.length_m * (1.0 - sp.depth_fraction);
}

}  // namespace

WearRun run_wear(const Config& config, const WearRunOptions& o) {
  if (config.brush) throw ConfigError("brush.*: `rotbeam wear` runs one filament; give a configuration without [brush]");
  if (!(o.hours > 0) || !std::isfinite(o.hours))
    throw ConfigError("--hours " + shown(o.hours) + ": must be a positive number of hours");
  if (o.steps < 1 || o.steps > 100000) throw ConfigError("--steps " + std::to_string(o.steps) + ": must be 1 … 100000");
  Config base = config;
  base.simulation.until_steady = true;
  if (base.simulation.revolutions <= 0) base.simulation.revolutions = kDefaultSteadyRevolutionCap;
  base.simulation.multipliers = false;
  base.simulation.output_interval_s = 1e30;  // no history rows are kept
  base.simulation.near_surface_gap_m = 0.0;
  base = revalidate(base);

  WearRun run;
  const double rev_per_hour = 60.0 * base.beam.speed_rpm;
  const double rev_period_s = 60.0 / base.beam.speed_rpm;
  const double dt_h = o.hours / o.steps;
  std::vector<std::vector<WearBin>> profiles;
  std::vector<double> weights;
  double length = base.beam.length_m, time_h = 0;
  const double reach = shortest_reaching_length(base);
  const bool spinning = base.surface.shape == SurfaceShape::cylinder && base.surface.speed_rpm != 0.0;
  for (int k = 0; k <= o.steps; ++k) {
    WearStep s;
    s.step = k;
    s.time_h = time_h;
    s.duration_h = k < o.steps ? dt_h : 0.0;
    s.length_m = length;
    if (o.on_step) o.on_step(k, o.steps, length);
    if (o.stop && o.stop->stop_requested()) {
      s.ran = false;
      run.stopped_early = true;
      run.note = "stopped on request at " + shown(s.time_h) + " h";
      break;
    }
    if (!(length > reach)) {
      s.reaches = false;
      run.steps.push_back(s);
      run.stopped_early = true;
      run.note = "the filament no longer reaches the surface at L = " + shown(length) + " m after " +
                 shown(s.time_h) + " h: wear stops";
      break;
    }
    const double start = clock_s();
    Config c;
    try {
      c = worn_config(base, length);
    } catch (const ConfigError& e) {
      s.reaches = false;
      run.steps.push_back(s);
      run.stopped_early = true;
      run.note = "the worn filament (L = " + shown(length) + " m) is no longer a case the model builds (" + e.what() +
                 ") after " + shown(s.time_h) + " h: wear stops";
      break;
    }
    const Case cs = build_case(c);
    const PassResult r = run_case(cs, {nullptr, o.stop, {}});
    s.wall_time_s = clock_s() - start;
    if (r.failure) {
      s.ran = false;
      run.steps.push_back(s);
      run.failure = r.failure;
      run.stopped_early = true;
      run.note = "the steady-state run at L = " + shown(length) + " m failed: " + r.failure->message;
      break;
    }
    const WearReport w = wear_report(r, c.wear, *cs.surface, c.beam.diameter_m, c.simulation.wear_profile_bins);
    if (run.steps.empty()) {
      run.coordinate = w.coordinate;
      run.track_width_m = w.track_width_m;
    }
    const SteadyState& st = r.summary.steady_state;
    s.steady = st.reached;
    s.period_revolutions = st.reached ? st.period_revolutions : 0;
    s.revolutions_run = r.summary.revolutions;
    s.per_revolution = w.amounts;
    s.profile = spinning ? spread_around(w.profile, c.simulation.wear_profile_bins, w.coordinate.period) : w.profile;
    // The orbit's mean per revolution of the impacts, the normal impulse and the hub's work; its
    // section distance over its period (the steady test's measure).
    const int m = std::max(w.revolutions, 1);
    const std::size_t kept = r.revolutions.size();
    s.section_distance = kept > static_cast<std::size_t>(m)
                             ? section_distance(section_state(*cs.beam, r.revolutions[kept - 1].q, r.revolutions[kept - 1].qd),
                                                section_state(*cs.beam, r.revolutions[kept - 1 - m].q,
                                                              r.revolutions[kept - 1 - m].qd))
                             : st.final_distance;
    double impacts = 0;
    double normal = 0, hub = 0;
    for (int j = 0; j < m && j < static_cast<int>(r.revolutions.size()); ++j) {
      const RevolutionRecord& rev = r.revolutions[r.revolutions.size() - 1 - j];
      impacts += rev.impacts;
      normal += rev.ledger[LedgerTerm::normal_impulse];
      hub += rev.ledger[LedgerTerm::hub_work];
    }
    s.impacts_per_revolution = impacts / m;
    s.ran = true;
    s.mean_normal_force_n = normal / m / rev_period_s;
    s.mean_hub_power_w = hub / m / rev_period_s;
    s.mean_hub_torque_n_m = s.mean_hub_power_w / (2.0 * M_PI / rev_period_s);
    s.removal_rate_m3_h = w.amounts.surface_volume_m3 * rev_per_hour;
    s.length_rate_m_h = w.amounts.filament_length_m * rev_per_hour;
    s.heat_rate_w = w.amounts.heat_j / rev_period_s;
    s.length_lost_m = s.length_rate_m_h * s.duration_h;
    // A step that would wear the filament past its reach wears only until then (at the step's rate).
    if (s.length_lost_m > length - reach) {
      const double share = (length - reach) / s.length_lost_m;
      s.duration_h *= share;
      s.length_lost_m = length - reach;
    }
    // Explicit Euler holds the step's rates: a step that uses up much of what is left of the reach
    // changes the contact within it, and is said to be too long.
    if (s.length_lost_m > 0.1 * (length - reach) && run.warnings.size() < 5)
      run.warnings.push_back("step " + std::to_string(k) + " wore " + shown(s.length_lost_m) + " m of the " +
                             shown(length - reach) + " m left before the filament stops reaching: give more --steps");
    s.volume_removed_m3 = s.removal_rate_m3_h * s.duration_h;
    if (s.duration_h > 0.0 && !s.profile.empty()) {
      profiles.push_back(s.profile);
      weights.push_back(rev_per_hour * s.duration_h);
    }
    run.length_lost_m += s.length_lost_m;
    run.volume_removed_m3 += s.volume_removed_m3;
    run.heat_j += s.heat_rate_w * s.duration_h * 3600.0;
    run.steps.push_back(s);
    if (k < o.steps && w.amounts.sliding_load_n_m <= 0.0) {
      run.stopped_early = true;
      run.note = "the filament no longer touches the surface at L = " + shown(length) + " m after " +
                 shown(s.time_h) + " h: wear stops";
      break;
    }
    length -= s.length_lost_m;
    time_h += s.duration_h;
  }
  if (!profiles.empty()) run.removed_profile = rebin(profiles, weights, base.simulation.wear_profile_bins, run.coordinate.period);
  return run;
}

}  // namespace rotbeam
