// The pass engine's seams (issue "One pass engine that grows"): the outcome table, the surface's
// contact geometry through the generic kinematics, the contact load against virtual work, the hub
// torque's closed-form dH_z/dt against differences of H_z, the driver's bounce rule, and streams.
#include "fakes.hpp"
#include "reference_beam.hpp"
#include "rotbeam/contact_law.hpp"
#include "rotbeam/dynamics.hpp"
#include "rotbeam/energy.hpp"
#include "rotbeam/pass.hpp"
#include "rotbeam/plane.hpp"

#include <cmath>
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <set>
#include <thread>

using namespace rotbeam;

TEST(Outcomes, EveryKindHasOneNameAndTheDocumentedExitCode) {
  const std::vector<std::pair<FailureKind, int>> documented = {
      {FailureKind::painleve, 4},  {FailureKind::stick, 5},         {FailureKind::corrector, 6},
      {FailureKind::step_underflow, 7}, {FailureKind::non_finite, 8}, {FailureKind::validity, 9},
      {FailureKind::impacts, 10},  {FailureKind::chatter, 10},      {FailureKind::initial_state, 2},
      {FailureKind::interrupted, 130}};
  std::set<std::string> names;
  for (const auto& [kind, code] : documented) {
    const FailureInfo& info = failure_info(kind);
    EXPECT_EQ(info.kind, kind);
    EXPECT_EQ(info.exit_code, code) << info.name;
    EXPECT_TRUE(names.insert(info.name).second) << "duplicate name " << info.name;
    EXPECT_EQ(failure_from_name(info.name), kind);
  }
  EXPECT_FALSE(failure_from_name("no_such_kind"));
  std::set<std::string> events;
  for (EventKind k : {EventKind::impact, EventKind::lift_off, EventKind::contact_start, EventKind::contact_end,
                      EventKind::slip_reversal, EventKind::tip_distance_rule, EventKind::warning, EventKind::failure,
                      EventKind::end}) {
    EXPECT_TRUE(events.insert(event_name(k)).second) << event_name(k);
    EXPECT_EQ(event_from_name(event_name(k)), k);
  }
}

namespace {
struct Scenario {
  int n;
  double rpm, t;
  unsigned seed;
};
}  // namespace

class SurfaceGeometry : public ::testing::TestWithParam<Scenario> {};

TEST_P(SurfaceGeometry, TangentialFieldsMatchDifferencesOfTheTipPosition) {
  // What the contact algorithms use of the tangent: V_t = t·(V − V_s), ∂V_t/∂q̇ = (∂R/∂q)ᵀt and
  // V̇_t = (∂V_t/∂q̇)ᵀq̈ + γ_t, checked by differencing t·R along q(τ) = q + v τ + ½ a τ² (the plane is
  // at rest and flat, so t is constant). Central differences, Richardson-extrapolated: the same error
  // budget as the gap's in test_kinematics (1e-9 and 1e-6 of ω(r_h + L), ω²(r_h + L)).
  const Scenario s = GetParam();
  BeamParameters p;
  p.modes = s.n;
  p.speed_rpm = s.rpm;
  const ForeshorteningBeam model = make_beam(p);
  const Plane plane = plane_at_depth(model, 0.03);
  Eigen::VectorXd q, v;
  rotbeam::testing::random_state(model, s.seed, 0.02, 2.0, q, v);
  TipKinematics k(s.n);
  tip_kinematics(model, plane, s.t, q, v, k);
  const Eigen::VectorXd a = Eigen::VectorXd::LinSpaced(s.n, -200.0, 150.0);
  auto along = [&](double tau) {
    const Eigen::VectorXd qt = q + v * tau + 0.5 * a * tau * tau;
    const Eigen::Vector2d r = tip_position(model, s.t + tau, qt);
    return k.tangent_x * r.x() + k.tangent_y * r.y();
  };
  const double tau = 1e-5;
  const double d1 = (along(tau) - along(-tau)) / (2 * tau), d1h = (along(tau / 2) - along(-tau / 2)) / tau;
  const double d2 = (along(tau) - 2 * along(0) + along(-tau)) / (tau * tau);
  const double d2h = (along(tau / 2) - 2 * along(0) + along(-tau / 2)) / (tau * tau / 4);
  const double speed = model.omega * model.tip_radius(), accel = model.omega * speed;
  EXPECT_NEAR(k.slip_speed, (4 * d1h - d1) / 3, 1e-9 * speed);
  EXPECT_NEAR(k.grad_tangent.dot(a) + k.gamma_tangent, (4 * d2h - d2) / 3, 1e-6 * accel);
  // ∂V_t/∂q̇ = ∂(t·R)/∂q: C is linear in R, so a difference in q with a 1e-3 m step is exact to round-off.
  for (int i = 0; i < s.n; ++i) {
    Eigen::VectorXd qp = q, qm = q;
    qp[i] += 1e-3;
    qm[i] -= 1e-3;
    const Eigen::Vector2d rp = tip_position(model, s.t, qp), rm = tip_position(model, s.t, qm);
    EXPECT_NEAR(k.grad_tangent[i], (k.tangent_y * (rp.y() - rm.y()) + k.tangent_x * (rp.x() - rm.x())) / 2e-3, 1e-10);
  }
  // The normal is the gap's gradient in space and the tangent is it turned +90°.
  EXPECT_NEAR(k.normal_x * k.tangent_x + k.normal_y * k.tangent_y, 0.0, 1e-15);
  EXPECT_NEAR(k.normal_x * k.tangent_y - k.normal_y * k.tangent_x, 1.0, 1e-15);
}

