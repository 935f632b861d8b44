#include "rotbeam/case.hpp"
#include "rotbeam/beam_factory.hpp"
#include "rotbeam/contact_laws.hpp"
#include "rotbeam/modal_analysis.hpp"
#include "rotbeam/steady_state.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace rotbeam {

Case build_case(const Config& config) {
  if (config.brush)
    throw ConfigError("brush: this configuration describes a brush ([brush]), which runs as a whole "
                      "(rotbeam brush, rotbeam.brush), not as one filament's pass");
  Case c;
  try {
    auto beam = make_beam_model(config.beam);
    c.surface = make_surface(config.surface, *beam);
    c.beam = std::move(beam);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(e.what());
  }
  c.law = make_contact_law(config.contact, config.beam.youngs_modulus_pa, config.beam.diameter_m);
  c.options = config.simulation;
  c.options.wear_point_span_m = config.beam.diameter_m;
  // The bending modes from initial.*; the coordinates beyond them (an extensible filament's stretch)
  // at the filament's rest state.
  const int n = config.beam.modes;
  c.initial.rigid_start = config.initial.start == "rigid";
  c.initial.q0 = Eigen::VectorXd::Zero(c.beam->modes());
  c.beam->rest_state(c.initial.q0);
  c.initial.qd0 = Eigen::VectorXd::Zero(c.beam->modes());
  for (int i = 0; i < n && i < static_cast<int>(config.initial.modal_displacement.size()); ++i)
    c.initial.q0[i] = config.initial.modal_displacement[i];
  for (int i = 0; i < n && i < static_cast<int>(config.initial.modal_velocity.size()); ++i)
    c.initial.qd0[i] = config.initial.modal_velocity[i];
  return c;
}

PassResult run_case(const Case& c, const PassControl& control) {
  PassResult r = run_to_steady_state(c.system(), c.initial, c.options, control);
  r.summary.natural_frequencies_hz = natural_frequencies_hz(*c.beam);
  return r;
}

FirstImpactResult run_first_impact(const Case& c, const PassControl& control) {
  // The first impact is the rigid law's momentum balance at the first touch; a compliant contact has
  // none (it is a force over time, resolved by a pass).
  if (c.law->kind(Phase::contact) == PhaseKind::force)
    throw ConfigError(std::string("contact.model = \"") + c.law->name() +
                      "\": the first impact is the rigid law's momentum balance; a compliant contact is resolved in "
                      "time: run the case (`rotbeam run`: its first contact_start and contact_end events)");
  return first_impact(c.system(), c.initial, c.options.end_angle_deg, c.options.free_step_s, control);
}

