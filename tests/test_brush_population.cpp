// The brush as a population (brush.method = "population", docs/brush.md), checked against the
// filament-by-filament route on the same drawn filaments: its sums within its own error estimate,
// exact where every filament is a node, the workpiece's phase-shifted sum, the counts, its
// independence of the thread count, and the configuration and command line.
#include "rotbeam/brush.hpp"
#include "rotbeam/brush_output.hpp"
#include "rotbeam/config.hpp"
#include "rotbeam/pass.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

using namespace rotbeam;

namespace {

BrushResult brush(std::vector<std::string> sets, const std::string& method, int threads = 0) {
  sets.push_back("brush.method=\"" + method + "\"");
  BrushOptions o;
  o.threads = threads;
  return run_brush(load_config_string("", sets), o);
}

double rel(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

// A filament that settles in a few revolutions (about 0.1 s a run): 3 modes, 10 % damping, 3 % depth.
const std::vector<std::string> kFast = {"beam.modes=3", "beam.damping_ratio=0.1", "surface.friction=0.2",
                                        "surface.depth_fraction=0.03"};

}  // namespace

// The population's sums against the filament-by-filament route over the same 60 filaments (lengths
// scattered by 5 %, some too short to reach; diameters by 2 %; phases jittered): within 1 % (the
// issue's target) and within twice the population's own estimate (the estimate is honest), with
// fewer runs than filaments. Seen to fail when the estimate drops its 1/3 or its hat weights.
TEST(BrushPopulation, AgreesWithTheFilamentRouteWithinItsOwnEstimate) {
  for (const std::vector<std::string>& scatter :
       {std::vector<std::string>{"brush.length_scatter=0.05"},
        std::vector<std::string>{"brush.length_scatter=0.05", "brush.diameter_scatter=0.02", "brush.phase_jitter_deg=2"}}) {
    std::vector<std::string> sets = kFast;
    sets.insert(sets.end(), scatter.begin(), scatter.end());
    sets.insert(sets.end(), {"brush.filaments=60", "brush.seed=3", "brush.population_tolerance=0.002",
                             "brush.population_max_runs=40"});
    const BrushResult f = brush(sets, "filaments"), p = brush(sets, "population");
    ASSERT_FALSE(f.summary.failure);
    ASSERT_FALSE(p.summary.failure);
    ASSERT_TRUE(p.summary.population);
    const PopulationEstimate& e = *p.summary.population;
    EXPECT_LT(p.summary.distinct_filaments, f.summary.reaching) << scatter.size();
    EXPECT_EQ(p.summary.reaching, f.summary.reaching);
    EXPECT_EQ(p.summary.steady + p.summary.not_steady, f.summary.steady + f.summary.not_steady);
    const double normal = rel(p.summary.mean_normal_force_n, f.summary.mean_normal_force_n);
    const double torque = rel(p.summary.mean_hub_torque_n_m, f.summary.mean_hub_torque_n_m);
    EXPECT_LT(normal, 0.01) << scatter.size();
    EXPECT_LT(torque, 0.01) << scatter.size();
    EXPECT_LE(normal, 2.0 * e.normal_force_error) << scatter.size();
    EXPECT_LE(torque, 2.0 * e.hub_torque_error) << scatter.size();
    EXPECT_DOUBLE_EQ(p.summary.mean_hub_power_w, p.summary.mean_hub_torque_n_m * 550 * M_PI / 30);
    // The workpiece carries the means' momentum, and the profile the mean filament's.
    double bins = 0, profile = 0;
    for (const ForceBin& b : p.workpiece) bins += b.normal_impulse_n_s;
    for (const ForceBin& b : p.profile) profile += b.normal_impulse_n_s;
    const double period = p.summary.revolution_period_s;
    EXPECT_LT(rel(bins / period, p.summary.mean_normal_force_n), 1e-9);
    EXPECT_LT(rel(profile * p.summary.filaments / period, p.summary.mean_normal_force_n), 1e-9);
    // Each filament's estimate sums to the brush's.
    double sum = 0;
    for (const FilamentEstimate& est : p.estimates) sum += est.mean_normal_force_n;
    EXPECT_LT(rel(sum, p.summary.mean_normal_force_n), 1e-9);
  }
}

// Without scatter every filament is the one node: the population is the filament route to
// rounding, the workpiece bin by bin included (4 filaments 90° apart: phases on whole fine cells).
TEST(BrushPopulation, IdenticalFilamentsAreTheFilamentRoute) {
  std::vector<std::string> sets = kFast;
  sets.push_back("brush.filaments=4");
  const BrushResult f = brush(sets, "filaments"), p = brush(sets, "population");
  ASSERT_FALSE(p.summary.failure);
  EXPECT_EQ(p.summary.distinct_filaments, 1);
  EXPECT_LT(rel(p.summary.mean_normal_force_n, f.summary.mean_normal_force_n), 1e-12);
  EXPECT_LT(rel(p.summary.mean_hub_torque_n_m, f.summary.mean_hub_torque_n_m), 1e-12);
  EXPECT_LT(rel(p.summary.ledger[LedgerTerm::friction_work], f.summary.ledger[LedgerTerm::friction_work]), 1e-12);
  ASSERT_EQ(p.workpiece.size(), f.workpiece.size());
  double largest = 0;
  for (const ForceBin& b : f.workpiece) largest = std::max(largest, b.normal_impulse_n_s);
  for (std::size_t k = 0; k < f.workpiece.size(); ++k) {
    EXPECT_NEAR(p.workpiece[k].normal_impulse_n_s, f.workpiece[k].normal_impulse_n_s, 1e-12 * largest) << k;
    EXPECT_EQ(p.workpiece[k].impacts, f.workpiece[k].impacts) << k;
  }
  EXPECT_TRUE(p.summary.population->converged);
}

// The same brush on one thread and on two: the same files, byte for byte.
TEST(BrushPopulation, IndependentOfTheThreadCount) {
  std::vector<std::string> sets = kFast;
  sets.insert(sets.end(), {"brush.filaments=30", "brush.length_scatter=0.04", "brush.diameter_scatter=0.02",
                           "brush.phase_jitter_deg=3", "brush.population_max_runs=20"});
  const BrushResult a = brush(sets, "population", 1), b = brush(sets, "population", 2);
  const double omega = 550 * M_PI / 30;
  EXPECT_EQ(workpiece_csv(a, omega), workpiece_csv(b, omega));
  EXPECT_EQ(profile_csv(a, omega), profile_csv(b, omega));
  EXPECT_EQ(filaments_csv(a), filaments_csv(b));
  EXPECT_EQ(representatives_csv(a), representatives_csv(b));
}

// The budget: a population that cannot meet its tolerance within brush.population_max_runs says so
// (a warning naming both keys) and reports its estimate; it never runs more than the budget.
TEST(BrushPopulation, ABudgetTooSmallIsSaid) {
  std::vector<std::string> sets = kFast;
  sets.insert(sets.end(), {"brush.filaments=40", "brush.length_scatter=0.05", "brush.diameter_scatter=0.02",
                           "brush.population_tolerance=1e-6", "brush.population_max_runs=16"});
  const BrushResult p = brush(sets, "population");
  ASSERT_TRUE(p.summary.population);
  EXPECT_FALSE(p.summary.population->converged);
  EXPECT_LE(p.summary.distinct_filaments, 16);
  bool said = false;
  for (const std::string& w : p.summary.warnings)
    said |= w.find("brush.population_max_runs") != std::string::npos && w.find("brush.population_tolerance") != std::string::npos;
  EXPECT_TRUE(said);
}

// The keys: brush.method's words, the tolerance and the budget's ranges, each refused by name.
TEST(BrushPopulation, ConfigurationRefusals) {
  const auto refused = [](const std::string& set, const std::string& key) {
    try {
      load_config_string("", {"brush.filaments=3", set});
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      return true;
    }
    return false;
  };
  EXPECT_TRUE(refused("brush.method=\"sample\"", "brush.method"));
  EXPECT_TRUE(refused("brush.population_tolerance=0", "brush.population_tolerance"));
  EXPECT_TRUE(refused("brush.population_max_runs=14", "brush.population_max_runs"));
  EXPECT_NO_THROW(load_config_string("", {"brush.filaments=3", "brush.method=\"population\""}));
}

// The workpiece's spectrum: N identical filaments equally spaced make a force that repeats N times a
// revolution, so only harmonics at multiples of N carry amplitude (the others cancel to rounding),
// and order 0 is the mean force. With 5 filaments, order 5's amplitude is 5 times a single filament's
// order-5 amplitude (the copies add in phase there): a lost copy, a wrong scale or the one-sided
// factor 2 moves it by O(1).
TEST(BrushSpectrum, IdenticalFilamentsHaveLinesAtMultiplesOfTheirNumber) {
  std::vector<std::string> one = kFast, five = kFast;
  one.push_back("brush.filaments=1");
  five.push_back("brush.filaments=5");
  const BrushResult a = brush(one, "filaments"), b = brush(five, "filaments");
  const double omega = 550 * M_PI / 30;
  const std::vector<SpectrumLine> sa = workpiece_spectrum(a, omega), sb = workpiece_spectrum(b, omega);
  ASSERT_EQ(sa.size(), sb.size());
  ASSERT_GT(sa.size(), 100u);
  EXPECT_LT(rel(sb[0].normal_force_n, b.summary.mean_normal_force_n), 1e-12);
  EXPECT_LT(rel(sb[0].hub_torque_n_m, b.summary.mean_hub_torque_n_m), 1e-12);
  EXPECT_NEAR(sa[1].frequency_hz, omega / (2 * M_PI), 1e-12);
  for (std::size_t h = 1; h < 60; ++h) {
    if (h % 5 == 0) {
      EXPECT_LT(rel(sb[h].normal_force_n, 5 * sa[h].normal_force_n), 1e-9) << h;
    } else {
      EXPECT_LT(sb[h].normal_force_n, 1e-9 * sb[0].normal_force_n) << h;
    }
  }
}

// The spread between seeds: √N·σ/|sum| of the filaments' own values, computed here from the
// filament route's per-filament means (the clear ones as 0); zero without scatter. The roll-up's
// counts against the filaments' own depths and validity.
TEST(BrushSpread, TheSeedSpreadIsTheFilamentsStandardDeviation) {
  std::vector<std::string> sets = kFast;
  sets.insert(sets.end(), {"brush.filaments=24", "brush.length_scatter=0.05", "brush.seed=4"});
  const BrushResult f = brush(sets, "filaments");
  double sum = 0, sum2 = 0;
  int barely = 0;
  for (const BrushFilament& x : f.filaments) {
    const double v = x.depth_fraction > 0 ? f.distinct[x.group].mean_normal_force_n : 0.0;
    sum += v, sum2 += v * v;
    barely += x.depth_fraction > 0 && x.depth_fraction < 0.25 * 0.03;
  }
  const double n = f.filaments.size(), var = (sum2 - sum * sum / n) / (n - 1);
  EXPECT_LT(rel(f.summary.seed_spread_normal_force, std::sqrt(n * var) / sum), 1e-9);
  EXPECT_EQ(f.summary.barely_reaching, barely);
  std::vector<std::string> same = kFast;
  same.push_back("brush.filaments=4");
  EXPECT_EQ(brush(same, "filaments").summary.seed_spread_normal_force, 0.0);
}

// Runs that fail: every output leaves out the same filaments. Filaments with more than 60 impacts a
// revolution stop on simulation.max_impacts; the population's sums, its filaments' values and its
// workpiece then agree (to rounding), it is not converged while a filament leans on a failed run,
// and the filaments it counts failed are those the filament route counts failed, or more.
TEST(BrushPopulation, FailedRunsAreLeftOutOfEverySum) {
  std::vector<std::string> sets = kFast;
  sets.insert(sets.end(), {"brush.filaments=60", "brush.length_scatter=0.05", "simulation.max_impacts=60",
                           "brush.population_max_runs=60"});
  const BrushResult f = brush(sets, "filaments"), p = brush(sets, "population");
  ASSERT_GT(f.summary.failed, 0);
  ASSERT_GT(p.summary.failed, 0);
  double estimates = 0, bins = 0;
  for (const FilamentEstimate& e : p.estimates) estimates += e.mean_normal_force_n;
  for (const ForceBin& b : p.workpiece) bins += b.normal_impulse_n_s;
  EXPECT_LT(rel(estimates, p.summary.mean_normal_force_n), 1e-9);
  EXPECT_LT(rel(bins / p.summary.revolution_period_s, p.summary.mean_normal_force_n), 1e-9);
  EXPECT_GE(p.summary.failed, f.summary.failed);
  if (p.summary.failed == f.summary.failed) {
    EXPECT_EQ(p.summary.failed_indices, f.summary.failed_indices);
    EXPECT_TRUE(p.summary.population->converged || p.summary.population->normal_force_error > 0);
  } else {
    EXPECT_FALSE(p.summary.population->converged);
  }
}

// A brush of fewer reaching filaments than the first grid has nodes runs each on its own: the
// filament route's sums exactly, with no estimated error.
TEST(BrushPopulation, FewFilamentsRunOnTheirOwn) {
  std::vector<std::string> sets = kFast;
  sets.insert(sets.end(), {"brush.filaments=6", "brush.length_scatter=0.02", "brush.diameter_scatter=0.02",
                           "brush.phase_jitter_deg=3"});
  const BrushResult f = brush(sets, "filaments"), p = brush(sets, "population");
  EXPECT_EQ(p.summary.population->exact_filaments, f.summary.reaching);
  EXPECT_LT(rel(p.summary.mean_normal_force_n, f.summary.mean_normal_force_n), 1e-12);
  EXPECT_LT(rel(p.summary.mean_hub_torque_n_m, f.summary.mean_hub_torque_n_m), 1e-12);
  EXPECT_TRUE(p.summary.population->converged);
  EXPECT_EQ(p.summary.population->normal_force_error, 0.0);
}