INSTANTIATE_TEST_SUITE_P(States, SurfaceGeometry,
                         ::testing::Values(Scenario{3, 550, 0.024, 11}, Scenario{5, 1000, 0.012, 12},
                                           Scenario{8, 3000, 0.0046, 13}, Scenario{5, 200, 0.05, 14}));

TEST(SurfaceGeometry, FirstContactAngleOfThePlane) {
  // The undeformed tip at radius r touches X = d at cos θ = d/r while approaching (sin θ < 0); from a
  // start past that angle the next touch is a turn later; a plane beyond r is never reached.
  const Plane plane(0.1);
  const double r = 0.127, star = -std::acos(0.1 / r);
  EXPECT_DOUBLE_EQ(plane.first_contact_angle(r, -M_PI / 2), star);
  EXPECT_NEAR(plane.first_contact_angle(r, 0.0), star + 2 * M_PI, 1e-15);
  EXPECT_NEAR(plane.first_contact_angle(r, -M_PI / 2 + 6 * M_PI), star + 6 * M_PI, 1e-14);
  EXPECT_TRUE(std::isnan(plane.first_contact_angle(0.09, -M_PI / 2)));
  EXPECT_NEAR(plane.gap(Eigen::Vector2d(r * std::cos(star), r * std::sin(star)), 0.0), 0.0, 1e-16);
}

TEST(ContactLoad, GeneralisedForceIsTheVirtualWorkOfTheForceOnTheTip) {
  // Q must equal (∂R/∂q)ᵀF for the force F = (force_x, force_y) reported on the tip, and q̇ᵀQ the
  // power; both conventions of the friction force (physical and the thesis's), both slip senses.
  BeamParameters p;
  const ForeshorteningBeam model = make_beam(p);
  const Plane plane = plane_at_depth(model, 0.02);
  Eigen::VectorXd q, v;
  rotbeam::testing::random_state(model, 3, 0.01, 1.0, q, v);
  TipKinematics tip(model.n);
  tip_kinematics(model, plane, 0.026, q, v, tip);
  Eigen::VectorXd force(model.n);
  for (bool thesis : {false, true})
    for (double slip : {-1.0, 1.0}) {
      const FrictionModel friction{0.35, thesis};
      const ContactLoad l = contact_load(friction, tip, v, -0.7, slip, force);
      const Eigen::VectorXd virtual_work = l.force_x * tip.grad_x + l.force_y * tip.grad_y;
      EXPECT_LT((force - virtual_work).norm(), 1e-14 * force.norm());
      EXPECT_NEAR(l.rate[LedgerTerm::contact_work], v.dot(force), 1e-15 * std::abs(l.rate[LedgerTerm::contact_work]) + 1e-18);
      EXPECT_NEAR(std::abs(l.friction_force), friction.mu * (thesis ? tip.grad_gap.norm() : 1.0) * 0.7, 1e-15);
      EXPECT_LT(l.friction_force * slip, 0.0) << "friction opposes the slip";
      EXPECT_NEAR(l.rate[LedgerTerm::friction_work], l.friction_force * tip.slip_speed, 1e-18);
    }
  const ContactLoad none = contact_load(FrictionModel{}, tip, v, 0.0, 1.0, force);
  EXPECT_EQ(none.normal_force, 0.0);
  EXPECT_EQ(force.norm(), 0.0);
}

