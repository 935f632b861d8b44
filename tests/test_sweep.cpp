// Sweeps: axis parsing (lists and ranges), the Cartesian grid, resumption, failure isolation.
#include "rotbeam/sweep.hpp"

#include <filesystem>
#include <fstream>
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
  EXPECT_NE(second.results[0].message.find("impacts: "), std::string::npos) << second.results[0].message;
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
