// Every case of the Table 5-2 grid (4 speeds × 4 depths × 5 friction values, rigid start) and the
// five flexible starts of Figure 12 complete: either normally or with a correctly diagnosed stop.
#include "rotbeam/pass.hpp"
#include "rotbeam/dynamics.hpp"
#include "rotbeam/plane.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>
#include <set>

using namespace rotbeam;

namespace {
struct Tally {
  int completed = 0;
  std::set<std::string> failures;
};

void check(const PassResult& r, const std::string& label, Tally& tally) {
  if (r.failure) {
    // A diagnosed stop must name a known kind, a time within the pass and a message.
    EXPECT_TRUE(r.failure->kind == FailureKind::painleve || r.failure->kind == FailureKind::stick ||
                r.failure->kind == FailureKind::corrector || r.failure->kind == FailureKind::impacts)
        << label << ": " << failure_name(r.failure->kind);
    EXPECT_FALSE(r.failure->message.empty());
    EXPECT_FALSE(r.history.empty());
    tally.failures.insert(label + " → " + failure_name(r.failure->kind) + ": " + r.failure->message);
  } else {
    ++tally.completed;
    EXPECT_GT(r.summary.impacts, 0) << label;
    EXPECT_FALSE(r.events.empty());
    EXPECT_EQ(r.events.back().kind, EventKind::end);
  }
  EXPECT_LE(r.history.back().theta, M_PI / 2 + 1e-12) << label;
}
}  // namespace

TEST(Grid, Table52RigidStartsComplete) {
  Tally tally;
  for (double rpm : {550.0, 1000.0, 2000.0, 3000.0})
    for (double depth : {0.02, 0.04, 0.06, 0.08})
      for (double mu : {0.1, 0.3, 0.4, 0.5, 0.7}) {
        BeamParameters p;
        p.speed_rpm = rpm;
        const ForeshorteningBeam model = make_beam(p);
        const Plane plane = plane_at_depth(model, depth);
        InitialConditions ic;
        PassOptions opt;
        opt.scheme = Scheme::thesis;
        opt.output_interval_s = 1e-3;
        const PassResult r = run_pass({model, plane, *test::rigid_law({mu, false}, {})}, ic, opt);
        char label[64];
        std::snprintf(label, sizeof label, "%4.0f rpm %2.0f %% μ %.1f", rpm, depth * 100, mu);
        check(r, label, tally);
        std::printf("%s: impacts %4d, episodes %3d, last separation %7.3f°, peak F_n %7.4f N, max |y|/L %.2f%s\n",
                    label, r.summary.impacts, r.summary.contact_episodes, r.summary.last_separation_deg,
                    r.summary.peak_normal_force_n, r.summary.max_tip_deflection_ratio,
                    r.failure ? (std::string(" — ") + failure_name(r.failure->kind)).c_str() : "");
      }
  std::printf("%d of 80 completed normally; diagnosed stops:\n", tally.completed);
  for (const std::string& f : tally.failures) std::printf("  %s\n", f.c_str());
}

TEST(Grid, Figure12FlexibleStartsComplete) {
  Tally tally;
  for (int k = 0; k < 5; ++k) {
    BeamParameters p;
    const ForeshorteningBeam model = make_beam(p);
    const Plane plane = plane_at_depth(model, 0.02);
    InitialConditions ic;
    ic.rigid_start = false;
    ic.q0 = Eigen::VectorXd::Zero(5);
    ic.qd0 = Eigen::VectorXd::Zero(5);
    ic.qd0[k] = 0.1;
    PassOptions opt;
    opt.scheme = Scheme::thesis;
    opt.output_interval_s = 1e-3;
    const PassResult r = run_pass({model, plane, *test::rigid_law({0.4, false}, {})}, ic, opt);
    check(r, "q̇_" + std::to_string(k + 1) + " = 0.1", tally);
    std::printf("q̇_%d = 0.1: first impact %.4f°, impacts %d, episodes %d, last separation %.3f°\n", k + 1,
                r.summary.first_impact_deg, r.summary.impacts, r.summary.contact_episodes,
                r.summary.last_separation_deg);
  }
}
