// Many revolutions (docs/model.md §11): the per-revolution energy ledger, the section map being a function
// of the section state alone (so that a run of N revolutions equals N one-revolution runs chained),
// the steady state reached with damping and its independence of the start, the windowed history,
// and the configuration's rules.
#include "rotbeam/case.hpp"
#include "rotbeam/config.hpp"

#include <cmath>
#include <gtest/gtest.h>

using namespace rotbeam;

namespace {

PassResult run(const std::vector<std::string>& sets) {
  const Config c = load_config_string("", sets);
  return run_case(build_case(c));
}

// The section state z = (q/L, q̇/(ωL)) of a revolution record.
Eigen::VectorXd section(const RevolutionRecord& r, double L, double omega) {
  Eigen::VectorXd z(2 * r.q.size());
  z << r.q / L, r.qd / (omega * L);
  return z;
}

}  // namespace

// hub work = Δenergy − friction − damping − impact losses in every revolution: the tolerance 1e-8
// of the revolution's hub work is the issue's; the integrals are accurate to ≈ rtol = 1e-9. A sign
// or a missing term (damping, the impulsive hub work) breaks it by 1e-2 or more.
TEST(Revolutions, LedgerClosesEveryRevolution) {
  const std::vector<std::vector<std::string>> cases = {
      {"beam.damping_ratio=0.02"},
      {"beam.damping_ratio=0.01", "surface.friction=0.1", "hub.speed_rpm=1000"},
      {"beam.damping_ratio=[0.05,0.04,0.03,0.02,0.01]", "impact.restitution=0.6", "surface.depth_fraction=0.01"},
      // Undamped at 3000 rpm the hub's work per revolution is a small difference of large energies
      // (the filament also returns energy to the hub): 1e-8 of it needs rtol 1e-10.
      {"hub.speed_rpm=3000", "impact.friction=\"coulomb\"", "simulation.rtol=1e-10"},
  };
  for (const auto& sets : cases) {
    std::vector<std::string> s = sets;
    s.push_back("simulation.revolutions=3");
    s.push_back("output.history_revolutions=\"all\"");
    const PassResult r = run(s);
    ASSERT_FALSE(r.failure) << r.failure->message;
    ASSERT_EQ(r.revolutions.size(), 3u);
    EXPECT_EQ(r.summary.revolutions, 3);
    double hub = 0;
    for (const RevolutionRecord& rev : r.revolutions) {
      EXPECT_TRUE(rev.complete);
      EXPECT_LE(std::abs(rev.ledger.residual()), 1e-8 * std::abs(rev.ledger[LedgerTerm::hub_work])) << "revolution " << rev.revolution;
      EXPECT_NEAR(rev.mean_hub_power_w, rev.ledger[LedgerTerm::hub_work] / (rev.t_end - rev.t_start), 1e-15);
      hub += rev.ledger[LedgerTerm::hub_work];
    }
    // The revolutions add up to the run.
    EXPECT_NEAR(hub, r.summary.ledger[LedgerTerm::hub_work], 1e-9 * std::abs(r.summary.ledger[LedgerTerm::hub_work]));
    EXPECT_NEAR(r.summary.mean_hub_torque_n_m, r.revolutions.back().mean_hub_torque_n_m, 0.0);
    if (&sets == &cases.front())  // damped, rubbing: the hub drives the filament in every revolution
      for (const RevolutionRecord& rev : r.revolutions) EXPECT_GT(rev.ledger[LedgerTerm::hub_work], 0.0);
  }
}

