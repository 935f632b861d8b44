// The adaptive event-driven scheme (docs/model.md §6): convergence in tolerance, event location, the Jacobi
// integral, and the thesis scheme's error against it.
#include "rotbeam/case.hpp"
#include "rotbeam/convergence.hpp"
#include "rotbeam/energy.hpp"
#include "rotbeam/plane.hpp"

#include <cmath>
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <limits>

using namespace rotbeam;

namespace {
PassResult adaptive(double rtol, double interval = 1e30) {
  Config c = load_config_string("", {});
  c.simulation.rtol = rtol;
  c.simulation.output_interval_s = interval;
  return run_case(build_case(c));
}
}  // namespace

TEST(Adaptive, BaseCaseSettlesToSixDigitsAsTheToleranceTightens) {
  // rtol 1e-6 … 1e-12: the last separation angle and the total normal impulse must agree to ≥ 6
  // significant digits between the three tightest tolerances (measured: ~1e-10 relative).
  std::vector<double> sep, imp;
  for (double rtol : {1e-6, 1e-8, 1e-10, 1e-12}) {
    const PassResult r = adaptive(rtol);
    ASSERT_FALSE(r.failure) << r.failure->message;
    sep.push_back(r.summary.last_separation_deg);
    imp.push_back(r.summary.ledger[LedgerTerm::normal_impulse]);
    std::printf("rtol %.0e: last separation %.10f deg, normal impulse %.10e N s, impacts %d, episodes %d, audit %.2e\n",
                rtol, r.summary.last_separation_deg, r.summary.ledger[LedgerTerm::normal_impulse], r.summary.impacts,
                r.summary.contact_episodes, r.summary.energy_audit_residual);
  }
  for (int i = 1; i <= 2; ++i) {
    EXPECT_NEAR(sep[i], sep[3], 1e-6 * std::abs(sep[3])) << "rtol index " << i;
    EXPECT_NEAR(imp[i], imp[3], 1e-6 * std::abs(imp[3])) << "rtol index " << i;
  }
  // Differences shrink with the tolerance.
  EXPECT_LT(std::abs(sep[2] - sep[3]), std::abs(sep[0] - sep[3]));
  EXPECT_LT(std::abs(imp[2] - imp[3]), std::abs(imp[1] - imp[3]) + 1e-18);
}

TEST(Adaptive, ImpactsAreLocatedToAPicosecond) {
  // At every impact the gap must be within |V_X|·1e-12 s of zero (the events are bracketed to
  // 1e-13 s; the recorded state is the dense-output state at the bracket's end), or, for the slowest
  // touches (V_X below 1e-4 m/s), within the gap's own round-off: X_t − d from products of terms
  // of size r_h + L = 0.127 m, a few ulps of which is 16 ε (r_h + L) = 4.5e-16 m (measured up to
  // 2.5e-16 m: 9 ulps, depending on the compiler's inlining).
  const double roundoff_m = 16 * std::numeric_limits<double>::epsilon() * 0.127;
  const PassResult r = adaptive(1e-10, 1e30);
  ASSERT_FALSE(r.failure);
  int checked = 0;
  for (std::size_t i = 0; i + 1 < r.history.size(); ++i) {
    const HistoryRow& before = r.history[i];
    const HistoryRow& after = r.history[i + 1];
    // An impact pair: the first two rows at one time (after a plastic impact a third row, the
    // contact's start, follows the post-impact row, whose V_X is a round-off of zero).
    if (i > 0 && r.history[i - 1].t == before.t) continue;
    if (before.t != after.t || before.vx <= 0.0 || after.vx > before.vx) continue;
    ++checked;
    EXPECT_LE(std::abs(before.gap), 1e-12 * before.vx + roundoff_m) << "impact at t = " << before.t;
  }
  EXPECT_GE(checked, 10);
}

TEST(Adaptive, JacobiIntegralOverAFreePassAtTightTolerance) {
  // θ0 → +90° with q̇(0) = (2, 0, 0, 0, 0) m/s, no surface within reach, rtol = atol-scaled 1e-12:
  // max |h(t) − h(0)| ≤ 1e-10 |h(0)|.
  for (double rpm : {550.0, 3000.0}) {
    BeamParameters p;
    p.speed_rpm = rpm;
    const ForeshorteningBeam model = make_beam(p);
    const Plane plane(1.0);  // 1 m away: the tip never reaches it
    InitialConditions ic;
    ic.rigid_start = false;
    ic.q0 = Eigen::VectorXd::Zero(5);
    ic.qd0 = Eigen::VectorXd::Zero(5);
    ic.qd0[0] = 2.0;
    PassOptions opt;
    opt.rtol = 1e-12;
    opt.atol = 1e-15;
    opt.output_interval_s = 1e-4;
    const PassResult r = run_pass({model, plane, default_contact_law()}, ic, opt);
    ASSERT_FALSE(r.failure);
    EXPECT_EQ(r.summary.impacts, 0);
    const double h0 = r.history.front().jacobi;
    double drift = 0.0;
    for (const HistoryRow& row : r.history) drift = std::max(drift, std::abs(row.jacobi - h0));
    std::printf("%.0f rpm: %ld steps, max |Δh|/|h| = %.2e\n", rpm, r.summary.steps, drift / std::abs(h0));
    EXPECT_LE(drift / std::abs(h0), 1e-10);
    EXPECT_NEAR(r.history.back().theta, M_PI / 2, 1e-12);
  }
}

