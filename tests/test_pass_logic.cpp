// The pass driver's and the recorder's logic over fakes (fakes.hpp): revolutions and sections, a
// stepper's failure, a stop request, the chatter guard, the rigid turn and the early end. No case is
// built and nothing is integrated: what is checked is bookkeeping, exactly (times are compared to the
// scripted ones without tolerance, or to the last bit where they come from ω).
#include "fakes.hpp"

#include "rotbeam/pass.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace {

using namespace rotbeam;
using rotbeam::fakes::FakeBeam;
using rotbeam::fakes::FakeContactLaw;
using rotbeam::fakes::FakeSurface;
using rotbeam::fakes::ScriptedStep;
using rotbeam::fakes::ScriptedStepper;

InitialConditions flexible_start(int n = 1) {
  InitialConditions ic;
  ic.rigid_start = false;
  ic.q0 = Eigen::VectorXd::Zero(n);
  ic.qd0 = Eigen::VectorXd::Zero(n);
  return ic;
}

PassOptions options() {
  PassOptions o;
  o.output_interval_s = 1e-3;
  o.near_surface_gap_m = 0;
  return o;
}

long count(const std::vector<FreeStart>& starts, FreeStart s) { return std::count(starts.begin(), starts.end(), s); }

TEST(PassLogic, EveryRevolutionClosesAtItsSectionWhereTheStepperRestarts) {
  FakeBeam beam(2);
  FakeSurface surface;
  FakeContactLaw law;
  ScriptedStepper stepper(1e-3);
  PassOptions o = options();
  o.revolutions = 3;
  const PassResult r = run_pass_with({beam, surface, law}, flexible_start(2), o, stepper);
  const double period = 2 * M_PI / 100.0;
  ASSERT_FALSE(r.failure.has_value());
  ASSERT_EQ(r.revolutions.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(r.revolutions[k].complete) << k;
    EXPECT_EQ(r.revolutions[k].revolution, k + 1);
    EXPECT_EQ(r.revolutions[k].t_end, (k + 1) * period) << k;  // the section itself, not a step near it
    EXPECT_EQ(r.revolutions[k].impacts, 0);
  }
  EXPECT_EQ(r.final_t, 3 * period);
  // The run's start and the two interior sections restart free flight; nothing else does.
  EXPECT_EQ(count(stepper.free_starts, FreeStart::pass_start), 3);
  EXPECT_EQ(stepper.free_starts.size(), 3u);
  // No step was asked to go past a section.
  const double t_first = *std::find_if(stepper.stops.begin(), stepper.stops.end(), [](double t) { return t > 0; });
  EXPECT_EQ(t_first, period);
  EXPECT_EQ(law.touches, 0);
}

TEST(PassLogic, AStepperFailureEndsThePassWhereItFailedAndKeepsWhatCameBefore) {
  FakeBeam beam;
  FakeSurface surface;
  FakeContactLaw law;
  ScriptedStepper stepper(1e-3);
  stepper.script.push_back({0.0105, StepStatus::failed, Root::none, FailureKind::step_underflow});
  const PassResult r = run_pass_with({beam, surface, law}, flexible_start(), options(), stepper);
  ASSERT_TRUE(r.failure.has_value());
  EXPECT_EQ(r.failure->kind, FailureKind::step_underflow);
  EXPECT_EQ(r.failure->t, 0.0105);
  EXPECT_DOUBLE_EQ(r.failure->theta, 100.0 * 0.0105);  // θ0 = 0 for the fake hub
  EXPECT_NE(r.failure->message.find("scripted failure"), std::string::npos);
  // The rows up to the last good state are kept: one per millisecond from t = 0 to 0.010 s.
  ASSERT_FALSE(r.history.empty());
  EXPECT_EQ(r.history.front().t, 0.0);
  EXPECT_NEAR(r.history.back().t, 0.010, 1e-15);
  EXPECT_GE(r.history.size(), 11u);
  // The failure event where the stepper failed (inside its step), then the end at the last good state.
  ASSERT_GE(r.events.size(), 2u);
  const PassEvent& failure = r.events[r.events.size() - 2];
  EXPECT_EQ(failure.kind, EventKind::failure);
  EXPECT_EQ(failure.t, 0.0105);
  EXPECT_EQ(r.events.back().kind, EventKind::end);
  EXPECT_NEAR(r.events.back().t, 0.010, 1e-15);  // ten steps of 1 ms
}

