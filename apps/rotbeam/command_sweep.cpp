// `rotbeam sweep`: a Cartesian grid of cases, in parallel, resumable (issue: studies), or a shard
// of it (--shard I/N); `rotbeam merge`: the shards' folders combined into one sweep (issue 20).
#include "commands.hpp"
#include "common.hpp"
#include "python_bridge.hpp"

#include "rotbeam/sweep.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <unistd.h>

namespace rotbeam::cli {

namespace {

struct SweepCommandOptions {
  CaseOptions case_options;
  std::vector<std::string> vary;
  std::string output_dir;
  int jobs = 0;
  bool quiet = false;
  std::string shard;            // "I/N", "" for the whole grid
  std::string format = "csv";   // csv | netcdf
};

constexpr const char* kNetcdfWriter = "the netCDF writer";

// Whether `--format` asks for sweep.nc (checked: csv or netcdf).
bool wants_netcdf(const std::string& format) {
  if (format != "csv" && format != "netcdf")
    throw ConfigError("--format " + path_text(format) + ": must be csv (sweep.csv) or netcdf (sweep.nc beside sweep.csv)");
  return format == "netcdf";
}

// Before any work: the Python that writes sweep.nc can (xarray and netCDF4 import). Returns 0 when it
// can; kBadInput when not, the module having said why in the one line of the refusal (naming
// --format netcdf and what to install), nothing run; kInterrupted when a Ctrl-C (SIGINT/SIGTERM)
// stopped the check: the caller says so in one line.
int check_netcdf_writer() {
  const int code = run_python_module("rotbeam.netcdf", {"--check", "--then", "use --format csv"}, kNetcdfWriter, false);
  if (code == kInterrupted || code == 0) return code;
  return kBadInput;
}

// The hook that writes DIR/sweep.nc from the finished index (sweep.csv's text in `csv`), before
// sweep.csv itself: rotbeam.netcdf through Python. `code` gets the module's exit code; a failure
// is the module's one line, which ends with `then` (what the command does next); an interruption
// is left to the caller to report.
BeforeIndex netcdf_writer(const std::string& dir, const std::string& then, int& code) {
  return [dir, then, &code](const std::filesystem::path& csv) {
    code = run_python_module("rotbeam.netcdf", {dir, "--index", csv.string(), "--then", then}, kNetcdfWriter, false);
    if (code != 0) throw std::runtime_error("sweep.nc not written");
  };
}

int run_sweep_command(const SweepCommandOptions& o) {
  if (o.vary.empty()) throw ConfigError("--vary: give at least one KEY=V1,V2,… or KEY=A:B:N");
  if (o.jobs < 0) throw ConfigError("--jobs " + std::to_string(o.jobs) + ": must be >= 0");
  std::vector<SweepAxis> axes;
  for (const std::string& spec : o.vary) axes.push_back(parse_sweep_axis(spec));
  const bool netcdf = wants_netcdf(o.format);
  SweepOptions options;
  options.config_path = o.case_options.config_path;
  options.base_overrides = o.case_options.overrides;
  options.dir = o.output_dir;
  options.jobs = o.jobs;
  if (!o.shard.empty()) options.shard = parse_shard(o.shard);
  install_interrupt_handlers();  // from here on, a Ctrl-C is reported (it ended the process silently)
  const int writer = netcdf ? check_netcdf_writer() : 0;
  if (writer == kBadInput) return kBadInput;
  if (netcdf && (writer == kInterrupted || interrupt_token().stop_requested())) {
    print_error("sweep interrupted before any case ran: nothing written");
    return kInterrupted;
  }
  int netcdf_code = 0;
  if (netcdf) options.before_index = netcdf_writer(o.output_dir, "sweep.csv is written without it", netcdf_code);
  const bool terminal = !o.quiet && isatty(STDERR_FILENO), quiet = o.quiet;
  auto line = std::make_unique<LiveLine>(terminal);
  // The case under way that reported last, in words ("case_0004 θ 2514° of 7110°, revolution 7/20"):
  // the live line shows it, so a long case is seen to move. Read by the line's ticker thread.
  struct Running {
    std::mutex mutex;
    std::string text;
  };
  const auto running = std::make_shared<Running>();
  const auto running_text = [running]() {
    std::lock_guard<std::mutex> lock(running->mutex);
    return running->text.empty() ? std::string() : "; " + running->text;
  };
  line->set([running_text](double e) { return "cases under way, " + duration_text(e) + " elapsed" + running_text(); });
  // Without a terminal, a line per running case at most every 30 s of its own.
  std::map<std::string, double> printed_at;
  options.on_case_progress = [terminal, quiet, running, &printed_at](const SweepCase& c, const PassProgress& p) {
    if (quiet) return;
    std::string text = c.folder + " at θ = " + std::to_string(static_cast<long>(std::lround(p.theta_deg))) + "° of " +
                       std::to_string(static_cast<long>(std::lround(p.end_deg))) + "°";
    if (p.revolutions > 0) text += ", revolution " + std::to_string(p.revolution) + "/" + std::to_string(p.revolutions);
    if (terminal) {
      std::lock_guard<std::mutex> lock(running->mutex);
      running->text = text;
      return;
    }
    double& at = printed_at[c.folder];
    if (p.elapsed_s < at + 30.0) return;
    at = p.elapsed_s;
    std::fprintf(stderr, "%s running: %s, %s\n", c.folder.c_str(), text.c_str() + c.folder.size() + 1,
                 duration_text(p.elapsed_s).c_str());
    std::fflush(stderr);
  };
  options.on_case_finished = [terminal, quiet, &line, running, running_text](const SweepProgress& p) {
    if (quiet) return;
    if (terminal) {
      {
        std::lock_guard<std::mutex> lock(running->mutex);
        if (running->text.rfind(p.last->folder + " ", 0) == 0) running->text.clear();  // it has finished
      }
      // Redrawn every second: the clock moves and the ETA counts down between finished cases.
      const int width = 30, filled = p.total ? width * p.finished / p.total : width;
      const std::string bar = std::string(filled, '#') + std::string(width - filled, '.');
      const int finished = p.finished, total = p.total, failed = p.failed;
      const double at = p.elapsed_s, eta = p.eta_s;
      line->set([=](double e) {
        return "[" + bar + "] " + std::to_string(finished) + "/" + std::to_string(total) + " cases" +
               (failed ? ", " + std::to_string(failed) + " failed" : "") + ", " + duration_text(e) + " elapsed, ETA " +
               duration_text(std::max(0.0, eta - (e - at))) + running_text();
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
  const std::string shard_text = std::to_string(r.shard.index) + "/" + std::to_string(r.shard.count);
  if (r.shard.count > 1) std::cout << "shard " << shard_text << " of a grid of " << counted(r.grid_cases, "case") << ", ";
  std::cout << counted(r.cases.size(), "case") << ": " << r.ran << " run, " << r.resumed << " already done; " << r.failed
            << " stopped on a diagnosed failure, " << counted(r.errors, "error") << ", " << r.interrupted << " interrupted\n";
  for (std::size_t i = 0; i < r.cases.size(); ++i)
    if (r.results[i].status == SweepStatus::failed || r.results[i].status == SweepStatus::error)
      std::cout << "  " << r.cases[i].folder << " " << sweep_status_name(r.results[i].status) << ": "
                << printable(r.results[i].message) << "\n";
  const bool wrote_netcdf = netcdf && r.interrupted == 0 && r.index_error.empty();
  std::cout << "wrote " << path_text((options.dir / "sweep.csv").string())
            << (wrote_netcdf ? ", " + path_text((options.dir / "sweep.nc").string()) : std::string()) << " and a folder per case\n";
  if (r.shard.count > 1)
    std::cout << "merge the shards' folders when all have finished: rotbeam merge DIR… -o OUT\n";
  if (r.other_case_folders > 0)
    std::cout << counted(static_cast<std::size_t>(r.other_case_folders), "case folder") << " in "
              << path_text(options.dir.string()) << (r.other_case_folders == 1 ? " is" : " are")
              << (r.shard.count > 1 ? " not in this shard (an earlier sweep's: kept, not in sweep.csv)\n"
                                    : " not in this grid (an earlier sweep's: kept, not in sweep.csv)\n");
  if (r.interrupted > 0) {
    print_error("sweep interrupted: " + counted(r.interrupted, "case") + " not finished; run the same command again to resume");
    return kInterrupted;
  }
  if (r.errors > 0) {
    print_error(std::to_string(r.errors) + " of " + counted(r.cases.size(), "case") +
                " could not be run or written (status `error` in sweep.csv); run the same command again to retry them");
    return kRuntimeFailure;
  }
  if (!r.index_error.empty()) {
    if (netcdf_code == kInterrupted) {
      print_error("interrupted while writing sweep.nc: every case is done and sweep.csv written; run the same command "
                  "again to write sweep.nc");
      return kInterrupted;
    }
    // The module said why in its line (or rotbeam, where the module did not run or crashed); a
    // failure before it ran (the index's temporary copy) is said here.
    if (netcdf_code == 0)
      print_error("sweep.nc was not written (" + printable(r.index_error) + "); every case is done and sweep.csv written");
    return kRuntimeFailure;
  }
  return kSuccess;
}

struct MergeCommandOptions {
  std::vector<std::string> dirs;
  std::string output_dir;
  std::string format = "csv";
  bool quiet = false;
};

int run_merge_command(const MergeCommandOptions& o) {
  const bool netcdf = wants_netcdf(o.format);
  MergeOptions options;
  for (const std::string& d : o.dirs) options.dirs.emplace_back(d);
  options.output = o.output_dir;
  install_interrupt_handlers();
  const int writer = netcdf ? check_netcdf_writer() : 0;
  if (writer == kBadInput) return kBadInput;
  if (netcdf && (writer == kInterrupted || interrupt_token().stop_requested())) {
    print_error("merge interrupted before anything was written");
    return kInterrupted;
  }
  int netcdf_code = 0;
  if (netcdf)
    options.before_index = netcdf_writer(o.output_dir, "merge: nothing written (" + path_text(o.output_dir) + " removed)",
                                         netcdf_code);
  const bool terminal = !o.quiet && isatty(STDERR_FILENO);
  auto line = std::make_unique<LiveLine>(terminal);
  options.on_case = [&line](std::size_t done, std::size_t total) {
    line->set([=](double e) {
      return "merge: " + std::to_string(done) + "/" + std::to_string(total) + " case folders, " + duration_text(e) + " elapsed";
    });
  };
  install_interrupt_handlers();
  options.stop = &interrupt_token();
  MergeReport r;
  try {
    r = merge_sweeps(options);
  } catch (const std::runtime_error& e) {
    line.reset();
    if (netcdf_code == kInterrupted) {
      print_error("merge interrupted while writing sweep.nc: nothing written (" + path_text(o.output_dir) + " removed)");
      return kInterrupted;
    }
    if (netcdf_code != 0) return kRuntimeFailure;  // the module said why and what is left, in one line
    throw;
  }
  line.reset();
  if (r.interrupted) {
    print_error("merge interrupted: nothing written (" + path_text(o.output_dir) + " removed)");
    return kInterrupted;
  }
  const SweepReport& s = r.sweep;
  std::cout << "merged " << r.shards << (r.shards == 1 ? " shard" : " shards")
            << (r.shards < r.shard_count ? " of " + std::to_string(r.shard_count) + " (the others hold no case of the grid)"
                                         : std::string())
            << ": " << s.cases.size()
            << (s.cases.size() == 1 ? " case (" : " cases (") << s.failed << " stopped on a diagnosed failure)\n";
  std::cout << "wrote " << path_text((std::filesystem::path(o.output_dir) / "sweep.csv").string())
            << (netcdf ? ", " + path_text((std::filesystem::path(o.output_dir) / "sweep.nc").string()) : std::string())
            << " and a folder per case (" << r.linked_files << " files linked, " << r.copied_files << " copied)\n";
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
  sub->add_option("--shard", opts->shard,
                  "Run only shard I of N (I counted from 0: the cases whose index mod N is I), e.g. "
                  "--shard $SLURM_ARRAY_TASK_ID/8; combine the shards' folders with `rotbeam merge`");
  sub->add_option("--format", opts->format,
                  "csv (default): sweep.csv; netcdf: also sweep.nc (netCDF4, through Python's xarray)");
  return [opts] { return run_sweep_command(*opts); };
}

Command add_merge_command(CLI::App& app) {
  auto opts = std::make_shared<MergeCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "merge", "Combine the folders of a sweep's shards (sweep --shard I/N) into one sweep folder: sweep.csv, a folder per case");
  sub->add_option("folders", opts->dirs, "The shards' folders, one per shard 0…N-1")->required()->check(non_empty_path());
  sub->add_option("-o,--output", opts->output_dir, "The merged sweep's folder (new, or empty)")->required()->check(non_empty_path());
  sub->add_option("--format", opts->format, "csv (default): sweep.csv; netcdf: also sweep.nc");
  sub->add_flag("--quiet", opts->quiet, "No progress line on stderr");
  return [opts] { return run_merge_command(*opts); };
}

}  // namespace rotbeam::cli
