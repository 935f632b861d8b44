// Reliability III (docs/reliability.md): passes that advance at every time and honour every stop.
#include "rotbeam/brush.hpp"
#include "rotbeam/brush_output.hpp"
#include "rotbeam/case.hpp"
#include "rotbeam/sample_grid.hpp"
#include "rotbeam/stop_token.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>
#include <unistd.h>
#include <random>

using namespace rotbeam;

TEST(ReliabilityIII, TheNextGridTimeAlwaysAdvances) {
  // h·(floor(t/h + 1e-9) + 1) gave t itself for t = 0.03125 s, h = 1 ns and for t = 256 s with the
  // default 10 µs: the history stalled there. The next grid time is after t and at most one step
  // (plus t's own rounding) beyond it, at every time and grid.
  EXPECT_GT(next_grid_time(0.03125, 1e-9), 0.03125);
  EXPECT_GT(next_grid_time(256.0, 1e-5), 256.0);
  EXPECT_GT(next_grid_time(1e9, 1e-12), 1e9);  // h below t's resolution: the next double
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(-12.0, 3.0), mantissa(1.0, 10.0);
  for (int i = 0; i < 200000; ++i) {
    const double h = mantissa(rng) * std::pow(10.0, std::round(exponent(rng)) - 3.0);
    // t on the grid itself (the case that stalled) and off it.
    const double k = std::floor(std::uniform_real_distribution<double>(0.0, 1e7)(rng));
    for (const double t : {k * h, (k + 0.5) * h}) {
      const double next = next_grid_time(t, h);
      ASSERT_GT(next, t) << "t = " << t << ", h = " << h;
      ASSERT_LE(next, t + h * (1.0 + 1e-9) + 4.0 * std::nextafter(t, INFINITY) - 4.0 * t) << "t = " << t << ", h = " << h;
    }
  }
}

TEST(ReliabilityIII, SuccessiveGridTimesAreTheGrid) {
  // Walking the grid from 0 gives k·h at the k-th call (no skipped and no repeated point) far past
  // where the old guard failed.
  const double h = 1e-5;
  double t = 255.99;
  for (long k = std::lround(t / h); t < 256.01; ++k) {
    const double next = next_grid_time(t, h);
    ASSERT_EQ(next, (k + 1) * h) << "t = " << t;
    t = next;
  }
}

namespace {
// Counts rows and asks the pass to stop once a row is written past `stop_after_s`.
struct StoppingSink : PassSink {
  StopToken* stop = nullptr;
  double stop_after_s = 0.0;
  long rows = 0, rows_after_stop = 0;
  double last_t = 0.0;
  void row(const HistoryRow& r) override {
    ++rows;
    last_t = r.t;
    if (stop->stop_requested()) ++rows_after_stop;
    else if (r.t > stop_after_s) stop->request_stop();
  }
  void event(const PassEvent&) override {}
};
}  // namespace

TEST(ReliabilityIII, AFineNearSurfaceGridPassesTheTimeThatStalledAndHonoursAStop) {
  // 400 rpm, a near-surface grid of 1 ns within 0.2 mm of the surface: the history stopped growing
  // at t = 0.03124789 s and the pass ignored SIGINT. The rows now pass that time, and a stop
  // requested inside the fine grid (millions of rows per step) ends the pass within a few thousand
  // rows (the loop looks at the token every 1024 rows).
  const Case c = build_case(load_config_string("", {"hub.speed_rpm=400", "initial.modal_velocity=[0.01,0,0,0,0]",
                                                    "output.near_surface_interval_s=1e-9",
                                                    "output.near_surface_gap_m=3.2e-3"}));
  StopToken stop;
  StoppingSink sink;
  sink.stop = &stop;
  sink.stop_after_s = 0.0312479;
  PassControl control;
  control.stop = &stop;
  control.sink = &sink;
  const PassResult r = run_case(c, control);
  ASSERT_TRUE(r.failure);
  EXPECT_EQ(r.failure->kind, FailureKind::interrupted);
  EXPECT_GT(sink.last_t, 0.0312479);
  EXPECT_LT(sink.rows_after_stop, 4096);
}

TEST(ReliabilityIII, AStopEndsTheRowsOfALongStepOnAFineGrid) {
  // The base case with every row a near-surface row (a gap of 1 m) on a 1 ns grid: one free-flight
  // step holds millions of rows, and SIGTERM waited 13 minutes (6.95 GB). A stop requested at the
  // first row past 1 µs ends the pass within the next 1024 rows, not at the step's end.
  const Case c = build_case(load_config_string(
      "", {"output.near_surface_interval_s=1e-9", "output.near_surface_gap_m=1", "output.interval_s=1e-9"}));
  StopToken stop;
  StoppingSink sink;
  sink.stop = &stop;
  sink.stop_after_s = 1e-6;
  PassControl control;
  control.stop = &stop;
  control.sink = &sink;
  const PassResult r = run_case(c, control);
  ASSERT_TRUE(r.failure);
  EXPECT_EQ(r.failure->kind, FailureKind::interrupted);
  EXPECT_LE(sink.rows_after_stop, 1100);
}

namespace {
bool warns_of(const PassResult& r, const std::string& words) {
  for (const std::string& w : r.summary.warnings)
    if (w.find(words) != std::string::npos) return true;
  return false;
}
}  // namespace

