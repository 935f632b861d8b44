// The periodic steady state (docs/model.md §11, docs/model.md "Many revolutions"): shooting (Newton on the
// one-revolution map) against brute force, the Floquet multipliers against the decay of a small
// perturbation, and the report of a search that does not converge.
#include "rotbeam/case.hpp"
#include "rotbeam/config.hpp"
#include "rotbeam/steady_state.hpp"

#include <cmath>
#include <gtest/gtest.h>

using namespace rotbeam;

namespace {

std::vector<std::string> with(std::vector<std::string> sets, const std::vector<std::string>& more) {
  sets.insert(sets.end(), more.begin(), more.end());
  return sets;
}

Eigen::VectorXd final_section(const Case& c, const PassResult& r) {
  return section_state(*c.beam, r.final_q, r.final_qd);
}

}  // namespace

// Where both converge they find the same orbit. Both stop when the section state changes by less
// than tol = 1e-9 over the period; with multipliers |μ| ≤ 0.5 the state is then within ≈ tol/(1 − |μ|)
// = 2e-9 of the fixed point, and rtol = 1e-10 keeps the map's noise near 1e-11: the 1e-8
// holds with margin, while a wrong velocity scale in the map's restart (ω missing: 190× off) or a
// Newton sign moves the shooting result by O(1) or stops it converging.
TEST(SteadyState, ShootingAgreesWithBruteForce) {
  const std::vector<std::vector<std::string>> cases = {
      {"beam.damping_ratio=0.03"},  // the base case: 5 modes, 550 rpm, μ = 0.4
      {"beam.modes=3", "beam.damping_ratio=0.02", "surface.friction=0.1", "hub.speed_rpm=800",
       "impact.restitution=0.6"},
  };
  for (const auto& sets : cases) {
    const auto common = with(sets, {"simulation.until_steady=true", "simulation.steady_tolerance=1e-9",
                                    "simulation.rtol=1e-10", "simulation.revolutions=200"});
    const Case brute = build_case(load_config_string("", with(common, {"simulation.steady_method=\"brute_force\""})));
    const Case shoot = build_case(load_config_string("", with(common, {"simulation.steady_method=\"shooting\""})));
    const PassResult b = run_case(brute);
    const PassResult s = run_case(shoot);
    ASSERT_FALSE(b.failure) << b.failure->message;
    ASSERT_FALSE(s.failure) << s.failure->message;
    const SteadyState& sb = b.summary.steady_state;
    const SteadyState& ss = s.summary.steady_state;
    ASSERT_TRUE(sb.reached) << sb.note;
    ASSERT_TRUE(ss.reached) << ss.note;
    EXPECT_EQ(ss.method, SteadyMethod::shooting);
    EXPECT_EQ(ss.period_revolutions, sb.period_revolutions);
    EXPECT_GT(ss.newton_iterations + ss.map_evaluations, 0);
    EXPECT_LT(ss.final_distance, 1e-9);
    const Eigen::VectorXd zb = final_section(brute, b), zs = final_section(shoot, s);
    EXPECT_LE(section_distance(zb, zs), 1e-8) << "zb = " << zb.transpose() << "\nzs = " << zs.transpose();
    // The files of a shooting run hold the orbit: its revolution returns the energy it started with
    // (Δenergy → 0 in steady state) while the hub keeps doing work.
    ASSERT_EQ(s.summary.revolutions, ss.period_revolutions);
    EXPECT_LE(std::abs(s.summary.ledger.energy_change_j), 1e-6 * std::abs(s.summary.ledger[LedgerTerm::hub_work]));
    EXPECT_NEAR(s.summary.mean_hub_power_w, b.summary.mean_hub_power_w, 1e-6 * std::abs(b.summary.mean_hub_power_w));
    // Both report the same multipliers (the FD Jacobian is good to ≈ 1e-4 at this rtol).
    ASSERT_FALSE(sb.multipliers.empty());
    ASSERT_EQ(sb.multipliers.size(), ss.multipliers.size());
    EXPECT_NEAR(sb.multipliers[0].magnitude(), ss.multipliers[0].magnitude(), 1e-3);
    EXPECT_LT(sb.multipliers[0].magnitude(), 1.0);
  }
}

