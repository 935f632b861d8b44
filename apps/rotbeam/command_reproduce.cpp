// `rotbeam reproduce -o DIR`: the thesis's Table 5-3 and Figures 4–13 regenerated with the cases
// their captions state (Table 5-2 values), twice: with the thesis's scheme and force convention,
// and with the default physical model; then DIR/report.md (drawn by Python's rotbeam.reproduce).
#include "commands.hpp"
#include "common.hpp"
#include "python_bridge.hpp"
#include "rotbeam/folder_lock.hpp"

#include "rotbeam/atomic_file.hpp"
#include "rotbeam/case.hpp"
#include "rotbeam/impact_output.hpp"
#include "rotbeam/job_runner.hpp"
#include "rotbeam/pass_output.hpp"

#include <optional>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>

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
  add("figure_12", "Normal force profiles for 2 % depth, 550 rpm, μ = 0.4, flexible start q̇_k(0) = 0.1 for k = 1…5",
      "With the disturbance in the higher modes (4, 5) the profile is very similar to the rigid start's.",
      {curve("rigid start", 550, 2, 0.4), curve("q̇_1 = 0.1", 550, 2, 0.4, 1), curve("q̇_2 = 0.1", 550, 2, 0.4, 2),
       curve("q̇_3 = 0.1", 550, 2, 0.4, 3), curve("q̇_4 = 0.1", 550, 2, 0.4, 4), curve("q̇_5 = 0.1", 550, 2, 0.4, 5)});
  add("figure_13", "Tip path for 2 % depth, 550 rpm, μ = 0.4 (−X against Y) with close-ups",
      "First impact near (Y, −X) = (−0.0179, −0.1257) m; contact with intervals of free motion; "
      "a bounce back after the first impact.",
      {curve("path", 550, 2, 0.4)});
  return f;
}

struct ReproduceOptions {
  std::string output_dir = "reproduction";
  int jobs = 0;
};

int run_reproduce(const ReproduceOptions& o) {
  if (o.jobs < 0) throw ConfigError("--jobs " + std::to_string(o.jobs) + ": must be >= 0");
  const fs::path dir(o.output_dir);
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
  struct Job {
    fs::path folder;
    Config config;
  };
  std::vector<Job> jobs;
  for (const auto& [model, model_overrides] : models)
    for (const auto& [id, ov] : used) {
      std::vector<std::string> all = model_overrides;
      all.insert(all.end(), ov.begin(), ov.end());
      jobs.push_back({dir / model / id, load_config(std::nullopt, all)});
    }
  install_interrupt_handlers();
  std::mutex mutex;
  std::vector<std::string> failures;
  std::vector<std::string> outcome(jobs.size());
  JobRunnerOptions runner;
  runner.threads = o.jobs;
  runner.stop = &interrupt_token();
  runner.on_job_finished = [&](const JobProgress& p) {
    const fs::path& folder = jobs[p.job].folder;
    std::fprintf(stderr, "%3zu/%zu %s%s\n", p.finished, p.total, (folder.parent_path().filename() / folder.filename()).c_str(),
                 outcome[p.job].c_str());
  };
  run_jobs(
      jobs.size(),
      [&](std::size_t i) {
        const rotbeam::Case c = build_case(jobs[i].config);
        PassFiles files(jobs[i].folder, jobs[i].config.beam.modes, jobs[i].config.simulation.history_revolutions);
        const PassResult r = run_case(c, {&files, &interrupt_token(), {}});
        files.commit(r, jobs[i].config, *c.surface);
        if (!r.failure) return;
        std::lock_guard<std::mutex> lock(mutex);
        outcome[i] = std::string(" (") + failure_name(r.failure->kind) + ")";
        failures.push_back(jobs[i].folder.string() + ": " + failure_name(r.failure->kind) + ": " + r.failure->message);
      },
      runner);
  if (interrupt_token().stop_requested()) {
    print_error("reproduction interrupted; run it again");
    return kInterrupted;
  }

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
  write_file_atomically(dir / "manifest.json", manifest.dump(2) + "\n");
  return run_python_plots({"--reproduce", o.output_dir});
}

}  // namespace

Command add_reproduce_command(CLI::App& app) {
  auto opts = std::make_shared<ReproduceOptions>();
  CLI::App* sub = app.add_subcommand(
      "reproduce", "Regenerate the thesis's Table 5-3 and Figures 4-13 (thesis model and physical model) with a report");
  sub->add_option("-o,--output", opts->output_dir, "Output folder (default: reproduction)");
  sub->add_option("--jobs", opts->jobs, "Threads (default: all cores)");
  return [opts] { return run_reproduce(*opts); };
}

}  // namespace rotbeam::cli
