// `rotbeam wear`: a filament's wear and frictional heat over hours of operation (docs/wear.md).
#include "commands.hpp"
#include "common.hpp"

#include "rotbeam/wear_output.hpp"
#include "rotbeam/wear_run.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <unistd.h>

namespace rotbeam::cli {

namespace {

struct WearCommandOptions {
  CaseOptions case_options;
  std::string output_dir;
  double hours = 10;
  int steps = 10;
  bool json = false;
  bool quiet = false;
};

void print_summary(const Config& config, const WearRun& r, const WearRunOptions& o, const std::string& dir) {
  std::cout << "Wear: " << number_text(o.hours) << " h of operation in " << o.steps << " steps, "
            << number_text(config.beam.speed_rpm) << " rpm, " << surface_text(config) << ", μ = "
            << config.contact.friction.mu << ", " << modes_text(config) << "\n";
  const WearStep* first = nullptr;
  const WearStep* last = nullptr;
  for (const WearStep& s : r.steps)
    if (s.ran) last = &s, first = first ? first : &s;
  if (first) {
    const WearStep& a = *first;
    const WearStep& b = *last;
    std::cout << "  filament length       " << fixed(r.steps.front().length_m * 1e3, 4) << " mm → "
              << fixed((config.beam.length_m - r.length_lost_m) * 1e3, 4) << " mm (lost "
              << number_text(r.length_lost_m * 1e6) << " µm)\n";
    std::cout << "  mean normal force     " << fixed(a.mean_normal_force_n, 5) << " N → " << fixed(b.mean_normal_force_n, 5)
              << " N\n";
    std::cout << "  removal rate          " << number_text(a.removal_rate_m3_h * 1e9) << " → "
              << number_text(b.removal_rate_m3_h * 1e9) << " mm³/h; " << number_text(r.volume_removed_m3 * 1e9)
              << " mm³ removed\n";
    std::cout << "  frictional heat       " << number_text(a.heat_rate_w) << " → " << number_text(b.heat_rate_w)
              << " W; " << number_text(r.heat_j) << " J in all\n";
    int not_steady = 0;
    for (const WearStep& s : r.steps) not_steady += s.ran && !s.steady;
    if (not_steady > 0)
      std::cout << "  warning: " << not_steady << " of " << r.steps.size()
                << " steady-state searches did not settle within simulation.revolutions: their last revolution is used\n";
  }
  for (const std::string& w : r.warnings) std::cout << "  warning: " << w << "\n";
  if (!r.note.empty()) std::cout << "  note: " << r.note << "\n";
  std::cout << "  wrote " << (std::filesystem::path(dir) / "wear_history.csv").string()
            << ", wear_depth.csv, summary.json (pictures: rotbeam plot " << dir << ")\n";
}

int run_wear_command(const WearCommandOptions& o) {
  const Config config = o.case_options.load_filament("wear");
  WearRunOptions options;
  options.hours = o.hours;
  options.steps = o.steps;
  if (!(o.hours > 0) || !std::isfinite(o.hours)) throw ConfigError("--hours " + number_text(o.hours) + ": must be a positive number");
  if (o.steps < 1 || o.steps > 100000) throw ConfigError("--steps " + std::to_string(o.steps) + ": must be 1 … 100000");
  std::unique_ptr<WearFiles> files;
  try {
    files = std::make_unique<WearFiles>(o.output_dir);
  } catch (const std::exception& e) {
    throw ConfigError(std::string("-o ") + e.what());
  }
  install_interrupt_handlers();
  options.stop = &interrupt_token();
  auto line = std::make_unique<LiveLine>(!o.quiet && isatty(STDERR_FILENO));
  const auto started = std::chrono::steady_clock::now();
  options.on_step = [&line, started](int step, int steps, double length) {
    const double at = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    line->set([=](double e) {
      const double eta = step > 0 ? at / step * (steps + 1 - step) - (e - at) : NAN;
      return "slow step " + std::to_string(step) + "/" + std::to_string(steps) + " (L = " + fixed(length * 1e3, 4) +
             " mm), " + fixed(e, 0) + " s elapsed" + (std::isfinite(eta) ? ", ETA " + fixed(std::max(0.0, eta), 0) + " s" : "");
    });
  };
  const WearRun r = run_wear(config, options);
  line.reset();
  files->commit(r, config, options);
  if (o.json) std::cout << wear_run_json(r, config, options).dump(2) << "\n";
  else print_summary(config, r, options, o.output_dir);
  if (interrupt_token().stop_requested()) {
    print_error("interrupted: the files in " + o.output_dir + " hold the steps finished");
    return kInterrupted;
  }
  if (r.failure) {
    const NumericalFailure& f = *r.failure;
    print_error("the wear run stopped: " + r.note + " (" + failure_name(f.kind) + " at t = " + number_text(f.t) +
                " s, θ = " + fixed(f.theta * 180.0 / M_PI, 4) + " deg); the files in " + o.output_dir +
                " hold the steps before it");
    return exit_code_for_failure(f.kind);
  }
  return kSuccess;
}

}  // namespace

Command add_wear_command(CLI::App& app) {
  auto opts = std::make_shared<WearCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "wear", "A filament's wear and frictional heat over hours of operation: length, force, removal, heat");
  opts->case_options.add_to(*sub);
  sub->add_option("-o,--output", opts->output_dir, "Output folder (created if needed)")->required()->check(non_empty_path());
  sub->add_option("--hours", opts->hours, "Operating time [h] (default 10)");
  sub->add_option("--steps", opts->steps, "Slow-time steps over it (default 10)");
  sub->add_flag("--json", opts->json, "Print summary.json instead of the human summary");
  sub->add_flag("--quiet", opts->quiet, "No progress line on stderr");
  return [opts] { return run_wear_command(*opts); };
}

}  // namespace rotbeam::cli
