// Free flight with the thesis's RK5: conservation of the Jacobi integral over a whole pass,
// the order of the method, and location of the first C = 0 crossing.
#include "rotbeam/energy.hpp"
#include "rotbeam/kinematics.hpp"
#include "rotbeam/plane.hpp"
#include "rotbeam/rk5.hpp"
#include "rotbeam/stepper.hpp"

#include <cmath>
#include <functional>
#include "test_support.hpp"

#include <gtest/gtest.h>

using namespace rotbeam;

namespace {
ForeshorteningBeam base_model(double rpm, int n = 5) {
  BeamParameters pp;
  pp.speed_rpm = rpm;
  pp.modes = n;
  return make_beam(pp);
}

struct FreeFlight {
  bool contact = false;        // stopped at a located C = 0 crossing
  double t = 0;
  Eigen::VectorXd q, qd;
  long steps = 0;
  double linear_estimate_t = 0;  // the thesis's linear interpolation over the crossing step
  double min_gap = -INFINITY;    // the largest gap seen (closest approach)
};

// Free flight with the thesis stepper (fixed-step RK5, C = 0 located on the step) from t = 0 to
// t_end or the first crossing; `observer` sees every accepted state.
FreeFlight free_flight(const ForeshorteningBeam& model, const Surface& surface, const Eigen::VectorXd& q0,
                       const Eigen::VectorXd& v0, double step, double t_end,
                       const std::function<void(double, const Eigen::VectorXd&, const Eigen::VectorXd&)>& observer = {}) {
  PassOptions opt;
  opt.scheme = Scheme::thesis;
  opt.free_step_s = step;
  const System system{model, surface, default_contact_law()};
  const auto stepper = make_thesis_stepper(system, opt);
  FilamentState s(model.n);
  s.q = q0;
  s.qd = v0;
  stepper->begin_free(s, FreeStart::pass_start);
  FreeFlight r;
  r.min_gap = gap(model, surface, s.t, s.q);
  while (s.t < t_end) {
    const FilamentState before = s;
    const StepOutcome o = stepper->step(s, t_end);
    EXPECT_NE(o.status, StepStatus::failed);
    r.min_gap = std::max(r.min_gap, gap(model, surface, s.t, s.q));
    if (o.status == StepStatus::root) {
      // The thesis's estimate: linear interpolation of C over the whole RK5 step that crossed.
      const double h = std::min(step, t_end - before.t);
      Rk5Stepper rk(model.n);
      ForeshorteningWorkspace ws(model.n);
      Eigen::VectorXd q1(model.n), v1(model.n);
      rk.step([&](double, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                  Eigen::VectorXd& a) { acceleration(model, q, v, nullptr, ws, a); },
              before.t, before.q, before.qd, h, q1, v1);
      const double c0 = gap(model, surface, before.t, before.q), c1 = gap(model, surface, before.t + h, q1);
      r.linear_estimate_t = before.t - c0 * h / (c1 - c0);
      r.contact = true;
      break;
    }
    if (observer) observer(s.t, s.q, s.qd);
  }
  r.t = s.t;
  r.q = s.q;
  r.qd = s.qd;
  r.steps = stepper->statistics().steps;
  return r;
}
}  // namespace

class JacobiIntegral : public ::testing::TestWithParam<double> {};