// Requests a stop from inside the pass when the history reaches a given row.
class StopAtRow final : public PassSink {
public:
  StopAtRow(StopToken& token, const ScriptedStepper& stepper, int row) : token_(token), stepper_(stepper), row_(row) {}
  void row(const HistoryRow&) override {
    if (++rows_ == row_) {
      token_.request_stop();
      steps_at_request = stepper_.statistics().steps;
    }
  }
  void event(const PassEvent& e) override { events.push_back(e); }
  long steps_at_request = -1;
  std::vector<PassEvent> events;

private:
  StopToken& token_;
  const ScriptedStepper& stepper_;
  int row_, rows_ = 0;
};

TEST(PassLogic, AStopRequestEndsThePassAtTheEndOfTheStepUnderWay) {
  FakeBeam beam;
  FakeSurface surface;
  FakeContactLaw law;
  ScriptedStepper stepper(2e-3);  // two rows per step
  StopToken token;
  StopAtRow sink(token, stepper, 5);
  PassControl control;
  control.sink = &sink;
  control.stop = &token;
  const PassResult r = run_pass_with({beam, surface, law}, flexible_start(), options(), stepper, control);
  ASSERT_TRUE(r.failure.has_value());
  EXPECT_EQ(r.failure->kind, FailureKind::interrupted);
  ASSERT_GT(sink.steps_at_request, 0);
  EXPECT_EQ(stepper.statistics().steps, sink.steps_at_request);  // no step after the one under way
  EXPECT_LT(r.final_t, 0.02);
  ASSERT_GE(sink.events.size(), 2u);
  EXPECT_EQ(sink.events[sink.events.size() - 2].kind, EventKind::failure);
  EXPECT_EQ(sink.events.back().kind, EventKind::end);
  EXPECT_EQ(sink.events.back().t, r.final_t);
}

TEST(PassLogic, TouchesWithoutTimeAdvancingEndInTheChatterDiagnostic) {
  FakeBeam beam;
  FakeSurface surface;
  FakeContactLaw law;
  ScriptedStepper stepper(1e-3);
  for (int i = 0; i < 80; ++i) stepper.script.push_back({0.005, StepStatus::root, Root::gap_closes});
  const PassResult r = run_pass_with({beam, surface, law}, flexible_start(), options(), stepper);
  ASSERT_TRUE(r.failure.has_value());
  EXPECT_EQ(r.failure->kind, FailureKind::chatter);
  EXPECT_EQ(r.failure->t, 0.005);
  // The first touch advanced time; the guard allows 50 more that do not, and stops at the 51st.
  EXPECT_EQ(law.touches, 52);
  EXPECT_EQ(count(stepper.free_starts, FreeStart::rebound), 52);
}

TEST(PassLogic, TouchesThatAdvanceTimeAreNotChatter) {
  FakeBeam beam;
  FakeSurface surface;
  FakeContactLaw law;
  ScriptedStepper stepper(1e-3);
  for (int i = 0; i < 80; ++i) stepper.script.push_back({0.005 + 1e-9 * i, StepStatus::root, Root::gap_closes});
  const PassResult r = run_pass_with({beam, surface, law}, flexible_start(), options(), stepper);
  EXPECT_FALSE(r.failure.has_value()) << r.failure->message;
  EXPECT_EQ(law.touches, 80);
  EXPECT_DOUBLE_EQ(r.final_t, beam.time_at(M_PI / 2));
}

