// `rotbeam continue`: a filament's periodic orbits followed in one configuration key, with their
// stability and the bifurcations met (docs/continuation.md).
#include "commands.hpp"
#include "common.hpp"

#include "rotbeam/continuation_output.hpp"
#include "rotbeam/job_runner.hpp"
#include "rotbeam/orbit_continuation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <unistd.h>

namespace rotbeam::cli {

namespace {

struct ContinueCommandOptions {
  CaseOptions case_options;
  std::string output_dir;
  std::string parameter;
  double from = NAN, to = NAN;
  int period = 0;
  double tolerance = 0;
  double step = 0.02, max_step = 0.1;
  int max_points = 400;
  bool no_doubling = false;
  int jobs = 0;
  bool json = false;
  bool quiet = false;
};

void print_summary(const OrbitContinuation& run, const std::string& dir) {
  const ContinuationResult& r = run.result;
  const std::string& key = run.options.parameter;
  std::cout << "Continuation of the period-" << run.period << " orbit in " << key << " from "
            << given_text(run.options.from) << " to " << given_text(run.options.to) << ", " << run.modes
            << (run.modes == 1 ? " mode" : " modes") << "\n";
  std::cout << "  start                 " << run.start_note << "\n";
  for (const BranchSummary& b : r.branches) {
    double lo = INFINITY, hi = -INFINITY;
    int stable = 0;
    for (const BranchPoint& p : r.points)
      if (p.branch == b.branch) lo = std::min(lo, p.parameter), hi = std::max(hi, p.parameter), stable += p.stable;
    std::cout << "  branch " << b.branch << " (period " << b.period << ")  " << b.points << " points";
    if (b.points > 0) std::cout << " over " << key << " " << number_text(lo) << " … " << number_text(hi) << ", " << stable << " stable";
    std::cout << "; " << (b.branch > 0 ? b.start + "; " : std::string()) << b.end << "\n";
  }
  for (const SpecialPoint& s : r.special)
    std::cout << "  " << special_kind_name(s.kind) << " at " << key << " ≈ " << number_text(s.parameter) << " (branch "
              << s.branch << "): " << s.note << "\n";
  std::cout << "  map evaluations       " << r.map_evaluations << " (" << r.revolutions << " revolutions), "
            << fixed(run.wall_time_s, 1) << " s\n";
  std::cout << "  wrote " << (std::filesystem::path(dir) / "branch.csv").string()
            << ", summary.json (pictures: rotbeam plot " << dir << ")\n";
}

int run_continue_command(const ContinueCommandOptions& o) {
  const Config base = o.case_options.load_filament("continue");
  (void)base;
  if (!(o.step >= ContinuationSettings{}.min_step) || !(o.max_step >= o.step) || !std::isfinite(o.max_step))
    throw ConfigError("--step " + number_text(o.step) + " --max-step " + number_text(o.max_step) + ": must be at least " +
                      number_text(ContinuationSettings{}.min_step) + " with --max-step ≥ --step");
  if (o.max_points < 2 || o.max_points > 100000)
    throw ConfigError("--max-points " + std::to_string(o.max_points) + ": must be 2 … 100000");
  if (o.tolerance < 0 || !std::isfinite(o.tolerance))
    throw ConfigError("--tolerance " + number_text(o.tolerance) + ": must be a positive number (0: simulation.steady_tolerance)");
  OrbitContinuationOptions options;
  options.parameter = o.parameter;
  options.from = o.from;
  options.to = o.to;
  options.period = o.period;
  options.tolerance = o.tolerance;
  options.settings.initial_step = o.step;
  options.settings.max_step = o.max_step;
  options.settings.max_points = o.max_points;
  options.settings.switch_period_doubling = !o.no_doubling;
  options.settings.threads = default_threads(o.jobs);
  const CaseOptions& co = o.case_options;
  const ConfigAtValue config_at = [&co, &o](const std::string& literal) {
    std::vector<std::string> overrides = co.overrides;
    overrides.push_back(o.parameter + "=" + literal);
    return load_config(co.config_path, overrides);
  };
  // The key and the range are checked before the folder is touched.
  check_orbit_continuation(config_at, options);
  std::unique_ptr<ContinuationFiles> files;
  try {
    files = std::make_unique<ContinuationFiles>(o.output_dir);
  } catch (const std::exception& e) {
    throw ConfigError(std::string("-o ") + e.what());
  }
  install_interrupt_handlers();
  options.settings.stop = &interrupt_token();
  auto line = std::make_unique<LiveLine>(!o.quiet && isatty(STDERR_FILENO));
  line->set([](double e) { return "seeking the steady state at the start, " + fixed(e, 0) + " s elapsed"; });
  const std::string key = o.parameter;
  const OrbitContinuation run = continue_orbits(config_at, options, [&line, key](const ContinuationProgress& p) {
    line->set([=](double e) {
      return "branch " + std::to_string(p.branch) + ", point " + std::to_string(p.points) + ": " + key + " = " +
             number_text(p.parameter) + " (" + fixed(100.0 * std::clamp(p.u, 0.0, 1.0), 0) + " % of the range), " +
             (p.stable ? "stable" : "unstable") + ", " + std::to_string(p.map_evaluations) + " map evaluations, " +
             fixed(e, 0) + " s elapsed";
    });
  });
  line.reset();
  files->commit(run);
  if (o.json) std::cout << continuation_json(run).dump(2) << "\n";
  else print_summary(run, o.output_dir);
  if (run.result.stopped || interrupt_token().stop_requested()) {
    print_error("interrupted: the files in " + o.output_dir + " hold the points found");
    return kInterrupted;
  }
  if (run.result.failure) {
    const NumericalFailure& f = *run.result.failure;
    print_error(std::string("the continuation stopped short: an evaluation of the orbit's map failed (") + failure_name(f.kind) +
                ": " + f.message + "); the files in " + o.output_dir + " hold the points before it");
    return exit_code_for_failure(f.kind);
  }
  if (run.result.points.empty()) {
    print_error("no periodic orbit to continue: " + (run.result.branches.empty() ? std::string() : run.result.branches.front().end));
    return kRuntimeFailure;
  }
  return kSuccess;
}

}  // namespace

Command add_continue_command(CLI::App& app) {
  auto opts = std::make_shared<ContinueCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "continue", "Follow a filament's periodic orbit in one key: stability, folds, period doublings, grazing");
  opts->case_options.add_to(*sub);
  sub->add_option("--parameter", opts->parameter, "The configuration key to continue in (e.g. hub.speed_rpm)")->required();
  sub->add_option("--from", opts->from, "Its first value (the orbit is found there)")->required();
  sub->add_option("--to", opts->to, "Its last value")->required();
  sub->add_option("--period", opts->period, "Revolutions per orbit (default: the steady state's at --from)");
  sub->add_option("-o,--output", opts->output_dir, "Output folder (created if needed)")->required()->check(non_empty_path());
  sub->add_option("--tolerance", opts->tolerance, "Relative residual of a point (default: simulation.steady_tolerance)");
  sub->add_option("--step", opts->step, "First step along the branch, in the range's fraction (default 0.02)");
  sub->add_option("--max-step", opts->max_step, "Largest step (default 0.1)");
  sub->add_option("--max-points", opts->max_points, "Points per branch at most (default 400)");
  sub->add_flag("--no-doubling", opts->no_doubling, "Do not follow the doubled branch from a period doubling");
  sub->add_option("-j,--jobs", opts->jobs, "Threads for the Jacobian's map evaluations (default: all cores)");
  sub->add_flag("--json", opts->json, "Print summary.json instead of the human summary");
  sub->add_flag("--quiet", opts->quiet, "No progress line on stderr");
  return [opts] { return run_continue_command(*opts); };
}

}  // namespace rotbeam::cli