TEST(HubTorque, ClosedFormAngularMomentumRateMatchesDifferencesOfHz) {
  // dH_z/dt from ω∇J·q̇ + d(p(q)·q̇)/dt against d/dε H_z(q + εq̇, q̇ + εq̈) by Richardson-extrapolated
  // central differences (H_z is a polynomial of degree 4 in ε: exact but for round-off, ~1e-9 relative
  // with ε = 1e-6 s); H_z itself from the independent quadrature of reference_beam. Random states with
  // 2 cm tip deflection, several mode counts and speeds, an arbitrary q̈.
  for (const Scenario& s : {Scenario{2, 550, 0, 21}, Scenario{5, 550, 0, 22}, Scenario{5, 3000, 0, 23},
                            Scenario{10, 1000, 0, 24}}) {
    BeamParameters p;
    p.modes = s.n;
    p.speed_rpm = s.rpm;
    const ForeshorteningBeam model = make_beam(p);
    const rotbeam::testing::ReferenceBeam ref(model, 64);
    ForeshorteningWorkspace ws(s.n);
    Eigen::VectorXd q, v;
    rotbeam::testing::random_state(model, s.seed, 0.02, 2.0, q, v);
    const Eigen::VectorXd a = Eigen::VectorXd::LinSpaced(s.n, 3e3, -1e3);
    const double rate = angular_momentum_rate(model, q, v, a, ws);
    auto h_at = [&](double e) { return ref.angular_momentum(q + e * v + 0.5 * e * e * a, v + e * a); };
    const double eps = 1e-6;
    const double d1 = (h_at(eps) - h_at(-eps)) / (2 * eps), d2 = (h_at(eps / 2) - h_at(-eps / 2)) / eps;
    const double fd = (4 * d2 - d1) / 3;
    const double scale = std::abs(fd) + model.mass * model.omega * model.tip_radius() * 2.0;
    std::printf("n = %2d, %4.0f rpm: dH_z/dt = %.10e (closed form), %.10e (differences)\n", s.n, s.rpm, rate, fd);
    EXPECT_NEAR(rate, fd, 1e-8 * scale);
    // The seam's call gives the same number.
    EXPECT_DOUBLE_EQ(model.angular_momentum_rate(q, v, a, ws), rate);
  }
}

TEST(Driver, TheBounceIsDecidedByTheRestitutionNotByTheSignOfRoundOff) {
  // After a plastic impact Ċ⁺ is zero only to round-off (here −2.8e-16 m/s after an approach at
  // 1.5e-4 m/s, as in the 10-mode thesis pass of docs/model.md §10): contact must follow, not a bounce.
  ImpactResult plastic;
  plastic.vx_before = 1.5e-4;
  plastic.vx_after = -2.8e-16;
  plastic.restitution = 0.0;
  EXPECT_FALSE(rebounds(plastic));
  ImpactResult elastic;
  elastic.vx_before = 1.5e-4;
  elastic.vx_after = -0.5 * 1.5e-4;
  elastic.restitution = 0.5;
  EXPECT_TRUE(rebounds(elastic));
  plastic.vx_after = +3e-16;  // a positive round-off is not a bounce either
  EXPECT_FALSE(rebounds(plastic));
}

namespace {
PassResult pass_of(int n, double rpm, double mu, Scheme scheme, double plastic_below) {
  BeamParameters p;
  p.modes = n;
  p.speed_rpm = rpm;
  const ForeshorteningBeam model = make_beam(p);
  const Plane plane = plane_at_depth(model, 0.02);
  ImpactLaw law;
  law.plastic_below_m_s = plastic_below;
  PassOptions opt;
  opt.scheme = scheme;
  opt.output_interval_s = 1e30;
  return run_pass({model, plane, *test::rigid_law({mu, false}, law)}, InitialConditions{}, opt);
}
}  // namespace

