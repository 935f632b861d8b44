// `rotbeam run`: a whole pass through contact (docs/model.md §6, §7, §9).
#include "commands.hpp"
#include "common.hpp"

#include "rotbeam/case.hpp"
#include "rotbeam/detail/diagnostics.hpp"
#include "rotbeam/pass_output.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

namespace rotbeam::cli {

namespace {

struct RunOptions {
  CaseOptions case_options;
  std::string output_dir;
  bool json = false;
  bool quiet = false;
};

void print_summary(const Config& config, const PassResult& r, const std::string& dir) {
  const PassSummary& s = r.summary;
  std::cout << "Pass: " << given_text(config.beam.speed_rpm) << " rpm, "
            << surface_text(config) << ", μ = " << given_text(config.contact.friction.mu) << ", "
            << modes_text(config) << ", " << config.initial.start << " start, " << scheme_name(s.scheme)
            << " scheme\n";
  // A pass that stopped says so first: `run > summary.txt` kept a complete-looking summary of a
  // partial pass, the failure being on stderr only.
  if (r.failure) {
    const std::string where = "at t = " + number_text(r.failure->t) + " s, θ = " +
                              fixed(r.failure->theta * 180.0 / M_PI, 4) + " deg";
    if (r.failure->kind == FailureKind::interrupted)
      std::cout << "  INTERRUPTED           " << where << " (exit " << exit_code_for_failure(r.failure->kind)
                << "): what follows covers the pass up to there\n";
    else
      std::cout << "  STOPPED               " << where << ": numerical failure (" << failure_name(r.failure->kind)
                << ", exit " << exit_code_for_failure(r.failure->kind) << "): what follows covers the pass up to there\n";
  }
  std::cout << "  impacts               " << s.impacts << " (" << s.plastic_impacts << " plastic)\n";
  std::cout << "  contact episodes      " << s.contact_episodes << ", " << fixed(s.contact_time_s * 1e3, 4)
            << " ms in contact\n";
  if (s.impacts > 0 || s.contact_episodes > 0)
    std::cout << "  contact span          θ from " << fixed(s.first_impact_deg, 3) << "° (first touch) to "
              << fixed(s.last_separation_deg, 3) << "° (last separation)\n";
  else
    std::cout << "  contact span          none: the tip never reached the surface\n";
  if (std::isfinite(s.ended_clear_deg))
    std::cout << "  ended early           at θ = " << fixed(s.ended_clear_deg, 3)
              << "°: the tip cannot reach the surface again before the end angle (simulation.end_when_clear)\n";
  if (s.contact_episodes > 0 || s.contact_time_s > 0)
    std::cout << "  peak normal force     " << fixed(s.peak_normal_force_n, 4) << " N (mean in contact "
              << fixed(s.mean_normal_force_n, 4) << " N)\n";
  else if (s.impacts > 0)
    std::cout << "  peak normal force     none at any instant: no sustained contact, the pass is " << s.impacts
              << (s.impacts == 1 ? " impact" : " impacts") << "\n";
  if (!r.force_bins.empty())
    std::cout << "  binned force          peak " << fixed(s.binned_force.peak_normal_force_n, 4) << " N normal, "
              << fixed(s.binned_force.peak_tangential_force_n, 4) << " N tangential (momentum per "
              << number_text(s.binned_force.bin_deg) << "° bin of hub angle, impacts included"
              << (config.simulation.revolutions > 0 ? ", last complete revolution" : "") << "; force_bins.csv)\n";
  std::cout << "  normal impulse        " << s.ledger[LedgerTerm::normal_impulse] * 1e3 << " mN s\n";
  std::cout << "  friction work         " << s.ledger[LedgerTerm::friction_work] * 1e3 << " mJ\n";
  if (s.ledger[LedgerTerm::surface_work] != 0.0)
    std::cout << "  surface work          " << s.ledger[LedgerTerm::surface_work] * 1e3 << " mJ (the spinning workpiece's, through friction)\n";
  std::cout << "  max |y_t|/L           " << fixed(s.max_tip_deflection_ratio, 4) << "\n";
  // "edge" is said by its warning below; "outside" here, in words that cannot be missed.
  if (s.validity == Validity::outside)
    std::cout << "  validity              OUTSIDE THE MODEL: "
              << (s.left_geometry ? "the tip went farther from its clamp than the filament's length"
                                  : "max |y_t|/L above " + detail::short_number(kOutsideDeflectionRatio) +
                                        ", where the foreshortening's tip is 0.01 L or more from the exact one")
              << "; these results are not physical (beam.theory = \"elastica\" is exact)\n";
  std::cout << "  energy audit residual " << s.energy_audit_residual << "\n";
  std::cout << "  steps                 " << s.steps << " (" << s.rhs_evaluations << " RHS evaluations), "
            << fixed(s.wall_time_s, 3) << " s\n";
  if (config.simulation.revolutions > 0) {
    if (s.steady_state.method == SteadyMethod::shooting && s.steady_state.map_evaluations > 0)
      std::cout << "  revolutions           " << s.revolutions
                << " written: the orbit, run from the "
                << (s.steady_state.reached ? "state the shooting converged to" : "best state the shooting found") << "\n";
    else
      std::cout << "  revolutions           " << s.revolutions << " complete of " << config.simulation.revolutions << "\n";
    if (std::isfinite(s.mean_hub_torque_n_m))
      std::cout << "  last revolution       mean hub torque " << s.mean_hub_torque_n_m * 1e3 << " mN m, mean power "
                << s.mean_hub_power_w * 1e3 << " mW\n";
    if (s.steady_state.sought) std::cout << "  steady state          " << s.steady_state.note << "\n";
  }
  for (const std::string& w : s.warnings) std::cout << "  warning: " << w << "\n";
  std::cout << "  wrote " << path_text((std::filesystem::path(dir) / "history.csv").string()) << ", events.csv, "
            << (std::filesystem::exists(std::filesystem::path(dir) / "revolutions.csv") ? "revolutions.csv, " : "")
            << "force_bins.csv, wear_profile.csv, summary.json\n";
}

// Passes estimated above this many steps are announced: a step costs a few microseconds at 5 modes
// (six or seven evaluations of q̈ at 0.6 µs, docs/performance.md; 3.7 µs measured), more with more
// modes, so an hour and more.
constexpr double kLongPassSteps = 1e9;
// Passes estimated to take longer than this [s] (of wall time) are announced too.
constexpr double kLongPassSeconds = 10.0;

int run_pass_command(const RunOptions& o) {
  const Config config = o.case_options.load_filament("run");
  if (o.output_dir.empty()) throw ConfigError("-o DIR: an output folder is required");
  const Case c = build_case(config);  // before the folder is touched: bad input leaves nothing behind
  // history.csv must fit on the disk it goes to.
  const HistoryEstimate estimate = check_history_fits(c, available_disk_bytes(o.output_dir), false);
  if (estimate.known && estimate.csv_bytes > 1e9 && !o.quiet)
    std::cerr << "rotbeam: note: history.csv will take " << (estimate.upper_bound ? "up to " : "about ")
              << size_text(estimate.csv_bytes) << " (" << estimate.sampling_key << " sets its sampling)" << std::endl;
  // The step keys' ranges cannot bound a pass's cost (config.cpp): a long one is said before it starts.
  const StepEstimate steps = estimate_steps(c);
  if (steps.steps > kLongPassSteps && !o.quiet) {
    char count[32], span[32];
    std::snprintf(count, sizeof count, "%.3g", steps.steps);
    std::snprintf(span, sizeof span, "%.3g", steps.governed_s);
    std::cerr << "rotbeam: note: " << steps.key << " = " << number_text(steps.step_s) << ": the pass "
              << (steps.at_least ? "takes at least " : "may take up to about ") << count << " steps (" << span << " s of "
              << steps.governed << " in steps of " << (steps.at_least ? "at most " : "") << number_text(steps.step_s)
              << " s), hours at a few microseconds a step" << std::endl;
  } else if (steps.at_least && steps.wall_s > kLongPassSeconds && !o.quiet) {
    // Steps that are each long (many modes, the elastica): the time, from an evaluation timed here.
    // Only a lower bound is announced: the thesis scheme's upper bound assumes the whole contact
    // stretch in contact steps, which a bounce or a failure cuts short.
    char count[32], each[32];
    std::snprintf(count, sizeof count, "%.3g", steps.steps);
    std::snprintf(each, sizeof each, "%.3g", steps.wall_s / steps.steps * 1e3);
    std::cerr << "rotbeam: note: the pass takes at least " << count << " steps of about " << each << " ms each ("
              << config.beam.modes << " modes, beam.theory = \"" << beam_theory_name(config.beam.theory) << "\"), at least "
              << duration_text(steps.wall_s) << std::endl;
  }
  std::unique_ptr<PassFiles> files_owner;
  try {
    files_owner = std::make_unique<PassFiles>(o.output_dir, coordinate_count(config.beam), config.simulation.history_revolutions);
  } catch (const std::exception& e) {
    throw ConfigError(std::string("-o ") + e.what());
  }
  PassFiles& files = *files_owner;
  install_interrupt_handlers();
  PassResult r;
  {
    PassProgressLine progress(o.quiet);
    r = run_case(c, {&files, &interrupt_token(), progress.callback()});
  }
  files.commit(r, config, *c.surface);
  if (o.json)
    std::cout << summary_json(r, config, *c.surface).dump(2) << "\n";
  else
    print_summary(config, r, o.output_dir);
  if (r.failure) {
    const bool interrupted = r.failure->kind == FailureKind::interrupted;
    const std::string where = " at t = " + number_text(r.failure->t) + " s, θ = " +
                              fixed(r.failure->theta * 180.0 / M_PI, 4) + " deg";
    if (interrupted)
      print_error("interrupted" + where + "; results up to there are in " + o.output_dir);
    else
      print_error(std::string("numerical failure (") + failure_name(r.failure->kind) + ")" + where + ": " +
                  r.failure->message + "; results up to there are in " + o.output_dir);
    return exit_code_for_failure(r.failure->kind);
  }
  return kSuccess;
}

}  // namespace

Command add_run_command(CLI::App& app) {
  auto opts = std::make_shared<RunOptions>();
  CLI::App* sub = app.add_subcommand("run", "A whole pass: impacts, contact with friction, separation; writes history, events, summary");
  opts->case_options.add_to(*sub);
  sub->add_option("-o,--output", opts->output_dir, "Output folder (created if needed)")->required()->check(non_empty_path());
  sub->add_flag("--json", opts->json, "Print summary.json instead of the human summary");
  sub->add_flag("--quiet", opts->quiet, "No progress line on stderr (shown otherwise on a terminal for runs over a second)");
  return [opts] { return run_pass_command(*opts); };
}

}  // namespace rotbeam::cli