TEST(Adaptive, ThesisSchemeErrorFallsWithItsStep) {
  // The first contact episodes (to θ = −5°, all impacts plastic) where the thesis scheme keeps the
  // reference's sequence of events: its normal-impulse error against the tight adaptive run must
  // fall at every halving of the step, at first order (ratio 1.5…2.5; measured ≈ 1.9…2.0).
  Config c = load_config_string("", {"simulation.end_angle_deg=-5", "impact.plastic_below_m_s=10"});
  ConvergenceLadder ladder;
  ladder.rtols = {1e-12};
  ladder.thesis_free_steps = {2e-6, 1e-6, 5e-7, 2.5e-7};
  ladder.modes = {};
  const ConvergenceStudy s = run_convergence(c, ladder, 0);
  ASSERT_EQ(s.runs.size(), 5u);
  const double ref = s.runs[0].summary.ledger[LedgerTerm::normal_impulse];
  std::vector<double> err;
  for (std::size_t i = 1; i < s.runs.size(); ++i) {
    ASSERT_TRUE(s.runs[i].failure.empty()) << s.runs[i].failure;
    err.push_back(std::abs(s.runs[i].summary.ledger[LedgerTerm::normal_impulse] - ref) / ref);
    std::printf("%s: normal impulse error %.3e\n", s.runs[i].label.c_str(), err.back());
  }
  for (std::size_t i = 1; i < err.size(); ++i) {
    EXPECT_GT(err[i - 1] / err[i], 1.5) << i;
    EXPECT_LT(err[i - 1] / err[i], 2.5) << i;
  }
}

TEST(Adaptive, MatchesTheIndependentRunsOfSpec10) {
  // As for the thesis scheme: μ = 0, all impacts plastic; 5 modes ~5 episodes and ≈ 2.5 N,
  // 10 modes ~20 episodes and ≈ 5.7 N, last separation ≈ 10°.
  for (int n : {5, 10}) {
    Config c = load_config_string("", {"surface.friction=0", "impact.plastic_below_m_s=10",
                                       "beam.modes=" + std::to_string(n), "simulation.rtol=1e-8"});
    c.initial.modal_velocity.assign(n, 0.0);
    c.initial.modal_displacement.assign(n, 0.0);
    c.simulation.output_interval_s = 1e30;
    const PassResult r = run_case(build_case(c));
    ASSERT_FALSE(r.failure);
    std::printf("n = %d: %d episodes, peak %.4f N, last separation %.4f deg\n", n, r.summary.contact_episodes,
                r.summary.peak_normal_force_n, r.summary.last_separation_deg);
    EXPECT_NEAR(r.summary.contact_episodes, n == 5 ? 5 : 20, n == 5 ? 2 : 5);
    EXPECT_NEAR(r.summary.peak_normal_force_n, n == 5 ? 2.5 : 5.7, n == 5 ? 0.25 : 0.57);
    EXPECT_NEAR(r.summary.last_separation_deg, 10.0, 0.5);
  }
}

TEST(Adaptive, Table52GridCompletes) {
  int completed = 0;
  for (double rpm : {550.0, 1000.0, 2000.0, 3000.0})
    for (double depth : {0.02, 0.04, 0.06, 0.08})
      for (double mu : {0.1, 0.3, 0.4, 0.5, 0.7}) {
        char buf[3][32];
        std::snprintf(buf[0], 32, "hub.speed_rpm=%g", rpm);
        std::snprintf(buf[1], 32, "surface.depth_fraction=%g", depth);
        std::snprintf(buf[2], 32, "surface.friction=%g", mu);
        Config c = load_config_string("", {buf[0], buf[1], buf[2]});
        c.simulation.output_interval_s = 1e30;
        const PassResult r = run_case(build_case(c));
        if (r.failure) {
          EXPECT_TRUE(r.failure->kind == FailureKind::painleve || r.failure->kind == FailureKind::stick ||
                      r.failure->kind == FailureKind::impacts)
              << buf[0] << " " << buf[1] << " " << buf[2] << ": " << r.failure->message;
          std::printf("%s %s %s: diagnosed %s: %s\n", buf[0], buf[1], buf[2], failure_name(r.failure->kind),
                      r.failure->message.c_str());
        } else {
          ++completed;
          EXPECT_EQ(r.events.back().kind, EventKind::end);
        }
      }
  std::printf("%d of 80 completed normally\n", completed);
}
