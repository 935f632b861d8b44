// `rotbeam sweep`: a Cartesian grid of cases, in parallel, resumable (issue: studies).
#include "commands.hpp"
#include "common.hpp"

#include "rotbeam/sweep.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <unistd.h>

namespace rotbeam::cli {

namespace {

struct SweepCommandOptions {
  CaseOptions case_options;
  std::vector<std::string> vary;
  std::string output_dir;
  int jobs = 0;
  bool quiet = false;
};

int run_sweep_command(const SweepCommandOptions& o) {
  if (o.vary.empty()) throw ConfigError("--vary: give at least one KEY=V1,V2,… or KEY=A:B:N");
  if (o.jobs < 0) throw ConfigError("--jobs " + std::to_string(o.jobs) + ": must be >= 0");
  std::vector<SweepAxis> axes;
  for (const std::string& spec : o.vary) axes.push_back(parse_sweep_axis(spec));
  SweepOptions options;
  options.config_path = o.case_options.config_path;
  options.base_overrides = o.case_options.overrides;
  options.dir = o.output_dir;
  options.jobs = o.jobs;
  const bool terminal = !o.quiet && isatty(STDERR_FILENO), quiet = o.quiet;
  auto line = std::make_unique<LiveLine>(terminal);
  line->set([](double e) { return "cases under way, " + duration_text(e) + " elapsed"; });
  options.on_case_finished = [terminal, quiet, &line](const SweepProgress& p) {
    if (quiet) return;
    if (terminal) {
      // Redrawn every second: the clock moves and the ETA counts down between finished cases.
      const int width = 30, filled = p.total ? width * p.finished / p.total : width;
      const std::string bar = std::string(filled, '#') + std::string(width - filled, '.');
      const int finished = p.finished, total = p.total, failed = p.failed;
      const double at = p.elapsed_s, eta = p.eta_s;
      line->set([=](double e) {
        return "[" + bar + "] " + std::to_string(finished) + "/" + std::to_string(total) + " cases" +
               (failed ? ", " + std::to_string(failed) + " failed" : "") + ", " + duration_text(e) + " elapsed, ETA " +
               duration_text(std::max(0.0, eta - (e - at)));
      });
    } else {
      std::string values;
      for (const std::string& ov : p.last->overrides) values += (values.empty() ? "" : ", ") + ov;
      std::fprintf(stderr, "%s %s (%s): %d/%d, ETA %s%s\n", p.last->folder.c_str(),
                   sweep_status_name(p.last_result->status), printable(values).c_str(), p.finished, p.total,
                   duration_text(p.eta_s).c_str(),
                   p.last_result->message.empty() ? "" : (" — " + printable(p.last_result->message)).c_str());
    }
    std::fflush(stderr);
  };
  install_interrupt_handlers();
  options.stop = &interrupt_token();
  const SweepReport r = run_sweep(axes, options);
  line.reset();  // the progress line is cleared before the results are printed
  const auto counted = [](std::size_t n, const std::string& word) {
    return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
  };
  std::cout << counted(r.cases.size(), "case") << ": " << r.ran << " run, " << r.resumed << " already done; " << r.failed
            << " stopped on a diagnosed failure, " << counted(r.errors, "error") << ", " << r.interrupted << " interrupted\n";
  for (std::size_t i = 0; i < r.cases.size(); ++i)
    if (r.results[i].status == SweepStatus::failed || r.results[i].status == SweepStatus::error)
      std::cout << "  " << r.cases[i].folder << " " << sweep_status_name(r.results[i].status) << ": "
                << printable(r.results[i].message) << "\n";
  std::cout << "wrote " << path_text((options.dir / "sweep.csv").string()) << " and a folder per case\n";
  if (r.other_case_folders > 0)
    std::cout << counted(static_cast<std::size_t>(r.other_case_folders), "case folder") << " in "
              << path_text(options.dir.string()) << (r.other_case_folders == 1 ? " is" : " are")
              << " not in this grid (an earlier sweep's: kept, not in sweep.csv)\n";
  if (r.interrupted > 0) {
    print_error("sweep interrupted: " + counted(r.interrupted, "case") + " not finished; run the same command again to resume");
    return kInterrupted;
  }
  if (r.errors > 0) {
    print_error(std::to_string(r.errors) + " of " + counted(r.cases.size(), "case") +
                " could not be run or written (status `error` in sweep.csv); run the same command again to retry them");
    return kRuntimeFailure;
  }
  return kSuccess;
}

}  // namespace

Command add_sweep_command(CLI::App& app) {
  auto opts = std::make_shared<SweepCommandOptions>();
  CLI::App* sub = app.add_subcommand("sweep", "Run a Cartesian grid of cases in parallel (resumable); writes DIR/sweep.csv");
  opts->case_options.add_to(*sub);
  sub->add_option("--vary", opts->vary, "An axis: KEY=V1,V2,… (TOML values) or KEY=A:B:N (repeatable)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  sub->add_option("-o,--output", opts->output_dir, "Output folder (created if needed)")->required()->check(non_empty_path());
  sub->add_option("--jobs", opts->jobs, "Threads (default: all cores)");
  sub->add_flag("--quiet", opts->quiet,
                "No progress on stderr (otherwise a redrawn line on a terminal, a line per finished case elsewhere)");
  return [opts] { return run_sweep_command(*opts); };
}

}  // namespace rotbeam::cli
