// `rotbeam reproduce -o DIR`: the thesis's Table 5-3 and Figures 4–13 regenerated with the cases
// their captions state (Table 5-2 values), twice: with the thesis's scheme and force convention,
// and with the default physical model; then DIR/report.md (drawn by Python's rotbeam.reproduce).
// By default each run keeps summary.json, events.csv and the history rows the figures draw
// (ThinnedRows below); --keep-history keeps every row.
#include "commands.hpp"
#include "common.hpp"
#include "python_bridge.hpp"
#include "rotbeam/folder_lock.hpp"

#include "rotbeam/atomic_file.hpp"
#include "rotbeam/case.hpp"
#include "rotbeam/impact_output.hpp"
#include "rotbeam/job_runner.hpp"
#include "rotbeam/pass_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <system_error>
#include <unistd.h>

namespace rotbeam::cli {

namespace {

namespace fs = std::filesystem;

struct Case {
  std::string id;                      // folder name, e.g. "550rpm_d2_mu0.4_rigid"
  std::vector<std::string> overrides;  // relative to the base case
};

struct Figure {
  std::string id, caption, trend;
  std::vector<std::pair<std::string, std::string>> curves;  // label, case id
};

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string case_id(double rpm, double depth_pct, double mu, int disturbed_mode = 0) {
  std::string id = number(rpm) + "rpm_d" + number(depth_pct) + "_mu" + number(mu);
  return id + (disturbed_mode ? "_qd" + std::to_string(disturbed_mode) : "_rigid");
}

std::vector<std::string> case_overrides(double rpm, double depth_pct, double mu, int disturbed_mode) {
  std::vector<std::string> o = {"hub.speed_rpm=" + number(rpm), "surface.depth_fraction=" + number(depth_pct / 100),
                                "surface.friction=" + number(mu), "output.interval_s=2e-6"};
  if (disturbed_mode) {
    std::string v = "[";
    for (int k = 1; k <= 5; ++k) v += std::string(k > 1 ? "," : "") + (k == disturbed_mode ? "0.1" : "0");
    o.push_back("initial.modal_velocity=" + v + "]");
  }
  return o;
}

std::vector<Figure> figures() {
  std::vector<Figure> f;
  auto add = [&](std::string id, std::string caption, std::string trend,
                 std::vector<std::pair<std::string, std::string>> curves) {
    f.push_back({std::move(id), std::move(caption), std::move(trend), std::move(curves)});
  };
  auto curve = [](std::string label, double rpm, double d, double mu, int k = 0) {
    return std::make_pair(std::move(label), case_id(rpm, d, mu, k));
  };
  add("figure_04", "Normal force profiles for 550 rpm and depths of 2, 4, 6, 8 % (μ = 0.4)",
      "No trend with depth: 4 % gives the largest forces, then 6, 8 and 2 %.",
      {curve("2 %", 550, 2, 0.4), curve("4 %", 550, 4, 0.4), curve("6 %", 550, 6, 0.4), curve("8 %", 550, 8, 0.4)});
  add("figure_05", "Normal force profiles for 3000 rpm and depths of 2, 4, 6, 8 % (μ = 0.4)",
      "Without the 2 % case, deeper penetration gives larger forces (4 < 6 < 8 %).",
      {curve("2 %", 3000, 2, 0.4), curve("4 %", 3000, 4, 0.4), curve("6 %", 3000, 6, 0.4), curve("8 %", 3000, 8, 0.4)});
  add("figure_06", "Normal force profiles for 2 % depth and 550, 1000, 2000, 3000 rpm (μ = 0.4)",
      "The normal force grows and the contact length shrinks with speed (holds from 550 to 2000 rpm).",
      {curve("550 rpm", 550, 2, 0.4), curve("1000 rpm", 1000, 2, 0.4), curve("2000 rpm", 2000, 2, 0.4),
       curve("3000 rpm", 3000, 2, 0.4)});
  add("figure_07", "Normal force profiles for 8 % depth and 550, 1000, 2000, 3000 rpm (μ = 0.4)",
      "Larger normal forces at higher speed; longer contact at lower speed (550 to 2000 rpm).",
      {curve("550 rpm", 550, 8, 0.4), curve("1000 rpm", 1000, 8, 0.4), curve("2000 rpm", 2000, 8, 0.4),
       curve("3000 rpm", 3000, 8, 0.4)});
  add("figure_08", "Normal force profiles for 2 % depth, 550 rpm and μ = 0.1, 0.3, 0.5, 0.7",
      "Smaller friction gives larger normal forces (in the first part of the process).",
      {curve("μ = 0.1", 550, 2, 0.1), curve("μ = 0.3", 550, 2, 0.3), curve("μ = 0.5", 550, 2, 0.5),
       curve("μ = 0.7", 550, 2, 0.7)});
  add("figure_09", "Normal force profiles for 8 % depth, 550 rpm and μ = 0.1, 0.3, 0.5",
      "Smaller friction gives larger normal forces (closely at first).",
      {curve("μ = 0.1", 550, 8, 0.1), curve("μ = 0.3", 550, 8, 0.3), curve("μ = 0.5", 550, 8, 0.5)});
  add("figure_10", "Normal force profiles for 2 % depth, 3000 rpm and μ = 0.1, 0.3, 0.5, 0.7",
      "Only some friction values follow the trend (smaller friction, larger forces).",
      {curve("μ = 0.1", 3000, 2, 0.1), curve("μ = 0.3", 3000, 2, 0.3), curve("μ = 0.5", 3000, 2, 0.5),
       curve("μ = 0.7", 3000, 2, 0.7)});
  add("figure_11", "Normal force profiles for 8 % depth, 3000 rpm and μ = 0.1, 0.3, 0.5",
      "The same tendencies as Figures 8–10 (smaller friction, larger forces).",
      {curve("μ = 0.1", 3000, 8, 0.1), curve("μ = 0.3", 3000, 8, 0.3), curve("μ = 0.5", 3000, 8, 0.5)});
  add("figure_12",
      "Normal force profiles for 2 % depth, 550 rpm, μ = 0.4, flexible start q̇_k(0) = 0.1 m/s (the thesis's "
      "0.1 s⁻¹) for k = 1…5",
      "With the disturbance in the higher modes (4, 5) the profile is very similar to the rigid start's.",
      {curve("rigid start", 550, 2, 0.4), curve("q̇_1(0) = 0.1 m/s", 550, 2, 0.4, 1), curve("q̇_2(0) = 0.1 m/s", 550, 2, 0.4, 2),
       curve("q̇_3(0) = 0.1 m/s", 550, 2, 0.4, 3), curve("q̇_4(0) = 0.1 m/s", 550, 2, 0.4, 4), curve("q̇_5(0) = 0.1 m/s", 550, 2, 0.4, 5)});
  add("figure_13",
      "Tip path for 2 % depth, 550 rpm, μ = 0.4 (−X against Y): (a) the pass, (b) the disturbances, (c) the "
      "contact region, (d) the bounce back",
      "First impact near (Y, −X) = (−0.0179, −0.1257) m; contact with intervals of free motion; two disturbances "
      "of the tip path in the free motion after contact; a bounce back after the first impact.",
      {curve("path", 550, 2, 0.4)});
  return f;
}

struct ReproduceOptions {
  std::string output_dir = "reproduction";
  int jobs = 0;
  bool keep_history = false;
  bool quiet = false;
};

// The history rows the figures draw, passed on to the run's PassFiles (the rest are dropped):
// every row in sustained contact with the free rows just before and after it (so each episode's
// ends are in the file and no two episodes join), the first and the last row; with `whole_path`
// (Figure 13's tip path) also the free flight, one row per kWholePathInterval, and every row in the
// kBounceWindow after the first impact (the bounce back). Events are all passed on.
constexpr double kWholePathInterval = 1e-5;  // [s]
constexpr double kBounceWindow = 2e-3;       // [s]
constexpr double kAnnounceBytes = 100e6;     // a reproduction writing more is announced first

class ThinnedRows final : public PassSink {
public:
  ThinnedRows(PassFiles& files, bool whole_path) : files_(files), whole_path_(whole_path) {}
  void row(const HistoryRow& r) override {
    const bool pressed = r.phase != Phase::free;
    bool keep = !have_previous_ || pressed || previous_pressed_;
    if (whole_path_)
      keep = keep || r.t - last_kept_t_ >= kWholePathInterval * (1 - 1e-9) ||
             (std::isfinite(first_impact_t_) && r.t <= first_impact_t_ + kBounceWindow);
    if (keep && pressed && have_previous_ && !previous_kept_) files_.row(previous_);
    if (keep) {
      files_.row(r);
      last_kept_t_ = r.t;
    }
    previous_ = r;
    have_previous_ = true;
    previous_kept_ = keep;
    previous_pressed_ = pressed;
  }
  void event(const PassEvent& e) override {
    if (e.kind == EventKind::impact && !std::isfinite(first_impact_t_)) first_impact_t_ = e.t;
    files_.event(e);
  }
  void revolution(const RevolutionRecord& record) override { files_.revolution(record); }
  /// Passes on the last row (before PassFiles::commit).
  void finish() {
    if (have_previous_ && !previous_kept_) files_.row(previous_);
    previous_kept_ = true;
  }

private:
  PassFiles& files_;
  bool whole_path_;
  HistoryRow previous_;
  bool have_previous_ = false, previous_kept_ = false, previous_pressed_ = false;
  double last_kept_t_ = -std::numeric_limits<double>::infinity();
  double first_impact_t_ = std::numeric_limits<double>::quiet_NaN();
};

// Bytes of the files under `dir` (0 for what cannot be read).
double folder_bytes(const fs::path& dir) {
  double total = 0;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code size_ec;
    if (it->is_regular_file(size_ec)) {
      const auto size = it->file_size(size_ec);
      if (!size_ec) total += static_cast<double>(size);
    }
  }
  return total;
}

int run_reproduce(const ReproduceOptions& o) {
  if (o.jobs < 0) throw ConfigError("--jobs " + std::to_string(o.jobs) + ": must be >= 0");
  const fs::path dir(o.output_dir);
  // A run's, a sweep's or a brush's folder is not made a reproduction's as well: `plot` would draw
  // one of the two, and the reproduction's files would stand beside results they do not describe.
  std::error_code kind_ec;
  const char* other = fs::exists(dir / "sweep.csv", kind_ec)       ? "a sweep (sweep.csv)"
                      : fs::exists(dir / "workpiece.csv", kind_ec) ? "a brush (workpiece.csv)"
                      : fs::exists(dir / "summary.json", kind_ec) && fs::exists(dir / "history.csv", kind_ec)
                          ? "a run (summary.json, history.csv)"
                          : nullptr;
  if (other)
    throw ConfigError("-o " + path_text(o.output_dir) + ": holds " + other + ", not a reproduction; give another folder");
  std::optional<FolderLock> lock;  // one reproduction at a time in a folder
  try {
    prepare_output_folder(dir);
    lock.emplace(dir);
  } catch (const std::exception& e) {
    throw ConfigError(std::string("-o ") + e.what());
  }
  const std::vector<Figure> figs = figures();
  std::map<std::string, std::vector<std::string>> cases;
  for (double rpm : {550.0, 1000.0, 2000.0, 3000.0})
    for (double d : {2.0, 4.0, 6.0, 8.0})
      for (double mu : {0.1, 0.3, 0.4, 0.5, 0.7}) cases[case_id(rpm, d, mu)] = case_overrides(rpm, d, mu, 0);
  for (int k = 1; k <= 5; ++k) cases[case_id(550, 2, 0.4, k)] = case_overrides(550, 2, 0.4, k);
  // Only the cases the figures use.
  std::vector<std::pair<std::string, std::vector<std::string>>> used;
  for (const auto& [id, ov] : cases) {
    bool needed = false;
    for (const Figure& f : figs)
      for (const auto& c : f.curves) needed |= c.second == id;
    if (needed) used.emplace_back(id, ov);
  }
  const std::vector<std::pair<std::string, std::vector<std::string>>> models = {
      {"thesis", {"simulation.scheme=thesis", "compat.thesis_forces=true"}}, {"physical", {}}};
  const std::string whole_path_case = figs.back().curves.front().second;  // Figure 13's tip path
  struct Job {
    fs::path folder;
    Config config;
    bool whole_path = false;
  };
  std::vector<Job> jobs;
  for (const auto& [model, model_overrides] : models)
    for (const auto& [id, ov] : used) {
      std::vector<std::string> all = model_overrides;
      all.insert(all.end(), ov.begin(), ov.end());
      jobs.push_back({dir / model / id, load_config(std::nullopt, all), id == whole_path_case});
    }
  // Every row of every history: announced when large, refused when it cannot fit on the disk.
  if (o.keep_history) {
    double bytes = 0, at_least = 0;
    for (const Job& j : jobs) {
      const HistoryEstimate e = estimate_history(build_case(j.config));
      bytes += e.csv_bytes;
      at_least += e.min_csv_bytes;
    }
    const double available = available_disk_bytes(dir);
    if (available > 0 && at_least > available)
      throw ConfigError("--keep-history: the " + std::to_string(jobs.size()) + " histories take at least " +
                        size_text(at_least) + ", more than the " + size_text(available) + " free in " + dir.string());
    if (bytes > kAnnounceBytes && !o.quiet)
      std::cerr << "rotbeam: note: --keep-history: the " << jobs.size() << " histories will take about "
                << size_text(bytes) << " in " << path_text(dir.string()) << std::endl;
  }
  install_interrupt_handlers();
  const bool terminal = !o.quiet && isatty(STDERR_FILENO);
  std::mutex mutex;
  std::vector<std::string> failures;
  auto line = std::make_unique<LiveLine>(terminal);  // cleared before anything else is printed
  {
    const std::size_t total = jobs.size();
    const int threads = std::min<int>(default_threads(o.jobs), static_cast<int>(total));
    line->set([total, threads](double e) {
      return "reproduce: " + std::to_string(total) + " runs on " + std::to_string(threads) + " threads, " +
             duration_text(e) + " elapsed";
    });
    JobRunnerOptions runner;
    runner.threads = o.jobs;
    runner.stop = &interrupt_token();
    runner.on_job_finished = [&](const JobProgress& p) {
      const fs::path& folder = jobs[p.job].folder;
      const std::string name = (folder.parent_path().filename() / folder.filename()).string();
      const std::size_t finished = p.finished;
      const double at = p.elapsed_s, eta = p.eta_s;
      line->set([=](double e) {
        return "reproduce: run " + std::to_string(finished) + "/" + std::to_string(total) + " " + name + ", " +
               duration_text(e) + " elapsed, ETA " + duration_text(std::max(0.0, eta - (e - at)));
      });
    };
    run_jobs(
        jobs.size(),
        [&](std::size_t i) {
          const rotbeam::Case c = build_case(jobs[i].config);
          PassFiles files(jobs[i].folder, coordinate_count(jobs[i].config.beam), jobs[i].config.simulation.history_revolutions);
          ThinnedRows thinned(files, jobs[i].whole_path);
          PassSink* sink = o.keep_history ? static_cast<PassSink*>(&files) : &thinned;
          const PassResult r = run_case(c, {sink, &interrupt_token(), {}});
          thinned.finish();
          files.commit(r, jobs[i].config, *c.surface);
          if (!r.failure) return;
          std::lock_guard<std::mutex> lock(mutex);
          failures.push_back(jobs[i].folder.string() + ": " + failure_name(r.failure->kind) + ": " + r.failure->message);
        },
        runner);
  }
  if (interrupt_token().stop_requested()) {
    line.reset();
    print_error("reproduction interrupted; run it again");
    return kInterrupted;
  }
  std::sort(failures.begin(), failures.end());
  line->set([](double e) { return "reproduce: Table 5-3, " + duration_text(e) + " elapsed"; });

  // Table 5-3 (first impacts; the model choice does not affect them).
  nlohmann::json table = nlohmann::json::array();
  const double printed[8][6] = {{550, 0, 1.0319, -0.5129, 1.5448, 0.4970}, {550, 0.1, 1.0171, -0.5074, 1.5245, 0.4989},
                                {550, 1, 0.9371, -0.4772, 1.4143, 0.5092},   {550, 2, 0.8912, -0.4596, 1.3508, 0.5157},
                                {3000, 0, 5.6283, -1.8307, 7.4590, 0.3253},  {3000, 0.1, 5.6006, -1.8239, 7.4245, 0.3257},
                                {3000, 1, 5.3422, -1.7605, 7.1027, 0.3295},  {3000, 2, 5.0358, -1.6842, 6.7200, 0.3344}};
  for (const auto& row : printed) {
    std::vector<std::string> ov = {"hub.speed_rpm=" + number(row[0])};
    if (row[1] != 0) ov.push_back("initial.modal_velocity=[" + number(row[1]) + ",0,0,0,0]");
    const Config c = load_config(std::nullopt, ov);
    const FirstImpactResult r = run_first_impact(build_case(c));
    table.push_back({{"rpm", row[0]},
                     {"modal_velocity_1", row[1]},
                     {"printed", {row[2], row[3], row[4], row[5]}},
                     {"ours", impact_json(r, c)}});
  }
  nlohmann::json manifest;
  manifest["models"] = {{{"id", "thesis"}, {"description", "the thesis's scheme (fixed steps, predictor–corrector) and force convention |λ|·|∇C|"}},
                        {{"id", "physical"}, {"description", "the default model: adaptive event-driven scheme, physical normal force F_n = −λ"}}};
  manifest["figures"] = nlohmann::json::array();
  for (const Figure& f : figs) {
    nlohmann::json curves = nlohmann::json::array();
    for (const auto& [label, id] : f.curves) curves.push_back({{"label", label}, {"case", id}});
    manifest["figures"].push_back({{"id", f.id}, {"caption", f.caption}, {"thesis_trend", f.trend}, {"curves", curves}});
  }
  manifest["table_5_3"] = table;
  manifest["failures"] = failures;
  manifest["history"] =
      o.keep_history
          ? nlohmann::json{{"kept", "all"}, {"description", "every row (output.interval_s = 2e-6 s)"}}
          : nlohmann::json{{"kept", "thinned"},
                           {"description",
                            "the rows the figures draw: every row in sustained contact with the free rows just before "
                            "and after it, the first and the last row; for Figure 13's case also the free flight, one "
                            "row per 1e-5 s, and every row in the 2e-3 s after the first impact (--keep-history keeps "
                            "every row, output.interval_s = 2e-6 s)"},
                           {"whole_path_case", whole_path_case}};
  write_file_atomically(dir / "manifest.json", manifest.dump(2) + "\n");
  line.reset();
  for (const std::string& f : failures) std::cerr << "rotbeam: note: a run stopped on a diagnosed failure: " << f << "\n";
  std::vector<std::string> args = {o.output_dir};
  if (terminal) args.push_back("--progress");
  const int code = run_python_module("rotbeam.reproduce", args);
  if (code == 0)
    std::cout << "the runs' files take " << size_text(folder_bytes(dir / "thesis") + folder_bytes(dir / "physical"))
              << " under " << path_text((dir / "thesis").string()) << " and " << path_text((dir / "physical").string())
              << (o.keep_history ? " (every history row)" : " (histories thinned to the rows the figures draw; --keep-history keeps every row)")
              << "\n";
  return code;
}

}  // namespace

Command add_reproduce_command(CLI::App& app) {
  auto opts = std::make_shared<ReproduceOptions>();
  CLI::App* sub = app.add_subcommand(
      "reproduce", "Regenerate the thesis's Table 5-3 and Figures 4-13 (thesis model and physical model) with a report");
  sub->add_option("-o,--output", opts->output_dir, "Output folder (default: reproduction)")->check(non_empty_path());
  sub->add_option("--jobs", opts->jobs, "Threads (default: all cores)");
  sub->add_flag("--keep-history", opts->keep_history,
                "Keep every history row of every run (about 290 MB; by default only the rows the figures draw)");
  sub->add_flag("--quiet", opts->quiet, "No progress line on stderr (shown otherwise on a terminal)");
  return [opts] { return run_reproduce(*opts); };
}

}  // namespace rotbeam::cli
