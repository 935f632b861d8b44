// Sweeps: axis parsing (lists and ranges), the Cartesian grid, resumption, failure isolation.
#include "rotbeam/sweep.hpp"

#include "rotbeam/pass_output.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <gtest/gtest.h>
#include <unistd.h>

using namespace rotbeam;
namespace fs = std::filesystem;

TEST(SweepAxis, ListsAndRanges) {
  EXPECT_EQ(parse_sweep_axis("hub.speed_rpm=550,1000,2000").values, (std::vector<std::string>{"550", "1000", "2000"}));
  EXPECT_EQ(parse_sweep_axis("surface.friction=0.1:0.7:4").values,
            (std::vector<std::string>{"0.1", "0.3", "0.5", "0.7"}));
  EXPECT_EQ(parse_sweep_axis("beam.modes=3:12:4").values, (std::vector<std::string>{"3", "6", "9", "12"}));
  EXPECT_EQ(parse_sweep_axis("hub.speed_rpm=550:550:1").values, (std::vector<std::string>{"550"}));
  // Spaces around the key are dropped, as by --set (it was an unknown key, "did you mean" itself).
  EXPECT_EQ(parse_sweep_axis(" hub.speed_rpm =550").key, "hub.speed_rpm");
  // Ends whose difference overflows (-1e308:1e308 gave nan for every value).
  EXPECT_EQ(parse_sweep_axis("hub.speed_rpm=-1e308:1e308:3").values, (std::vector<std::string>{"-1e+308", "0", "1e+308"}));
  // Commas inside arrays and strings do not split.
  EXPECT_EQ(parse_sweep_axis("initial.modal_velocity=[0.1,0,0,0,0],[0,0.1,0,0,0]").values,
            (std::vector<std::string>{"[0.1,0,0,0,0]", "[0,0.1,0,0,0]"}));
  EXPECT_EQ(parse_sweep_axis("simulation.scheme=\"thesis\",adaptive").values,
            (std::vector<std::string>{"\"thesis\"", "adaptive"}));
  // Single-quoted TOML literal strings too (it split 'flex,ible' in two); an escaped quote inside a
  // basic string does not end it.
  EXPECT_EQ(parse_sweep_axis("initial.start='rigid','flex,ible'").values,
            (std::vector<std::string>{"'rigid'", "'flex,ible'"}));
  EXPECT_EQ(parse_sweep_axis("simulation.scheme=\"a\\\",b\",c").values,
            (std::vector<std::string>{"\"a\\\",b\"", "c"}));
  for (const char* bad : {"hub.speed_rpm", "=1,2", "hub.speed_rpm=", "hub.speed_rpm=1:2", "hub.speed_rpm=1:x:3",
                          "hub.speed_rpm=1:2:0", "hub.speed_rpm=1,,2"})
    EXPECT_THROW(parse_sweep_axis(bad), ConfigError) << bad;
  // An unknown key is named as --vary's, with a suggestion; a line break never splits a value.
  auto message = [](const std::string& spec) {
    try {
      parse_sweep_axis(spec);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message("hub.sped_rpm=1,2"), "--vary hub.sped_rpm: unknown key (did you mean hub.speed_rpm?)");
  EXPECT_NE(message("hub.speed_rpm=3000\n,4000").find("--vary hub.speed_rpm: a value holds a line break"),
            std::string::npos);
}

TEST(SweepCases, CartesianGridLastAxisFastest) {
  const auto cases = sweep_cases({parse_sweep_axis("hub.speed_rpm=1,2"), parse_sweep_axis("initial.start=x,y,z")});
  ASSERT_EQ(cases.size(), 6u);
  EXPECT_EQ(cases[0].overrides, (std::vector<std::string>{"hub.speed_rpm=1", "initial.start=x"}));
  EXPECT_EQ(cases[1].overrides, (std::vector<std::string>{"hub.speed_rpm=1", "initial.start=y"}));
  EXPECT_EQ(cases[5].overrides, (std::vector<std::string>{"hub.speed_rpm=2", "initial.start=z"}));
  EXPECT_EQ(cases[5].folder, "case-0006");
  // One case without the others (a Dask task loads its own): the same.
  const std::vector<SweepAxis> axes = {parse_sweep_axis("hub.speed_rpm=1,2"), parse_sweep_axis("initial.start=x,y,z")};
  EXPECT_EQ(sweep_grid_size(axes), 6u);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    EXPECT_EQ(sweep_case_at(axes, i).overrides, cases[i].overrides);
    EXPECT_EQ(sweep_case_at(axes, i).folder, cases[i].folder);
  }
}

namespace {
std::string fresh(const std::string& name) {
  const fs::path p = fs::path(::testing::TempDir()) / ("rotbeam_sweep_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(p);
  return p.string();
}
std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}
}  // namespace