HistoryEstimate estimate_history(const Case& c) {
  HistoryEstimate e;
  const PassOptions& o = c.options;
  // Rows at every step (everywhere, or near the surface) depend on the steps: unknown.
  if (!(o.output_interval_s > 0.0)) return e;
  if (o.near_surface_gap_m > 0.0 && !(o.near_surface_interval_s > 0.0)) return e;
  const BeamModel& beam = *c.beam;
  const double omega = beam.hub_motion().omega;
  double span_s, rigid_rows = 0.0, passes = 1.0;
  if (o.revolutions > 0) {
    const int kept = o.history_revolutions > 0 ? std::min(o.history_revolutions, o.revolutions) : o.revolutions;
    span_s = kept * 2.0 * M_PI / omega;
    passes = kept;
    e.upper_bound = o.until_steady;
  } else {
    e.upper_bound = o.end_when_clear;  // the pass may end once the tip cannot touch again
    double start_s = 0.0;
    if (c.initial.rigid_start) {
      const double theta_star = c.surface->first_contact_angle(beam.tip_radius(), beam.theta(0.0));
      if (std::isfinite(theta_star)) start_s = beam.time_at(theta_star);
      // The rigid turn: a row every interval or 0.1°, whichever is longer.
      rigid_rows = start_s / std::max(o.output_interval_s, 0.1 * M_PI / 180.0 / omega);
    }
    span_s = std::max(0.0, beam.time_at(o.end_angle_deg * M_PI / 180.0) - start_s);
  }
  // Near the surface the rows come every near_surface_interval_s: over about the stretch where the
  // undeformed tip is within near_surface_gap_m of the surface, once per pass or kept revolution
  // (the flexible tip's stretch differs by its bounce and rub: the estimate is 0.89–1.20 of the
  // rows written on the cases of PassFiles.TheHistoryEstimateMatchesWhatARunWrites).
  double near_rows = 0.0;
  if (o.near_surface_gap_m > 0.0 && o.near_surface_interval_s > 0.0 && o.near_surface_interval_s < o.output_interval_s) {
    const double entry = c.surface->first_contact_angle(beam.tip_radius() + o.near_surface_gap_m, beam.theta(0.0));
    if (std::isfinite(entry)) {
      const double stretch_s = 2.0 * std::abs(std::remainder(c.surface->deepest_angle() - entry, 2.0 * M_PI)) / omega;
      near_rows = passes * stretch_s * (1.0 / o.near_surface_interval_s - 1.0 / o.output_interval_s);
    }
  }
  const double n = beam.modes();
  e.known = true;
  e.rows = span_s / o.output_interval_s + 1.0 + rigid_rows + near_rows;
  if (near_rows > 0.5 * e.rows) e.sampling_key = "output.near_surface_interval_s";
  // Bytes per row with the shortest round-trip decimals (std::to_chars): a number takes about 20.4
  // characters with its comma (fitted on the base case), an exact zero 2, the phase 5. A row of the
  // flexible motion has 9 + 2n numbers and, in free flight, F_n, F_t and λ at zero; a rigid-turn row
  // has 8 numbers and 4 + 2n zeros (q = q̇ = 0). Measured against written files: 0.96 (base case),
  // 0.88 (3000 rpm), 0.98 (8 modes, rows every 1 µs).
  constexpr double kNumber = 20.4, kZero = 2.0, kPhase = 5.0;
  const double flexible_row = kPhase + (9.0 + 2.0 * n) * kNumber + 3.0 * kZero;
  const double rigid_row = kPhase + 8.0 * kNumber + (4.0 + 2.0 * n) * kZero;
  e.csv_bytes = (e.rows - rigid_rows) * flexible_row + rigid_rows * rigid_row;
  // A HistoryRow with its two vectors' heap blocks, and the arrays handed to Python.
  e.memory_bytes = e.rows * (sizeof(HistoryRow) + 2.0 * (8.0 * n + 32.0) + 8.0 * (13.0 + 2.0 * n));
  const double longest_step =
      o.scheme == Scheme::thesis ? std::max(o.free_step_s, o.contact_step_s) : o.max_step_s;
  e.min_rows = span_s / (o.output_interval_s + longest_step) + rigid_rows;
  e.min_csv_bytes = e.csv_bytes * e.min_rows / e.rows;
  e.min_memory_bytes = e.memory_bytes * e.min_rows / e.rows;
  return e;
}

namespace {
StepEstimate estimate_step_count(const Case& c);

// The time of one evaluation of the beam's dynamics [s] at the case's start state, the median of
// three timings of a batch (a batch lasts about 0.2 ms: the whole costs about a millisecond).
double evaluation_time_s(const Case& c) {
  const BeamModel& beam = *c.beam;
  const auto ws = beam.make_workspace();
  const int n = beam.modes();
  const Eigen::VectorXd q = c.initial.q0.size() == n ? c.initial.q0 : Eigen::VectorXd::Zero(n);
  const Eigen::VectorXd qd = c.initial.qd0.size() == n ? c.initial.qd0 : Eigen::VectorXd::Zero(n);
  using clock = std::chrono::steady_clock;
  const auto seconds = [](clock::duration d) { return std::chrono::duration<double>(d).count(); };
  int batch = 1;
  for (;;) {  // a batch long enough for the clock
    const auto t0 = clock::now();
    for (int i = 0; i < batch; ++i) beam.evaluate_dynamics(q, qd, *ws);
    if (seconds(clock::now() - t0) > 2e-4 || batch >= (1 << 16)) break;
    batch *= 4;
  }
  std::array<double, 3> times{};
  for (double& t : times) {
    const auto t0 = clock::now();
    for (int i = 0; i < batch; ++i) beam.evaluate_dynamics(q, qd, *ws);
    t = seconds(clock::now() - t0) / batch;
  }
  std::nth_element(times.begin(), times.begin() + 1, times.end());
  return times[1];
}
}  // namespace

