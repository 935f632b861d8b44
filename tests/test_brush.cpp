// A brush (docs/brush.md): its sums checked against single-filament runs computed independently
// (run_case without [brush], whose revolution records and force bins the recorder keeps by its own
// route), the phase-shifted sum bin by bin, the hub's angular impulse against the revolutions'
// hub work, the ledger, the scatter's draws and their reproducibility, and the configuration rules.
#include "rotbeam/brush.hpp"
#include "rotbeam/brush_output.hpp"
#include "rotbeam/case.hpp"
#include "rotbeam/config.hpp"
#include "rotbeam/pass_output.hpp"
#include "rotbeam/sweep.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

using namespace rotbeam;

namespace {

PassResult single(const std::vector<std::string>& sets) {
  std::vector<std::string> s = sets;
  s.push_back("simulation.until_steady=true");
  s.push_back("simulation.multipliers=false");
  return run_case(build_case(load_config_string("", s)));
}

BrushResult brush(const std::vector<std::string>& sets, int threads = 0) {
  BrushOptions o;
  o.threads = threads;
  return run_brush(load_config_string("", sets), o);
}

namespace fs = std::filesystem;

// The CLI's exit status and its stdout and stderr together.
std::pair<int, std::string> cli(const std::string& args) {
  const std::string cmd = std::string(ROTBEAM_CLI) + " " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  std::array<char, 4096> buf{};
  while (std::size_t got = fread(buf.data(), 1, buf.size(), pipe)) out.append(buf.data(), got);
  const int st = pclose(pipe);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

std::string fresh(const std::string& name) {
  const fs::path p = fs::path(::testing::TempDir()) / ("rotbeam_brush_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(p);
  return p.string();
}

double rel(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

// Cases beyond the base one: another speed, friction, restitution law, depth, damping.
const std::vector<std::vector<std::string>> kCases = {
    {"beam.damping_ratio=0.05"},
    {"beam.damping_ratio=0.05", "hub.speed_rpm=3000", "surface.friction=0.2"},
    {"beam.damping_ratio=0.05", "impact.restitution=0.6", "surface.depth_fraction=0.01", "surface.friction=0.2"},
};

}  // namespace

// N identical filaments give N times one filament's steady-state means: the mean normal force of
// one filament is its steady revolution's normal impulse over the revolution's period. 1e-9 is the
// issue's tolerance; both sides come from the same integration (the brush reruns the filament), so
// the agreement is to rounding, and a lost factor (a copy, the 1/m weight, the period) is O(1).
TEST(Brush, IdenticalFilamentsGiveNTimesOneFilament) {
  for (const auto& base : kCases) {
    const PassResult one = single(base);
    ASSERT_FALSE(one.failure) << one.failure->message;
    ASSERT_TRUE(one.summary.steady_state.reached);
    ASSERT_EQ(one.summary.steady_state.period_revolutions, 1);
    const RevolutionRecord& last = one.revolutions.back();
    const double period = last.t_end - last.t_start;
    for (int n : {1, 3, 7}) {
      std::vector<std::string> sets = base;
      sets.push_back("brush.filaments=" + std::to_string(n));
      const BrushResult b = brush(sets);
      ASSERT_FALSE(b.summary.failure);
      EXPECT_EQ(b.summary.distinct_filaments, 1);
      EXPECT_LT(rel(b.summary.mean_normal_force_n, n * last.ledger[LedgerTerm::normal_impulse] / period), 1e-9) << n;
      EXPECT_LT(rel(b.summary.mean_hub_torque_n_m, n * last.mean_hub_torque_n_m), 1e-9) << n;
      EXPECT_LT(rel(b.summary.mean_hub_power_w, n * last.mean_hub_power_w), 1e-9) << n;
      EXPECT_LT(rel(b.summary.ledger[LedgerTerm::hub_work], n * last.ledger[LedgerTerm::hub_work]), 1e-9) << n;
      EXPECT_LT(rel(b.summary.ledger[LedgerTerm::friction_work], n * last.ledger[LedgerTerm::friction_work]), 1e-9) << n;
      // The workpiece's bins carry the same momentum as the means.
      double normal = 0, hub = 0;
      for (const ForceBin& f : b.workpiece) {
        normal += f.normal_impulse_n_s;
        hub += f.hub_angular_impulse_n_m_s;
      }
      EXPECT_LT(rel(normal, n * last.ledger[LedgerTerm::normal_impulse]), 1e-9) << n;
      // The profile is the mean filament at its own angle: n times it carries the same momentum.
      double profile = 0;
      for (const ForceBin& f : b.profile) profile += f.normal_impulse_n_s;
      EXPECT_LT(rel(n * profile, n * last.ledger[LedgerTerm::normal_impulse]), 1e-12) << n;
      // ω Σ(hub angular impulse) over a revolution is its hub work: the deliveries telescope ΔH_z.
      const double omega = 2.0 * M_PI / period;
      EXPECT_LT(rel(omega * hub, n * last.ledger[LedgerTerm::hub_work]), 1e-9) << n;
    }
  }
}

// The phase-shifted sum in time: with phases that are whole bins (2 filaments 180° apart in each of
// 2 rows offset by 30°: phases 0°, 180°, 30°, 210°; 0.5° bins), bin k of the brush is Σ_j bin
// (k + phase_j/0.5°) of the single filament's own force_bins (which the recorder fills by its own
// route, not from the deliveries). 1e-12 of the largest bin: the same steps summed in another
// order. The phases are not symmetric, so a filament shifted the wrong way moves whole bins.
TEST(Brush, WorkpieceIsThePhaseShiftedSumOfOneFilament) {
  for (const auto& base : kCases) {
    const PassResult one = single(base);
    ASSERT_FALSE(one.failure) << one.failure->message;
    std::vector<std::string> sets = base;
    sets.insert(sets.end(), {"brush.filaments=2", "brush.rows=2", "brush.row_phase_deg=30"});
    const BrushResult b = brush(sets);
    ASSERT_EQ(b.workpiece.size(), 720u);
    std::vector<double> single_bins(720, 0.0), single_tangential(720, 0.0);
    std::vector<int> single_impacts(720, 0);
    for (const ForceBin& f : one.force_bins) {
      const int k = static_cast<int>(std::lround((f.from_deg + 180.0) / 0.5));
      single_bins[k] = f.normal_impulse_n_s;
      single_tangential[k] = f.tangential_impulse_n_s;
      single_impacts[k] = f.impacts;
    }
    const double largest = *std::max_element(single_bins.begin(), single_bins.end());
    ASSERT_GT(largest, 0.0);
    for (int k = 0; k < 720; ++k) {
      double expected = 0, expected_t = 0;
      int impacts = 0;
      for (int shift : {0, 360, 60, 420}) {
        // A filament φ ahead reaches relative angle α when the reference is at α − φ.
        const int from = (k + shift) % 720;
        expected += single_bins[from];
        expected_t += single_tangential[from];
        impacts += single_impacts[from];
      }
      EXPECT_NEAR(b.workpiece[k].normal_impulse_n_s, expected, 1e-12 * largest) << k;
      EXPECT_NEAR(b.workpiece[k].tangential_impulse_n_s, expected_t, 1e-12 * largest) << k;
      EXPECT_EQ(b.workpiece[k].impacts, impacts) << k;
    }
  }
}

// The brush's ledger per revolution closes: hub + friction + damping + impact loss = energy change
// (≈ 0 on the periodic orbit). The residual is the filaments' own revolution ledgers', ≈ rtol·|E|;
// 1e-8 of the hub work, as for one filament (Revolutions.LedgerClosesEveryRevolution).
TEST(Brush, LedgerClosesPerRevolution) {
  std::vector<std::string> sets = kCases[0];
  sets.insert(sets.end(), {"brush.filaments=6", "brush.length_scatter=0.01", "brush.diameter_scatter=0.05", "brush.seed=7"});
  const BrushResult b = brush(sets);
  ASSERT_FALSE(b.summary.failure);
  const BrushSummary& s = b.summary;
  EXPECT_GT(s.distinct_filaments, 1);
  const double sum = s.ledger[LedgerTerm::hub_work] + s.ledger[LedgerTerm::friction_work] + s.ledger[LedgerTerm::surface_work] + s.ledger[LedgerTerm::damping_work] + s.ledger[LedgerTerm::impact_loss];
  EXPECT_LT(std::abs(sum - s.ledger.energy_change_j), 1e-8 * std::abs(s.ledger[LedgerTerm::hub_work]));
  EXPECT_LT(std::abs(s.ledger.energy_change_j), 1e-6 * std::abs(s.ledger[LedgerTerm::hub_work]));  // steady: the filaments end where they began
  EXPECT_GT(s.ledger[LedgerTerm::hub_work], 0.0);
  EXPECT_LT(s.ledger[LedgerTerm::friction_work], 0.0);
  EXPECT_LT(s.ledger[LedgerTerm::damping_work], 0.0);
}

// A seed gives the same brush, bit for bit, whatever the thread count; another seed another one.
TEST(Brush, ScatterIsReproducibleWithASeedAndIndependentOfThreads) {
  std::vector<std::string> sets = kCases[0];
  sets.insert(sets.end(), {"brush.filaments=3", "brush.length_scatter=0.01", "brush.phase_jitter_deg=2", "brush.seed=11"});
  const BrushResult a = brush(sets, 1), b = brush(sets, 2);
  const double omega = 550 * M_PI / 30;
  EXPECT_EQ(workpiece_csv(a, omega), workpiece_csv(b, omega));
  EXPECT_EQ(filaments_csv(a), filaments_csv(b));
  sets.back() = "brush.seed=12";
  const BrushResult c = brush(sets, 2);
  EXPECT_NE(filaments_csv(a), filaments_csv(c));
}

// The draws: L and D normal with the given relative standard deviations, truncated at ±3σ, phases
// equally spaced plus the jitter; three draws per filament, so setting one scatter leaves the
// others' values unchanged. Statistical bounds for 20 000 draws: the sample mean within 4σ/√N and
// the standard deviation of a ±3σ-truncated normal (0.9733σ) within 3 %.
TEST(Brush, DrawsHaveTheStatedDistributions) {
  const Config c = load_config_string("", {"brush.filaments=200", "brush.rows=100", "brush.length_scatter=0.05",
                                           "brush.diameter_scatter=0.1", "brush.seed=3"});
  const auto f = brush_filaments(c);
  ASSERT_EQ(f.size(), 20000u);
  const double l0 = 0.0635, d0 = 5.08e-4;
  double ml = 0, md = 0;
  for (const auto& x : f) ml += x.length_m / l0 - 1, md += x.diameter_m / d0 - 1;
  ml /= f.size(), md /= f.size();
  double vl = 0, vd = 0, worst = 0;
  for (const auto& x : f) {
    vl += std::pow(x.length_m / l0 - 1 - ml, 2), vd += std::pow(x.diameter_m / d0 - 1 - md, 2);
    worst = std::max(worst, std::abs(x.length_m / l0 - 1) / 0.05);
    EXPECT_NEAR(x.phase_deg, 360.0 * x.position / 200, 1e-12);  // no jitter, no row offset
    // The surface stays where the nominal depth puts it: p_k L_k − L_k = pL − L.
    EXPECT_NEAR(x.depth_fraction * x.length_m - x.length_m, 0.02 * l0 - l0, 1e-15);
  }
  EXPECT_LT(std::abs(ml), 4 * 0.05 / std::sqrt(f.size()));
  EXPECT_LT(std::abs(md), 4 * 0.1 / std::sqrt(f.size()));
  EXPECT_NEAR(std::sqrt(vl / f.size()) / (0.05 * 0.9733), 1.0, 0.03);
  EXPECT_NEAR(std::sqrt(vd / f.size()) / (0.1 * 0.9733), 1.0, 0.03);
  EXPECT_LE(worst, 3.0);
  EXPECT_GT(worst, 2.5);  // the tails are drawn
  // Without the diameter scatter the lengths are the same draws.
  const auto g = brush_filaments(load_config_string("", {"brush.filaments=200", "brush.rows=100",
                                                         "brush.length_scatter=0.05", "brush.seed=3"}));
  for (std::size_t i = 0; i < f.size(); i += 997) EXPECT_EQ(f[i].length_m, g[i].length_m);
  EXPECT_EQ(g[5].diameter_m, d0);
  // Rows offset in phase; jitter moves phases.
  const auto h = brush_filaments(load_config_string("", {"brush.filaments=4", "brush.rows=2", "brush.row_phase_deg=45"}));
  EXPECT_DOUBLE_EQ(h[5].phase_deg, 90.0 + 45.0);
  EXPECT_EQ(h[5].group, 0);  // identical: one distinct filament
}

// Filaments too short to reach the surface deliver nothing and are not run.
TEST(Brush, ShortFilamentsAreClear) {
  const Config c = load_config_string("", {"brush.filaments=400", "brush.length_scatter=0.3", "brush.seed=5"});
  int clear = 0;
  for (const auto& f : brush_filaments(c)) clear += f.depth_fraction <= 0.0;
  EXPECT_GT(clear, 100);  // a depth of 0.02 L is 0.07σ: about half the filaments are too short
  EXPECT_LT(clear, 300);
}

// Configuration rules: a brush always seeks the steady state; the size is bounded; keys are checked.
TEST(Brush, ConfigurationRules) {
  const Config c = load_config_string("", {"brush.filaments=3"});
  EXPECT_TRUE(c.simulation.until_steady);
  EXPECT_GT(c.simulation.revolutions, 0);
  EXPECT_TRUE(c.brush.has_value());
  EXPECT_FALSE(load_config_string("", {}).brush.has_value());
  const auto message = [](const std::vector<std::string>& sets) {
    try {
      load_config_string("", sets);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message({"brush.filaments=3", "simulation.until_steady=false"}).find("simulation.until_steady"), std::string::npos);
  EXPECT_NE(message({"brush.filaments=1000", "brush.rows=1000"}).find("brush.rows"), std::string::npos);
  EXPECT_NE(message({"brush.filaments=0"}).find("brush.filaments = 0"), std::string::npos);
  EXPECT_NE(message({"brush.length_scatter=0.5"}).find("brush.length_scatter"), std::string::npos);
  EXPECT_NE(message({"brush.seed=-1"}).find("brush.seed"), std::string::npos);
  EXPECT_NE(message({"brush.filamnets=3"}).find("did you mean"), std::string::npos);
  // A drawn filament that cannot be built (a diameter beyond its length) is bad input, named with
  // the filament, before anything runs.
  try {
    run_brush(load_config_string("", {"brush.filaments=50", "beam.diameter_m=0.05", "brush.diameter_scatter=0.3",
                                      "brush.seed=2"}));
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("brush: filament ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("beam.diameter_m"), std::string::npos) << e.what();
  }
  // The configuration round trip a filament goes through keeps every value.
  const Config d = load_config_string("", {"beam.damping_ratio=[0.1,0.2,0.3,0.4,0.5]", "hub.speed_rpm=777",
                                           "initial.modal_velocity=[0.1,0,0,0,0]", "simulation.revolutions=9",
                                           "simulation.until_steady=true", "output.history_revolutions=\"all\""});
  EXPECT_EQ(revalidate(d).to_json(), d.to_json());
}

// Brush maps: a sweep over brushes runs one brush per case, writes the brush's columns in sweep.csv,
// and resumes a finished case from its complete folder.
TEST(Brush, SweepOverBrushesWritesTheBrushColumnsAndResumes) {
  const std::string dir = fresh("sweep");
  SweepOptions options;
  options.dir = dir;
  options.jobs = 2;
  options.base_overrides = {"brush.filaments=2", "beam.damping_ratio=0.05"};
  const std::vector<SweepAxis> axes = {parse_sweep_axis("surface.depth_fraction=0.01,0.02")};
  const SweepReport first = run_sweep(axes, options);
  ASSERT_EQ(first.ran, 2);
  EXPECT_TRUE(first.brush);
  std::ifstream in(fs::path(dir) / "sweep.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("case,folder,surface.depth_fraction,status,mean_normal_force_n,mean_tangential_force_n,", 0), 0u)
      << header;
  EXPECT_NE(header.find(",force_ratio,"), std::string::npos);
  // Deeper, more force; each case's folder is a complete brush.
  EXPECT_GT(first.results[1].summary["mean_normal_force_n"].get<double>(),
            first.results[0].summary["mean_normal_force_n"].get<double>());
  EXPECT_TRUE(complete_run_folder(fs::path(dir) / "case-0001"));
  const SweepReport second = run_sweep(axes, options);
  EXPECT_EQ(second.resumed, 2);
  EXPECT_EQ(second.results[0].summary["mean_normal_force_n"], first.results[0].summary["mean_normal_force_n"]);
  // A damaged table makes its case incomplete: it runs again.
  {
    std::ofstream damage(fs::path(dir) / "case-0002" / "profile.csv", std::ios::app);
    damage << "x";
  }
  const SweepReport third = run_sweep(axes, options);
  EXPECT_EQ(third.resumed, 1);
  EXPECT_EQ(third.ran, 1);
  fs::remove_all(dir);
}

// The command line: `brush` writes its files; the one-filament commands refuse a brush; a brush
// needs its section; a run folder is not overwritten by a brush, nor a brush folder by a run.
TEST(Brush, CommandLine) {
  const std::string dir = fresh("cli");
  auto [code, out] = cli("brush --set brush.filaments=2 --set beam.damping_ratio=0.05 --quiet -o " + dir);
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("2 steady, 0 not steady, 0 failed, 0 clear"), std::string::npos) << out;
  for (const char* f : {"workpiece.csv", "profile.csv", "filaments.csv", "summary.json"})
    EXPECT_TRUE(fs::exists(fs::path(dir) / f)) << f;
  EXPECT_TRUE(complete_run_folder(dir));
  std::tie(code, out) = cli("run --set brush.filaments=2 -o " + dir + "-run");
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("rotbeam brush"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(dir + "-run"));
  std::tie(code, out) = cli("impact --set brush.rows=2");
  EXPECT_EQ(code, 2);
  std::tie(code, out) = cli("brush --set brush.filaments=2 -o ''");
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("an empty path"), std::string::npos) << out;
  std::tie(code, out) = cli("brush -o " + dir + "-none");
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("no [brush] section"), std::string::npos) << out;
  std::tie(code, out) = cli("run -o " + dir);
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("holds a brush"), std::string::npos) << out;
  EXPECT_TRUE(complete_run_folder(dir));  // untouched
  // A reproduction's folder is not mixed with a brush either.
  fs::create_directories(dir + "-rep");
  std::ofstream(dir + "-rep/manifest.json") << "{}\n";
  std::ofstream(dir + "-rep/report.md") << "# report\n";
  std::tie(code, out) = cli("brush --set brush.filaments=2 -o " + dir + "-rep");
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("holds a reproduction"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(dir + "-rep/workpiece.csv"));
  fs::remove_all(dir + "-rep");
  std::tie(code, out) = cli("brush --set brush.filaments=2 --set brush.seed=-3 -o " + dir);
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("brush.seed = -3"), std::string::npos) << out;
  fs::remove_all(dir);
}

// A brush whose filaments partly fail (the thesis scheme stops on Painlevé points the adaptive one
// resolves): exit 11, one line naming the first failure and the count, the failed filaments listed
// in summary.json and marked in filaments.csv, and the share of the force they miss estimated from
// the finished filament of the nearest depth fraction — recomputed here from filaments.csv.
TEST(Brush, APartialBrushNamesWhatFailedAndEstimatesWhatItMisses) {
  const std::string dir = fresh("partial");
  auto [code, out] = cli("brush --set brush.filaments=4 --set hub.speed_rpm=1000 --set surface.friction=0.4 "
                         "--set beam.damping_ratio=0.03 --set brush.length_scatter=0.03 --set brush.seed=3 "
                         "--set simulation.scheme=thesis --set simulation.revolutions=6 --quiet -o " + dir);
  ASSERT_EQ(code, 11) << out;
  const auto at = out.find("rotbeam: error: partial brush: ");
  ASSERT_NE(at, std::string::npos) << out;
  EXPECT_EQ(std::count(out.begin() + at, out.end(), '\n'), 1) << out;
  EXPECT_NE(out.find("failed (painleve) at t = "), std::string::npos) << out;
  std::ifstream js(dir + "/summary.json");
  const nlohmann::json j = nlohmann::json::parse(js);
  // filaments.csv: filament, …, depth_fraction (6), …, reaches (8), status (9), …, mean_normal_force_n (12).
  std::ifstream csv(dir + "/filaments.csv");
  std::string line;
  std::getline(csv, line);
  struct Row { int filament; double depth, force; bool failed; };
  std::vector<Row> rows;
  while (std::getline(csv, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> c;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) c.push_back(cell);
    if (c[8] != "true") continue;
    rows.push_back({std::stoi(c[0]), std::stod(c[6]), std::stod(c[12]), c[9] == "failed"});
  }
  std::vector<int> failed;
  double finished = 0, missing = 0;
  for (const Row& r : rows) {
    if (!r.failed) {
      finished += r.force;
      continue;
    }
    failed.push_back(r.filament);
    const Row* nearest = nullptr;
    for (const Row& g : rows)
      if (!g.failed && (!nearest || std::abs(g.depth - r.depth) < std::abs(nearest->depth - r.depth))) nearest = &g;
    ASSERT_NE(nearest, nullptr);
    missing += nearest->force;
  }
  ASSERT_FALSE(failed.empty());
  ASSERT_LT(failed.size(), rows.size());
  EXPECT_EQ(j["failed_filaments"].get<int>(), static_cast<int>(failed.size()));
  EXPECT_EQ(j["failed_filament_list"].get<std::vector<int>>(), failed);
  // filaments.csv carries 17 digits: the estimate agrees to round-off.
  EXPECT_NEAR(j["missing_force_fraction"].get<double>(), missing / (missing + finished), 1e-12);
  EXPECT_GT(j["missing_force_fraction"].get<double>(), 0.0);
  EXPECT_NE(out.find(std::to_string(failed.size()) + " filaments of " + std::to_string(rows.size()) + " failed"),
            std::string::npos)
      << out;
  fs::remove_all(dir);
}