TEST(Driver, EveryPlasticImpactIsFollowedByContactOrLiftOff) {
  // e = 0 leaves Ċ⁺ = 0: the tip cannot fly off, so at the same instant the driver must either start
  // sustained contact or find that the tip lifts off (docs/model.md §5). Passes with hundreds of plastic
  // impacts, some at approach speeds of ~1e-4 m/s where the recomputed Ċ⁺ is only zero to round-off
  // (the 10-mode thesis pass of docs/model.md §10 has one at θ = 9.108°).
  int checked = 0;
  for (Scheme scheme : {Scheme::thesis, Scheme::adaptive})
    for (int n : {5, 10}) {
      const PassResult r = pass_of(n, 550, 0.0, scheme, 10.0);
      ASSERT_FALSE(r.failure) << failure_name(r.failure->kind);
      for (std::size_t i = 0; i + 1 < r.events.size(); ++i) {
        if (r.events[i].kind != EventKind::impact || r.events[i].restitution != 0.0) continue;
        ++checked;
        const PassEvent& next = r.events[i + 1];
        EXPECT_TRUE(next.kind == EventKind::contact_start || next.kind == EventKind::lift_off)
            << scheme_name(scheme) << " n = " << n << ": plastic impact at " << r.events[i].theta * 180 / M_PI
            << "° followed by " << event_name(next.kind);
        EXPECT_EQ(next.t, r.events[i].t);
      }
    }
  EXPECT_GT(checked, 50);
}

namespace {
// A sink that keeps what it receives and checks the folder of a PassFiles writer as rows arrive.
struct CountingSink : PassSink {
  std::vector<HistoryRow> rows;
  std::vector<PassEvent> events;
  void row(const HistoryRow& r) override { rows.push_back(r); }
  void event(const PassEvent& e) override { events.push_back(e); }
};
}  // namespace

TEST(Streams, ASinkReceivesExactlyWhatAnInMemoryPassKeeps) {
  BeamParameters p;
  const ForeshorteningBeam model = make_beam(p);
  const Plane plane = plane_at_depth(model, 0.02);
  for (Scheme scheme : {Scheme::adaptive, Scheme::thesis}) {
    PassOptions opt;
    opt.scheme = scheme;
    const System system{model, plane, default_contact_law()};
    const PassResult memory = run_pass(system, InitialConditions{}, opt);
    CountingSink sink;
    const PassResult streamed = run_pass(system, InitialConditions{}, opt, {&sink, nullptr});
    EXPECT_TRUE(streamed.history.empty());
    EXPECT_TRUE(streamed.events.empty());
    ASSERT_EQ(sink.rows.size(), memory.history.size());
    ASSERT_EQ(sink.events.size(), memory.events.size());
    for (std::size_t i = 0; i < sink.rows.size(); ++i) {
      EXPECT_EQ(sink.rows[i].t, memory.history[i].t);
      EXPECT_EQ(sink.rows[i].q, memory.history[i].q);
      EXPECT_EQ(sink.rows[i].hub_torque, memory.history[i].hub_torque);
    }
    for (std::size_t i = 0; i < sink.events.size(); ++i) EXPECT_EQ(sink.events[i].kind, memory.events[i].kind);
    EXPECT_EQ(streamed.summary.impacts, memory.summary.impacts);
    EXPECT_EQ(streamed.summary.ledger[LedgerTerm::normal_impulse], memory.summary.ledger[LedgerTerm::normal_impulse]);
  }
}

TEST(Streams, EachPassHasItsOwnStopToken) {
  // Two passes at once on two threads over one shared system (fakes.hpp: a check of the logic, so
  // nothing is integrated): a stop requested on one token stops that pass only.
  const fakes::FakeBeam beam;
  const fakes::FakeSurface surface;
  const fakes::FakeContactLaw law;
  const System system{beam, surface, law};
  PassOptions opt;
  opt.output_interval_s = 1e30;
  StopToken stopped, running;
  stopped.request_stop();
  InitialConditions ic;
  ic.rigid_start = false;
  ic.q0 = ic.qd0 = Eigen::VectorXd::Zero(1);
  fakes::ScriptedStepper sa(1e-5), sb(1e-5);
  PassResult a, b;
  std::thread ta([&] { a = run_pass_with(system, ic, opt, sa, {nullptr, &stopped}); });
  std::thread tb([&] { b = run_pass_with(system, ic, opt, sb, {nullptr, &running}); });
  ta.join();
  tb.join();
  ASSERT_TRUE(a.failure);
  EXPECT_EQ(a.failure->kind, FailureKind::interrupted);
  EXPECT_EQ(sa.statistics().steps, 1);
  EXPECT_FALSE(b.failure) << failure_name(b.failure->kind);
  EXPECT_DOUBLE_EQ(b.final_t, beam.time_at(M_PI / 2));
}