TEST(ReliabilityIII, ACompliantTipThroughTheDepthIsOutsideHertzsTheory) {
  // A soft surface (E_s = 1 kPa) or a vanishing tip radius let the tip through the whole depth
  // (δ = pL = 1.27 mm) with validity "within" and no word. Hertz's law holds for δ ≪ R: beyond
  // 0.1 R the pass warns and is at the edge; the base case (δ of micrometres, 0.02 R) does not.
  for (const char* key : {"surface.youngs_modulus_pa=1e3", "contact.tip_radius_m=1e-9"}) {
    const PassResult r = run_case(build_case(load_config_string("", {"contact.model=hertz", key})));
    EXPECT_TRUE(warns_of(r, "exceeds")) << key;
    EXPECT_TRUE(warns_of(r, "a tenth of the tip radius")) << key;
    EXPECT_NE(r.summary.validity, Validity::within) << key;
  }
  for (const char* speed : {"hub.speed_rpm=550", "hub.speed_rpm=3000"}) {
    const PassResult r = run_case(build_case(load_config_string("", {"contact.model=hertz", speed})));
    ASSERT_FALSE(r.failure) << speed;
    EXPECT_FALSE(warns_of(r, "a tenth of the tip radius")) << speed;
  }
}

TEST(ReliabilityIII, ABrushWithNoFinishedFilamentReportsNoResultNotZero) {
  // Every filament of the example brush stops on its second impact: the summary said "mean force
  // 0.0000 N", "no filament touched the surface" and sweep.csv held 0. A brush without a finished
  // filament has no force, torque, power, zone or ledger: NaN (null in summary.json, an empty cell
  // in sweep.csv).
  const Config config = load_config(std::string(ROTBEAM_SOURCE_DIR) + "/examples/brush.toml", {"simulation.max_impacts=1"});
  const BrushResult r = run_brush(config);
  const BrushSummary& s = r.summary;
  ASSERT_GT(s.reaching, 0);
  ASSERT_EQ(s.steady + s.not_steady, 0);
  for (double v : {s.mean_normal_force_n, s.mean_tangential_force_n, s.peak_normal_force_n, s.mean_hub_torque_n_m,
                   s.mean_hub_power_w, s.force_ratio, s.contact_zone_width_m, s.ledger[LedgerTerm::hub_work]})
    EXPECT_TRUE(std::isnan(v)) << v;
  // summary.json: written as null.
  const nlohmann::json j = nlohmann::json::parse(brush_summary_json(r, config).dump());
  EXPECT_TRUE(j.at("mean_normal_force_n").is_null());
  // One finished filament is a result again (the sums over it are numbers).
  const BrushResult one = run_brush(load_config(std::string(ROTBEAM_SOURCE_DIR) + "/examples/brush.toml",
                                                {"brush.filaments=1", "brush.rows=1"}));
  EXPECT_GT(one.summary.mean_normal_force_n, 0.0);
}

TEST(ReliabilityIII, ALongPassIsAnnouncedAndReportsProgressInALog) {
  // The elastica at 80 modes took two minutes for 1546 steps with nothing said where stderr is not a
  // terminal. The pass is announced with its step count and the measured time of a step, and a log
  // gets a progress line after 10 s; SIGINT at 14 s ends it as interrupted.
  const std::string out = ::testing::TempDir() + "rotbeam_rel3_long_" + std::to_string(getpid());
  const std::string err = out + ".stderr";
  const std::string cmd = std::string("timeout -s INT 14 ") + ROTBEAM_CLI +
                          " run --set beam.theory=elastica --set beam.modes=80 -o " + out + " > /dev/null 2> " + err;
  const int status = std::system(cmd.c_str());
  std::ifstream in(err);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 124) << text;  // timeout's code: it had to stop it
  EXPECT_NE(text.find("rotbeam: note: the pass takes at least "), std::string::npos) << text;
  EXPECT_NE(text.find("ms each (80 modes, beam.theory = \"elastica\")"), std::string::npos) << text;
  EXPECT_NE(text.find("rotbeam: progress: θ = "), std::string::npos) << text;
  EXPECT_NE(text.find("interrupted at t = "), std::string::npos) << text;
  std::filesystem::remove_all(out);
  std::filesystem::remove(err);
}

// max |y_t|/L is the maximum of the pass, between the steps too (found on the dense output): at the
// default tolerance it agrees with a pass whose steps are bounded to 0.1 µs, where the ends of the
// steps sample the deflection finely, on cases beyond the base one (it was up to 2.9e-5 low).
TEST(ReliabilityIII, TheLargestDeflectionIsFoundBetweenTheSteps) {
  const std::vector<std::vector<std::string>> cases = {
      {},
      {"hub.speed_rpm=3000", "surface.friction=0.1"},
      {"hub.speed_rpm=1000", "initial.modal_velocity=[1,0,0,0,0]", "surface.depth_fraction=0.01"},
      {"beam.modes=8", "hub.speed_rpm=2000", "impact.restitution=0.6"},
  };
  for (const auto& sets : cases) {
    std::vector<std::string> fine = sets;
    fine.push_back("simulation.max_step_s=1e-7");
    const PassResult a = run_case(build_case(load_config_string("", sets)));
    const PassResult b = run_case(build_case(load_config_string("", fine)));
    ASSERT_FALSE(a.failure || b.failure);
    const double x = a.summary.max_tip_deflection_ratio, y = b.summary.max_tip_deflection_ratio;
    // Both passes carry the tolerance's error (rtol 1e-9) in the state; the steps of 0.1 µs still
    // sample the maximum to ≈ (ω_n · 0.1 µs)² / 8 ≈ 1e-8 of it at the highest mode's ω_n.
    EXPECT_NEAR(x, y, 1e-7 * y) << (sets.empty() ? "base" : sets[0]);
  }
}
