// Continuation of a filament's orbits (orbit_continuation.hpp) against brute force: every stable point
// of a branch over the hub speed is the steady state a brute-force run reaches at that speed, with
// the multipliers of simulation.multipliers there; the files and the errors a user meets.
#include "rotbeam/case.hpp"
#include "rotbeam/config.hpp"
#include "rotbeam/continuation_output.hpp"
#include "rotbeam/orbit_continuation.hpp"
#include "rotbeam/steady_state.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

using namespace rotbeam;

namespace {

std::vector<std::string> with(std::vector<std::string> sets, const std::vector<std::string>& more) {
  sets.insert(sets.end(), more.begin(), more.end());
  return sets;
}

ConfigAtValue loader(const std::vector<std::string>& sets, const std::string& key) {
  return [sets, key](const std::string& literal) { return load_config_string("", with(sets, {key + "=" + literal})); };
}

}  // namespace

// A filament rubbing a two-lobe casing (examples/casing-rub.toml's: 2 % damping, μ = 0.02) from
// 1000 to 1006 rpm, where its orbit rubs each lobe once a revolution with 4 impacts. The points are
// converged to a relative residual of 1e-10 with rtol = 1e-11 (the map's noise ≈ 1e-11); a brute-force
// run to a section distance of 1e-10 with multipliers |μ| ≤ 0.3 is within ≈ 1.5e-10 of its fixed
// point. The 1e-6 therefore holds with margin, while a point off the orbit by a wrong
// restart scale or a wrong parameter (a case built at another speed) is off by 1e-3 or more. The
// multipliers are both central differences with δ = 1e-5‖z‖ at states 1e-10 apart: 1e-4 (the
// issue's) holds; a Jacobian taken at the wrong speed differs by 1e-2.
TEST(OrbitContinuation, StablePointsAreTheBruteForceSteadyStates) {
  const std::vector<std::string> sets = {"surface.shape=\"casing\"", "surface.clearance_m=1e-4", "surface.lobes=2",
                                         "surface.lobe_amplitude_m=3e-4", "surface.lobe_law=\"cosine\"",
                                         "surface.friction=0.02", "beam.damping_ratio=0.02", "simulation.rtol=1e-11"};
  OrbitContinuationOptions o;
  o.tolerance = 1e-10;
  o.parameter = "hub.speed_rpm";
  o.from = 1000;
  o.to = 1006;
  o.settings.threads = 2;
  o.settings.initial_step = 0.1;
  o.settings.max_step = 0.25;
  const OrbitContinuation run = continue_orbits(loader(sets, o.parameter), o);
  ASSERT_FALSE(run.result.points.empty()) << run.start_note;
  ASSERT_FALSE(run.result.failure) << run.result.failure->message;
  EXPECT_EQ(run.period, 1);
  EXPECT_NEAR(run.result.points.back().parameter, 1006.0, 1e-9);
  EXPECT_EQ(run.result.branches.size(), 1u);
  int checked = 0;
  for (std::size_t k = 0; k < run.result.points.size(); k += 2) {
    const BranchPoint& p = run.result.points[k];
    if (!p.stable) continue;
    const Case c = build_case(load_config_string(
        "", with(sets, {"hub.speed_rpm=" + parameter_literal(p.parameter), "simulation.until_steady=true",
                        "simulation.steady_tolerance=1e-10",
                        "simulation.steady_method=\"brute_force\"", "simulation.revolutions=400",
                        "simulation.multipliers=true"})));
    const PassResult b = run_case(c);
    ASSERT_FALSE(b.failure) << b.failure->message;
    const SteadyState& st = b.summary.steady_state;
    ASSERT_TRUE(st.reached) << st.note;
    ASSERT_EQ(st.period_revolutions, 1);
    const Eigen::VectorXd zb = section_state(*c.beam, b.final_q, b.final_qd);
    EXPECT_LE(section_distance(zb, p.z), 1e-6) << "at " << p.parameter << " rpm";
    ASSERT_EQ(st.multipliers.size(), p.multipliers.size());
    for (std::size_t i = 0; i < p.multipliers.size(); ++i) {
      EXPECT_NEAR(p.multipliers[i].magnitude(), st.multipliers[i].magnitude(), 1e-4) << p.parameter << " rpm, μ" << i;
      EXPECT_NEAR(std::abs(p.multipliers[i].im), std::abs(st.multipliers[i].im), 1e-4) << p.parameter << " rpm, μ" << i;
    }
    // The metrics of the period are the brute-force orbit's revolution.
    EXPECT_EQ(p.metrics.impacts, b.summary.last_revolution->impacts);
    EXPECT_NEAR(p.metrics.mean_hub_power_w, b.summary.mean_hub_power_w, 1e-5 * std::abs(b.summary.mean_hub_power_w));
    ++checked;
  }
  EXPECT_GE(checked, 2);

  // The files: one row per point, the columns of the declared header, summary.json last.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "rotbeam-test-continuation";
  std::filesystem::remove_all(dir);
  {
    ContinuationFiles files(dir);
    files.commit(run);
  }
  std::ifstream csv(dir / "branch.csv");
  std::string line;
  int rows = -1;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, static_cast<int>(run.result.points.size()));
  std::ifstream js(dir / "summary.json");
  const nlohmann::json j = nlohmann::json::parse(js);
  EXPECT_EQ(j["kind"], "continuation");
  EXPECT_EQ(j["parameter"], "hub.speed_rpm");
  EXPECT_EQ(j["points"], run.result.points.size());
  std::filesystem::remove_all(dir);
}

TEST(OrbitContinuation, BadInputNamesTheKey) {
  const std::vector<std::string> sets = {"beam.damping_ratio=0.03"};
  OrbitContinuationOptions o;
  o.from = 1;
  o.to = 2;
  o.parameter = "hub.speed";
  EXPECT_THROW(continue_orbits(loader(sets, o.parameter), o), ConfigError);
  o.parameter = "beam.modes";
  o.from = 3;
  o.to = 4;
  try {
    continue_orbits(loader(sets, o.parameter), o);
    FAIL() << "beam.modes accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("beam.modes"), std::string::npos) << e.what();
  }
  o.parameter = "hub.speed_rpm";
  o.from = o.to = 550;
  try {
    continue_orbits(loader(sets, o.parameter), o);
    FAIL() << "an empty range accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos) << e.what();
  }
}