TEST(Sweep, RunsResumesAndIsolatesFailures) {
  // Four cases, one of which stops on a diagnosed failure (a cap of 3 impacts at 550 rpm): the
  // other three complete, sweep.csv has a row per case with the status, and a second run of the
  // same sweep runs nothing again.
  const std::string dir = fresh("resume");
  SweepOptions options;
  options.dir = dir;
  options.jobs = 2;
  options.base_overrides = {"output.interval_s=1e-3", "simulation.max_impacts=8"};
  const std::vector<SweepAxis> axes = {parse_sweep_axis("hub.speed_rpm=550,3000"),
                                       parse_sweep_axis("surface.friction=0.1,0.4")};
  int callbacks = 0;
  options.on_case_finished = [&](const SweepProgress& p) {
    ++callbacks;
    EXPECT_LE(p.finished, p.total);
  };
  const SweepReport first = run_sweep(axes, options);
  EXPECT_EQ(callbacks, 4);
  EXPECT_EQ(first.ran, 4);
  EXPECT_EQ(first.failed, 2);  // 550 rpm has > 8 impacts; 3000 rpm has 6
  EXPECT_EQ(first.results[0].status, SweepStatus::failed);
  EXPECT_NE(first.results[0].message.find("impacts"), std::string::npos);
  EXPECT_EQ(first.results[2].status, SweepStatus::done);
  for (const SweepCase& c : first.cases) EXPECT_TRUE(fs::exists(fs::path(dir) / c.folder / "summary.json"));
  const std::string csv = slurp(fs::path(dir) / "sweep.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);
  EXPECT_EQ(csv.rfind("case,folder,hub.speed_rpm,surface.friction,status,impacts,", 0), 0u);
  EXPECT_NE(csv.find(",3000,0.4,done,6,"), std::string::npos) << csv;
  // The binned peak, nested in summary.json, has its column: the impacts-only case's is its
  // largest bin (67.7 N at 3000 rpm), where its sustained-contact peak is 0.
  char binned[64];
  std::snprintf(binned, sizeof binned, ",%.17g,",
                first.results[3].summary["binned_force"]["peak_normal_force_n"].get<double>());
  EXPECT_GT(first.results[3].summary["binned_force"]["peak_normal_force_n"].get<double>(), 10.0);
  EXPECT_NE(csv.find("normal_impulse_n_s,binned_peak_normal_force_n,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(binned), std::string::npos) << csv;

  callbacks = 0;
  const SweepReport second = run_sweep(axes, options);
  EXPECT_EQ(callbacks, 0);
  EXPECT_EQ(second.resumed, 4);
  EXPECT_EQ(second.ran, 0);
  EXPECT_EQ(second.results[2].summary["impacts"], first.results[2].summary["impacts"]);
  // Resuming does not hide a failure: the failed cases stay `failed`, counted, with their message.
  EXPECT_EQ(second.failed, 2);
  EXPECT_EQ(second.results[0].status, SweepStatus::failed);
  EXPECT_TRUE(second.results[0].resumed);
  EXPECT_EQ(second.results[0].message.rfind("impacts at t = ", 0), 0u) << second.results[0].message;  // kind, where, why
  EXPECT_NE(second.results[0].message.find(" deg: "), std::string::npos) << second.results[0].message;
  EXPECT_NE(second.results[0].message.find("(computed by an earlier run)"), std::string::npos);
  EXPECT_EQ(second.results[2].status, SweepStatus::resumed);
  const std::string again = slurp(fs::path(dir) / "sweep.csv");
  EXPECT_NE(again.find(",550,0.1,failed,"), std::string::npos) << again;

  // A changed base configuration invalidates the finished cases. While the new sweep runs the
  // folder has no index: the older sweep.csv, which describes other results, is gone at once.
  options.base_overrides.push_back("simulation.rtol=1e-8");
  bool old_index_seen = false;
  options.on_case_finished = [&](const SweepProgress&) { old_index_seen |= fs::exists(fs::path(dir) / "sweep.csv"); };
  const SweepReport third = run_sweep(axes, options);
  EXPECT_EQ(third.resumed, 0);
  EXPECT_EQ(third.ran, 4);
  EXPECT_FALSE(old_index_seen);
  EXPECT_TRUE(fs::exists(fs::path(dir) / "sweep.csv"));
  fs::remove_all(dir);
}

TEST(Sweep, ABadValueStopsBeforeAnythingRuns) {
  const std::string dir = fresh("bad");
  SweepOptions options;
  options.dir = dir;
  try {
    run_sweep({parse_sweep_axis("surface.friction=0.1,-0.4")}, options);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("case-0002 (surface.friction=-0.4)"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir));
}

TEST(SweepShard, ParsesIOfNAndRefusesTheRest) {
  EXPECT_EQ(parse_shard("0/3").index, 0);
  EXPECT_EQ(parse_shard("2/3").index, 2);
  EXPECT_EQ(parse_shard("2/3").count, 3);
  auto message = [](const std::string& text) {
    try {
      parse_shard(text);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message("3/3"), "--shard 3/3: I must be from 0 to 2 (the shards of 3 are counted from 0)");
  EXPECT_EQ(message("x"), "--shard x: expected I/N, shard I of N counted from 0 (e.g. --shard 0/4 … --shard 3/4)");
  for (const char* bad : {"", "1", "1/", "/2", "-1/2", "1/0", "1/2/3", "1.0/2", " 1/2", "99999999999999999999/2"})
    EXPECT_NE(message(bad).rfind("--shard ", 0), std::string::npos) << bad;
}

TEST(SweepShard, InMemoryCasesEqualTheFilesToTheLastBit) {
  // run_sweep_case (Python's sweeps, Dask's tasks) keeps no rows; its metrics are those of the
  // case run into files by `rotbeam sweep`, a diagnosed failure included.
  const std::string dir = fresh("memory");
  SweepOptions options;
  options.dir = dir;
  options.jobs = 2;
  options.base_overrides = {"output.interval_s=1e-3", "simulation.max_impacts=4", "beam.modes=3"};
  const std::vector<SweepAxis> axes = {parse_sweep_axis("hub.speed_rpm=550,3000"), parse_sweep_axis("surface.friction=0.1,0.4")};
  const SweepReport files = run_sweep(axes, options);
  const SweepPlan plan = plan_sweep(axes, case_loader(std::nullopt, options.base_overrides));
  ASSERT_EQ(plan.configs.size(), 4u);
  int failed = 0, done = 0;
  for (std::size_t i = 0; i < plan.configs.size(); ++i) {
    const SweepCaseResult memory = run_sweep_case(plan.configs[i], nullptr);
    EXPECT_EQ(memory.status, files.results[i].status);
    EXPECT_EQ(memory.message, files.results[i].message);
    failed += memory.status == SweepStatus::failed;
    done += memory.status == SweepStatus::done;
    for (const SweepMetric& m : sweep_metrics(false)) {
      if (std::string(m.column) == "wall_time_s") continue;
      const auto a = sweep_metric_value(memory.summary, m), b = sweep_metric_value(files.results[i].summary, m);
      ASSERT_EQ(a.has_value(), b.has_value()) << m.column;
      if (a) EXPECT_EQ(*a, *b) << m.column;  // bit for bit
    }
  }
  EXPECT_GT(failed, 0);
  EXPECT_GT(done, 0);
  // What the cases share, and what varies.
  EXPECT_EQ(plan.common_config["beam"]["modes"], 3);
  EXPECT_FALSE(plan.common_config["hub"].contains("speed_rpm"));
  EXPECT_EQ(plan.varying_keys, (std::vector<std::string>{"hub.speed_rpm", "surface.friction"}));
  fs::remove_all(dir);
}

namespace {
std::string merge_message(const MergeOptions& o) {
  try {
    merge_sweeps(o);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(SweepShard, ShardsMergeIntoTheSweepAndMergeRefusesWhatDoesNotFit) {
  // Three shards of a 6-case grid, run into their own folders, merge into a folder whose sweep.csv
  // is the unsharded sweep's (but the wall times), and which a sweep of the same grid resumes whole.
  const std::string root = fresh("shards");
  const std::vector<SweepAxis> axes = {parse_sweep_axis("hub.speed_rpm=550,3000"),
                                       parse_sweep_axis("surface.friction=0.1,0.4,0.7")};
  SweepOptions options;
  options.jobs = 1;
  options.base_overrides = {"output.interval_s=1e-3", "beam.modes=3"};
  std::vector<std::filesystem::path> dirs;
  for (int i = 0; i < 3; ++i) {
    options.dir = fs::path(root) / ("shard" + std::to_string(i));
    options.shard = Shard{i, 3};
    const SweepReport r = run_sweep(axes, options);
    ASSERT_EQ(r.cases.size(), 2u);
    EXPECT_EQ(r.grid_cases, 6u);
    EXPECT_EQ(r.cases[0].index, i);  // cases i and i + 3
    EXPECT_EQ(r.cases[1].index, i + 3);
    EXPECT_TRUE(fs::exists(options.dir / "sweep.json"));
    EXPECT_FALSE(fs::exists(options.dir / "case-0001") && i != 0);
    dirs.push_back(options.dir);
  }
  options.dir = fs::path(root) / "whole";
  options.shard = Shard{};
  const SweepReport whole = run_sweep(axes, options);

  MergeOptions merge;
  merge.dirs = dirs;
  merge.output = fs::path(root) / "merged";
  // Refused before anything is written: a missing shard, one given twice, another grid, another
  // configuration, an unfinished shard, an output folder that holds files.
  merge.dirs = {dirs[0], dirs[2]};
  EXPECT_EQ(merge_message(merge).rfind("merge: cases missing, the folders of these shards were not given: shard 1/3: "
                                       "case-0002, case-0005 (2 cases)", 0), 0u) << merge_message(merge);
  EXPECT_FALSE(fs::exists(merge.output));
  merge.dirs = {dirs[0], dirs[1], dirs[2], dirs[1]};
  EXPECT_NE(merge_message(merge).find("given twice"), std::string::npos);
  options.dir = fs::path(root) / "other-config";
  options.shard = Shard{1, 3};
  options.base_overrides.push_back("surface.depth_fraction=0.03");
  run_sweep(axes, options);
  merge.dirs = {dirs[0], options.dir, dirs[2]};
  EXPECT_NE(merge_message(merge).find("another configuration (surface.depth_fraction = 0.02 in "), std::string::npos)
      << merge_message(merge);
  options.base_overrides.pop_back();
  options.dir = fs::path(root) / "other-grid";
  run_sweep({parse_sweep_axis("hub.speed_rpm=550,2000"), parse_sweep_axis("surface.friction=0.1,0.4,0.7")}, options);
  merge.dirs = {dirs[0], options.dir, dirs[2]};
  EXPECT_NE(merge_message(merge).find("another grid"), std::string::npos) << merge_message(merge);
  fs::copy(dirs[1], fs::path(root) / "killed", fs::copy_options::recursive);
  fs::remove(fs::path(root) / "killed" / "sweep.csv");
  merge.dirs = {dirs[0], fs::path(root) / "killed", dirs[2]};
  EXPECT_NE(merge_message(merge).find("no sweep.csv: its sweep (shard 1/3) has not finished"), std::string::npos);
  fs::create_directories(merge.output);
  std::ofstream(merge.output / "notes.txt") << "mine";
  merge.dirs = dirs;
  EXPECT_NE(merge_message(merge).find("the folder exists and holds files"), std::string::npos);
  EXPECT_EQ(slurp(merge.output / "notes.txt"), "mine");
  fs::remove(merge.output / "notes.txt");

  // Merged into the empty folder: the unsharded sweep's index, but the wall times.
  const MergeReport merged = merge_sweeps(merge);
  EXPECT_EQ(merged.shards, 3);
  EXPECT_EQ(merged.linked_files + merged.copied_files, 6u * 5u);  // history, events, force bins, wear profile, summary
  // sweep.csv without its wall_time_s column (the one that differs between runs); the message column
  // is quoted text that may hold commas.
  const auto without_wall_time = [](const std::string& csv) {
    const auto fields = [](const std::string& line) {
      std::vector<std::string> f(1);
      bool quoted = false;
      for (const char ch : line) {
        if (ch == '"') quoted = !quoted;
        if (ch == ',' && !quoted) f.emplace_back();
        else f.back() += ch;
      }
      return f;
    };
    std::istringstream in(csv);
    std::string line, out;
    std::ptrdiff_t wall = -1;  // the column's index, from the header
    while (std::getline(in, line)) {
      std::vector<std::string> f = fields(line);
      if (wall < 0) wall = std::find(f.begin(), f.end(), "wall_time_s") - f.begin();
      if (wall < static_cast<std::ptrdiff_t>(f.size())) f.erase(f.begin() + wall);
      for (const std::string& v : f) out += v + ",";
      out += "\n";
    }
    return out;
  };
  EXPECT_EQ(without_wall_time(slurp(merge.output / "sweep.csv")), without_wall_time(slurp(fs::path(root) / "whole" / "sweep.csv")));
  for (const SweepCase& c : whole.cases) EXPECT_TRUE(complete_run_folder(merge.output / c.folder)) << c.folder;
  options.dir = merge.output;
  options.shard = Shard{};
  const SweepReport resumed = run_sweep(axes, options);
  EXPECT_EQ(resumed.resumed, 6);
  EXPECT_EQ(resumed.ran, 0);

  // A stop removes what the merge wrote.
  StopToken stop;
  stop.request_stop();
  merge.stop = &stop;
  merge.output = fs::path(root) / "stopped";
  EXPECT_TRUE(merge_sweeps(merge).interrupted);
  EXPECT_FALSE(fs::exists(merge.output));
  fs::remove_all(root);
}