TEST(PassLogic, ARigidStartTurnsToTheSurfacesContactAngleAndTouchesThere) {
  FakeBeam beam;
  FakeSurface surface;
  surface.contact_angle = 0.5;  // [rad]
  FakeContactLaw law;
  ScriptedStepper stepper(1e-3);
  const PassResult r = run_pass_with({beam, surface, law}, InitialConditions{}, options(), stepper);
  ASSERT_FALSE(r.failure.has_value());
  EXPECT_EQ(law.touches, 1);
  // Free flight began only after the touch (a rebound), never at the pass's start.
  ASSERT_FALSE(stepper.free_starts.empty());
  EXPECT_EQ(stepper.free_starts.front(), FreeStart::rebound);
  EXPECT_EQ(count(stepper.free_starts, FreeStart::pass_start), 0);
  EXPECT_EQ(r.history.front().t, 0.0);
  // The first step starts at the contact time 0.5 / ω, where the touch was.
  ASSERT_FALSE(stepper.starts.empty());
  EXPECT_EQ(stepper.starts.front(), beam.time_at(0.5));
  EXPECT_DOUBLE_EQ(r.final_t, beam.time_at(M_PI / 2));
}

TEST(PassLogic, ARigidStartBeyondTheEndAngleNeverTouches) {
  FakeBeam beam;
  FakeSurface surface;
  surface.contact_angle = 2.0;  // beyond 90°
  FakeContactLaw law;
  ScriptedStepper stepper(1e-3);
  const PassResult r = run_pass_with({beam, surface, law}, InitialConditions{}, options(), stepper);
  ASSERT_FALSE(r.failure.has_value());
  EXPECT_EQ(law.touches, 0);
  EXPECT_EQ(count(stepper.free_starts, FreeStart::pass_start), 1);
}

TEST(PassLogic, AnInitialShapeThatTouchesIsRefused) {
  FakeBeam beam;
  FakeSurface surface;
  surface.gap_of_time = [](double) { return 0.0; };
  FakeContactLaw law;
  ScriptedStepper stepper;
  const PassResult r = run_pass_with({beam, surface, law}, flexible_start(), options(), stepper);
  ASSERT_TRUE(r.failure.has_value());
  EXPECT_EQ(r.failure->kind, FailureKind::initial_state);
  EXPECT_EQ(stepper.statistics().steps, 0);
}

TEST(PassLogic, TheEarlyEndAsksTheSurfaceAndEndsOnlyWhenTheArcIsClear) {
  PassOptions o = options();
  o.end_when_clear = true;
  const double t_end = 0.5 * M_PI / 100.0;
  {  // the arc is clear: the pass ends at the first check, with a `clear` event
    FakeBeam beam;
    beam.excursion_bound = 1e-3;
    FakeSurface surface;
    surface.arc_gap = -1e-3;
    FakeContactLaw law;
    ScriptedStepper stepper(1e-4);
    const PassResult r = run_pass_with({beam, surface, law}, flexible_start(), o, stepper);
    ASSERT_FALSE(r.failure.has_value());
    EXPECT_EQ(surface.arc_queries, 1);
    EXPECT_EQ(r.final_t, 1e-4);
    const auto clear = std::find_if(r.events.begin(), r.events.end(), [](const PassEvent& e) { return e.kind == EventKind::clear; });
    EXPECT_NE(clear, r.events.end());
  }
  {  // the arc may touch: the pass runs to its end, checking at the first step 0.5° of hub angle or more
     // after the last check (steps of 0.0573°: every 9 steps, 0.516°), so 90°/0.516° ≈ 174 times
    FakeBeam beam;
    beam.excursion_bound = 1e-3;
    FakeSurface surface;
    surface.arc_gap = 1e-3;
    FakeContactLaw law;
    ScriptedStepper stepper(1e-5);
    const PassResult r = run_pass_with({beam, surface, law}, flexible_start(), o, stepper);
    EXPECT_DOUBLE_EQ(r.final_t, t_end);
    const double step_deg = 1e-5 * 100.0 * 180.0 / M_PI;
    EXPECT_GE(surface.arc_queries, std::floor(90.0 / (0.5 + step_deg)));
    EXPECT_LE(surface.arc_queries, 90.0 / 0.5 + 1);
  }
  {  // a model without a bound on the excursion never asks
    FakeBeam beam;
    FakeSurface surface;
    surface.arc_gap = -1e-3;
    FakeContactLaw law;
    ScriptedStepper stepper(1e-4);
    const PassResult r = run_pass_with({beam, surface, law}, flexible_start(), o, stepper);
    EXPECT_EQ(surface.arc_queries, 0);
    EXPECT_DOUBLE_EQ(r.final_t, t_end);
  }
}

}  // namespace