// A lift-off right after a plastic impact and a return 10 µs later that never clears the surface by
// the detector's band ε: with ε = 10·rtol·(r_h + L) (1.3 nm, the tip's radius as the error scale)
// that return was taken 1.3 nm inside the surface and contact began with a position projection
// whose energy (3e-11 J) no ledger term carries, 1.5e-8 of revolution 7's hub work. ε is now the
// error allowed on the gap itself (Σ|∂C/∂q_i|(atol + rtol|q_i|)), and the revolution closes to
// the integration's accuracy. The case must still contain such a return, or it tests nothing.
TEST(Revolutions, LedgerClosesAfterAReturnInsideTheDetectorBand) {
  const PassResult r = run({"beam.damping_ratio=0.01", "simulation.revolutions=7", "output.history_revolutions=\"all\""});
  ASSERT_FALSE(r.failure);
  ASSERT_EQ(r.revolutions.size(), 7u);
  bool returns = false;
  for (std::size_t k = 1; k < r.events.size(); ++k)
    returns |= r.events[k - 1].kind == EventKind::lift_off && r.events[k].kind == EventKind::impact &&
               r.events[k].t - r.events[k - 1].t < 2e-5 && r.events[k].vx_before < 2e-3;
  EXPECT_TRUE(returns) << "no slow return within 20 µs of a lift-off: the case no longer exercises the band";
  for (const RevolutionRecord& rev : r.revolutions)
    EXPECT_LE(std::abs(rev.ledger.residual()), 1e-8 * std::abs(rev.ledger[LedgerTerm::hub_work])) << "revolution " << rev.revolution;
}

// Revolution 3 of a run equals one revolution run from revolution 2's end state (a flexible start at
// the section): one revolution is a map of the section state, which shooting needs. 1e-9 relative:
// the integrations differ only by the time offset's rounding and the stepper's restart at the section.
TEST(Revolutions, OneRevolutionIsAMapOfTheSectionState) {
  const std::vector<std::string> base = {"beam.damping_ratio=0.02", "surface.friction=0.3"};
  std::vector<std::string> s = base;
  s.push_back("simulation.revolutions=3");
  const PassResult chain = run(s);
  ASSERT_FALSE(chain.failure);
  const RevolutionRecord& r2 = chain.revolutions[1];
  Config c = load_config_string("", base);
  c.simulation.revolutions = 1;
  Case k = build_case(c);
  k.initial.rigid_start = false;
  k.initial.q0 = r2.q;
  k.initial.qd0 = r2.qd;
  const PassResult one = run_case(k);
  ASSERT_FALSE(one.failure);
  ASSERT_EQ(one.revolutions.size(), 1u);
  const double L = k.beam->beam_length(), w = k.beam->hub_motion().omega;
  const Eigen::VectorXd a = section(chain.revolutions[2], L, w), b = section(one.revolutions[0], L, w);
  EXPECT_LE((a - b).norm(), 1e-9 * a.norm());
  EXPECT_EQ(chain.revolutions[2].impacts, one.revolutions[0].impacts);
  EXPECT_NEAR(chain.revolutions[2].first_impact_deg, one.revolutions[0].first_impact_deg, 1e-7);
}

// With ζ in [0.01, 0.05] the base case settles, and to the same orbit from a rigid start and from a
// flexible one with q̇(0) = [1,0,0,0,0] (the 1e-6). At ζ = 0.02 the orbit repeats every three
// revolutions (64, 37 and 32 impacts), so the flexible start's last section is compared with the
// nearest of the rigid orbit's last three. Each search stops at a distance below 1e-9 over the
// period, so both lie within ≈ 1e-9/(1 − ρ) of the orbit; rtol 1e-11 keeps the map's integration
// noise (≈ 1e-10 at the default rtol) below that.
TEST(Revolutions, SteadyStateIndependentOfTheStart) {
  const std::vector<std::pair<std::string, int>> cases = {{"0.02", 3}, {"0.05", 1}};
  for (const auto& [zeta, period] : cases) {
    std::vector<std::string> s = {"beam.damping_ratio=" + zeta, "simulation.until_steady=true", "simulation.multipliers=false",
                                  "simulation.revolutions=80", "simulation.steady_tolerance=1e-9",
                                  "simulation.rtol=1e-11", "simulation.atol=1e-14"};
    const PassResult rigid = run(s);
    s.push_back("initial.modal_velocity=[1,0,0,0,0]");
    const PassResult flexible = run(s);
    for (const PassResult* r : {&rigid, &flexible}) {
      ASSERT_FALSE(r->failure) << r->failure->message;
      ASSERT_TRUE(r->summary.steady_state.reached) << "ζ = " << zeta << ": " << r->summary.steady_state.note;
      EXPECT_EQ(r->summary.steady_state.period_revolutions, period) << "ζ = " << zeta;
    }
    const Config c = load_config_string("", {});
    const double L = c.beam.length_m, w = c.beam.speed_rpm * M_PI / 30.0;
    const Eigen::VectorXd b = section(flexible.revolutions.back(), L, w);
    double nearest = INFINITY, scale = 0;
    for (int j = 0; j < period; ++j) {
      const Eigen::VectorXd a = section(rigid.revolutions[rigid.revolutions.size() - 1 - j], L, w);
      nearest = std::min(nearest, (a - b).norm());
      scale = std::max(scale, a.norm());
    }
    EXPECT_LE(nearest, 1e-6 * scale) << "ζ = " << zeta;
  }
}