TEST_P(JacobiIntegral, ConservedOverAFreePassToNinetyDegrees) {
  // θ0 = −90° → +90° with q̇(0) = (2, 0, 0, 0, 0) m/s, h = 1e-6 s, surface ignored.
  // Required: max |h(t) − h(0)| ≤ 1e-9 |h(0)|. Also reported relative to the vibration energy
  // T2 + U (a stricter scale, since |h| is dominated by the spin term T0).
  const double rpm = GetParam();
  const ForeshorteningBeam model = base_model(rpm);
  ForeshorteningWorkspace ws(model.n), ews(model.n);
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(5), v0 = Eigen::VectorXd::Zero(5);
  v0[0] = 2.0;
  const double h0 = evaluate_energy(model, q0, v0, ews).jacobi;
  double drift = 0.0, vib = 0.0;
  const Plane far(1.0);  // surface ignored: out of reach
  const double end_time_s = model.time_at(M_PI / 2);
  const FreeFlight r = free_flight(model, far, q0, v0, 1e-6, end_time_s,
                                   [&](double, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
                                     const EnergyTerms e = evaluate_energy(model, q, v, ews);
                                     drift = std::max(drift, std::abs(e.jacobi - h0));
                                     vib = std::max(vib, e.t2 + e.potential);
                                   });
  EXPECT_NEAR(r.t, end_time_s, 1e-15);
  std::printf("%.0f rpm: %ld steps, max |Δh| = %.3e J = %.3e of |h(0)| = %.3e of max(T2 + U)\n", rpm, r.steps, drift,
              drift / std::abs(h0), drift / vib);
  EXPECT_LE(drift / std::abs(h0), 1e-9);
  EXPECT_LE(drift / vib, 1e-8);
}

INSTANTIATE_TEST_SUITE_P(Speeds, JacobiIntegral, ::testing::Values(550.0, 3000.0));

TEST(ButcherRk5, FifthOrderConvergence) {
  // Error at a fixed time against a step-0.3125 µs solution for h = 10, 5, 2.5 µs at 3000 rpm with
  // 3 modes disturbed (highest Ω h ≈ 0.1, in the asymptotic range): successive error
  // ratios must approach 2⁵ = 32 (accept 26…38).
  const ForeshorteningBeam model = base_model(3000.0, 3);
  ForeshorteningWorkspace ws(model.n);
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(3), v0(3);
  v0 << 4.0, 1.0, 0.5;
  const Plane far(1.0);  // surface ignored: out of reach
  auto run = [&](double h) { return free_flight(model, far, q0, v0, h, 0.01).q; };
  const Eigen::VectorXd ref = run(0.3125e-6);
  const double e8 = (run(10e-6) - ref).norm(), e4 = (run(5e-6) - ref).norm(), e2 = (run(2.5e-6) - ref).norm();
  std::printf("RK5 errors: h=10us %.3e, 5us %.3e, 2.5us %.3e; ratios %.1f %.1f\n", e8, e4, e2, e8 / e4, e4 / e2);
  EXPECT_GT(e8 / e4, 26.0);
  EXPECT_LT(e8 / e4, 38.0);
  EXPECT_GT(e4 / e2, 26.0);
  EXPECT_LT(e4 / e2, 38.0);
}

TEST(FreeFlight, LocatesTheFirstCrossingOnTheStepItself) {
  // The located contact time must put C within 1e-13 m of zero, with the tip approaching, and
  // differ from the thesis's linear interpolation by less than one step.
  const ForeshorteningBeam model = base_model(550.0);
  const Plane plane = plane_at_depth(model, 0.02);
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(5), v0 = Eigen::VectorXd::Zero(5);
  v0[0] = 0.1;
  const double step_s = 1e-6;
  const FreeFlight r = free_flight(model, plane, q0, v0, step_s, model.time_at(M_PI / 2));
  ASSERT_TRUE(r.contact);
  TipKinematics k(model.n);
  tip_kinematics(model, plane, r.t, r.q, r.qd, k);
  EXPECT_NEAR(k.gap, 0.0, 1e-13);
  EXPECT_GT(k.gap_rate, 0.0);
  EXPECT_LT(std::abs(r.t - r.linear_estimate_t), step_s);
}

TEST(FreeFlight, StopsExactlyAtTheEndAngleWithoutContact) {
  BeamParameters pp;
  const ForeshorteningBeam model = make_beam(pp);
  const Plane plane = plane_at_depth(model, 0.02);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(5);
  const double end_time_s = model.time_at(-20.0 * M_PI / 180.0);  // before the −8.1° contact
  const FreeFlight r = free_flight(model, plane, z, z, 1e-6, end_time_s);
  EXPECT_FALSE(r.contact);
  EXPECT_DOUBLE_EQ(r.t, end_time_s);
  EXPECT_LT(r.min_gap, 0.0);
}