StepEstimate estimate_steps(const Case& c) {
  StepEstimate e = estimate_step_count(c);
  e.evaluation_s = evaluation_time_s(c);
  e.wall_s = e.steps * (c.options.scheme == Scheme::adaptive ? 7.0 : 6.0) * e.evaluation_s;
  return e;
}

namespace {
// The steps and the key that sets most of them (estimate_steps).
StepEstimate estimate_step_count(const Case& c) {
  const PassOptions& o = c.options;
  const BeamModel& beam = *c.beam;
  const double omega = beam.hub_motion().omega;
  // The integrated time: every revolution, or from the start of the flexible motion (the first
  // contact of a rigid start, whose turn up to it is not integrated) to the end angle.
  double span_s, passes = 1.0;
  const double theta_star = c.surface->first_contact_angle(beam.tip_radius(), beam.theta(0.0));
  if (o.revolutions > 0) {
    span_s = o.revolutions * 2.0 * M_PI / omega;
    passes = o.revolutions;
  } else {
    const double start_s = c.initial.rigid_start && std::isfinite(theta_star) ? beam.time_at(theta_star) : 0.0;
    span_s = std::max(0.0, beam.time_at(o.end_angle_deg * M_PI / 180.0) - start_s);
  }
  StepEstimate e;
  if (o.scheme == Scheme::adaptive) {
    e = {span_s / o.max_step_s, true, "simulation.max_step_s", o.max_step_s, span_s, "motion"};
    return e;
  }
  double contact_s = 0.0;
  if (std::isfinite(theta_star))
    contact_s = std::min(span_s, passes * 2.0 * std::abs(std::remainder(c.surface->deepest_angle() - theta_star, 2.0 * M_PI)) / omega);
  const bool fine = o.fine_below_n > 0.0 && o.fine_contact_step_s < o.contact_step_s;
  const double contact_step = fine ? o.fine_contact_step_s : o.contact_step_s;
  const double free_steps = (span_s - contact_s) / o.free_step_s, contact_steps = contact_s / contact_step;
  e.steps = free_steps + contact_steps;
  if (contact_steps > free_steps) {
    e.key = fine ? "simulation.fine_contact_step_s" : "simulation.contact_step_s";
    e.step_s = contact_step;
    e.governed_s = contact_s;
    e.governed = "contact";
  } else {
    e.key = "simulation.free_step_s";
    e.step_s = o.free_step_s;
    e.governed_s = span_s - contact_s;
    e.governed = "flight";
  }
  return e;
}
}  // namespace

std::string size_text(double bytes) {
  static const char* const units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (bytes >= 1000.0 && u < 6) {
    bytes /= 1000.0;
    ++u;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, bytes < 10.0 && u > 0 ? "%.1f %s" : "%.0f %s", bytes, units[u]);
  return buf;
}

HistoryEstimate check_history_fits(const Case& c, double available_bytes, bool in_memory) {
  const HistoryEstimate e = estimate_history(c);
  // The central estimate is what the run is told it will write: the check compares the same number
  // (the lower bound let a run announced at 121 GB start on a disk with 74 GB free).
  const double need = in_memory ? e.memory_bytes : e.csv_bytes;
  if (e.known && !e.upper_bound && available_bytes > 0 && need > available_bytes) {
    char rows[32];
    std::snprintf(rows, sizeof rows, "%.3g", e.rows);
    char interval[32];
    std::snprintf(interval, sizeof interval, "%g", c.options.output_interval_s);
    throw ConfigError(std::string("output.interval_s = ") + interval + ": the history would hold about " + rows + " rows, " +
                      (in_memory ? "about " + size_text(need) + " of memory, more than the " + size_text(available_bytes) +
                                       " available (run it with `rotbeam run -o DIR`, which streams to disk, or sample less often)"
                                 : "about " + size_text(need) + " in history.csv, more than the " +
                                       size_text(available_bytes) + " free there (sample less often)"));
  }
  return e;
}

}  // namespace rotbeam