// Without damping nothing settles within a few revolutions: the search says so.
TEST(Revolutions, NoSteadyStateIsReported) {
  const PassResult r = run({"simulation.until_steady=true", "simulation.revolutions=3"});
  ASSERT_FALSE(r.failure);
  EXPECT_FALSE(r.summary.steady_state.reached);
  EXPECT_NE(r.summary.steady_state.note.find("not reached within 3 revolutions"), std::string::npos);
  ASSERT_FALSE(r.summary.warnings.empty());
}

// One revolution has no earlier revolution to compare with ("within 1 revolutions (section distance 1"
// read as a measured distance): the note says what the distance is taken from.
TEST(Revolutions, OneRevolutionSaysItsSectionIsComparedWithTheStart) {
  const PassResult r = run({"simulation.until_steady=true", "simulation.revolutions=1"});
  ASSERT_FALSE(r.failure);
  EXPECT_NE(r.summary.steady_state.note.find("not reached within 1 revolution (its section compared with the start only"),
            std::string::npos)
      << r.summary.steady_state.note;
}

// output.history_revolutions = K keeps the rows, events and contact intervals of the last K
// revolutions; revolutions stay complete.
TEST(Revolutions, HistoryWindow) {
  const PassResult all = run({"simulation.revolutions=4", "beam.damping_ratio=0.02", "output.history_revolutions=\"all\""});
  const PassResult last2 = run({"simulation.revolutions=4", "beam.damping_ratio=0.02", "output.history_revolutions=2"});
  ASSERT_EQ(last2.revolutions.size(), 4u);
  const double t2 = last2.revolutions[1].t_end;
  ASSERT_FALSE(last2.history.empty());
  EXPECT_GT(last2.history.front().t, t2);
  EXPECT_GT(last2.events.front().t, t2);
  std::size_t rows_after = 0;
  for (const HistoryRow& h : all.history) rows_after += h.t > t2;
  EXPECT_EQ(last2.history.size(), rows_after);
  for (const ContactInterval& c : last2.summary.contact_intervals) EXPECT_GE(c.revolution, 3);
  EXPECT_EQ(all.summary.contact_episodes, last2.summary.contact_episodes);
}

TEST(Revolutions, ConfigurationRules) {
  auto error_of = [](const std::vector<std::string>& sets) {
    try {
      load_config_string("", sets);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of({"simulation.revolutions=3", "simulation.end_angle_deg=80"}).find("simulation.end_angle_deg"),
            std::string::npos);
  EXPECT_NE(error_of({"simulation.steady_method=shooting"}).find("simulation.until_steady"), std::string::npos);
  EXPECT_EQ(error_of({"simulation.until_steady=true", "simulation.steady_method=shooting"}), "");
  EXPECT_NE(error_of({"simulation.revolutions=0"}).find("simulation.revolutions"), std::string::npos);
  EXPECT_NE(error_of({"output.history_revolutions=0"}).find("output.history_revolutions"), std::string::npos);
  EXPECT_NE(error_of({"simulation.steady_method=newton"}).find("simulation.steady_method"), std::string::npos);
  const Config c = load_config_string("", {"simulation.until_steady=true"});
  EXPECT_EQ(c.simulation.revolutions, kDefaultSteadyRevolutionCap);
  EXPECT_DOUBLE_EQ(c.simulation.end_angle_deg, -90.0 + 360.0 * kDefaultSteadyRevolutionCap);
}