// The multipliers are the eigenvalues of the one-revolution map's Jacobian J at the orbit: a small
// perturbation e0 of the orbit's section state must evolve as J^k e0 (to O(|e0|) and the map's
// noise: 5 %), and in the end decay by the largest |μ| per revolution, with alternating sign when
// that multiplier is real and negative. A Jacobian column scaled wrong, or the multipliers of the
// wrong map, fails both.
TEST(SteadyState, MultipliersPredictTheDecayOfAPerturbation) {
  const Case c = build_case(load_config_string(
      "", {"beam.modes=3", "beam.damping_ratio=0.02", "surface.friction=0.1", "hub.speed_rpm=800",
           "simulation.until_steady=true", "simulation.steady_tolerance=1e-10", "simulation.rtol=1e-11"}));
  const PassResult r = run_case(c);
  ASSERT_FALSE(r.failure);
  const SteadyState& st = r.summary.steady_state;
  ASSERT_TRUE(st.reached) << st.note;
  ASSERT_EQ(st.period_revolutions, 1);
  ASSERT_GE(st.multipliers.size(), 2u);
  const Multiplier mu = st.multipliers[0];
  EXPECT_GT(mu.magnitude(), 0.3);  // this case's orbit is slow enough to measure the decay
  EXPECT_LT(mu.magnitude(), 1.0);

  const System system = c.system();
  const SectionMap map(system, c.options, nullptr);
  const Eigen::VectorXd z_star = final_section(c, r);
  const MapEvaluation base = map(z_star, 1);
  ASSERT_TRUE(base.complete);
  const Eigen::MatrixXd J = map.jacobian(z_star, 1, base, nullptr);
  ASSERT_EQ(J.rows(), z_star.size());
  const std::vector<Multiplier> again = floquet_multipliers(J);
  EXPECT_NEAR(again[0].magnitude(), mu.magnitude(), 1e-3);

  const Eigen::VectorXd e0 = 1e-5 * z_star.norm() * Eigen::VectorXd::Ones(z_star.size()).normalized();
  Eigen::VectorXd z = z_star + e0, predicted = e0;
  std::vector<Eigen::VectorXd> e;
  for (int k = 1; k <= 6; ++k) {
    const MapEvaluation next = map(z, 1);
    ASSERT_TRUE(next.complete);
    ASSERT_EQ(next.impacts, base.impacts) << "the perturbation changed the event sequence";
    z = next.z;
    predicted = J * predicted;
    e.push_back(z - z_star);
    if (k <= 4) EXPECT_LE((e.back() - predicted).norm(), 0.05 * predicted.norm()) << "revolution " << k;
  }
  const double ratio = e[5].norm() / e[4].norm();
  EXPECT_NEAR(ratio, mu.magnitude(), 0.05 * mu.magnitude());
  if (std::abs(mu.im) < 1e-9 && mu.re < 0) EXPECT_LT(e[5].dot(e[4]), 0.0);
  if (std::abs(mu.im) < 1e-9 && mu.re > 0) EXPECT_GT(e[5].dot(e[4]), 0.0);
}

// Where the rubbing does not settle (3 modes at 1000 rpm: the brute-force search is still at a
// section distance of order 1 after 1000 revolutions), shooting from the warm-up does not converge
// either: it must say so, with a warning, within the revolution cap, and still write the run.
TEST(SteadyState, ShootingThatDoesNotConvergeSaysSo) {
  const Case c = build_case(load_config_string(
      "", {"beam.modes=3", "beam.damping_ratio=0.03", "hub.speed_rpm=1000", "simulation.until_steady=true",
           "simulation.steady_method=\"shooting\"", "simulation.revolutions=60"}));
  const PassResult r = run_case(c);
  ASSERT_FALSE(r.failure);
  const SteadyState& st = r.summary.steady_state;
  EXPECT_FALSE(st.reached);
  EXPECT_EQ(st.after_revolutions, 0);
  EXPECT_NE(st.note.find("not reached by shooting"), std::string::npos) << st.note;
  EXPECT_GT(st.final_distance, 1e-8);
  bool warned = false;
  for (const std::string& w : r.summary.warnings) warned |= w.find("no steady state") != std::string::npos;
  EXPECT_TRUE(warned);
  EXPECT_GE(r.summary.revolutions, 1);
}

TEST(SteadyState, AShootingWarmUpThatFailsKeepsItsRecord) {
  // The warm-up of the shooting runs without recording. Where it fails, its record is what the
  // summary describes: before, the history and events were empty beside a summary of 522 impacts.
  // Now the warm-up is run again, recording: rows and the failure event are there, as with brute
  // force, which fails the same way.
  const std::vector<std::string> common = {"simulation.until_steady=true", "simulation.max_impacts=20"};
  const PassResult shot =
      run_case(build_case(load_config_string("", with(common, {"simulation.steady_method=\"shooting\""}))));
  const PassResult brute =
      run_case(build_case(load_config_string("", with(common, {"simulation.steady_method=\"brute_force\""}))));
  ASSERT_TRUE(shot.failure);
  ASSERT_TRUE(brute.failure);
  EXPECT_EQ(shot.failure->kind, FailureKind::impacts);
  EXPECT_DOUBLE_EQ(shot.failure->t, brute.failure->t);
  EXPECT_EQ(shot.history.size(), brute.history.size());
  ASSERT_FALSE(shot.events.empty());
  EXPECT_EQ(shot.events.back().kind, brute.events.back().kind);
  EXPECT_EQ(shot.summary.impacts, brute.summary.impacts);
  EXPECT_FALSE(shot.summary.steady_state.reached);
  EXPECT_NE(shot.summary.steady_state.note.find("the warm-up stopped in revolution 1"), std::string::npos);
}
