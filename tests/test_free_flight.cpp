// Free flight with the thesis's RK5: conservation of the Jacobi integral over a whole pass,
// the order of the method, and location of the first C = 0 crossing.
#include "rotbeam/energy.hpp"
#include "rotbeam/free_flight.hpp"
#include "rotbeam/kinematics.hpp"

#include <cmath>
#include <gtest/gtest.h>

using namespace rotbeam;

namespace {
Model base_model(double rpm, int n = 5) {
  PhysicalParameters pp;
  pp.speed_rpm = rpm;
  pp.modes = n;
  return make_model(pp);
}
}  // namespace

class JacobiIntegral : public ::testing::TestWithParam<double> {};

TEST_P(JacobiIntegral, ConservedOverAFreePassToNinetyDegrees) {
  // θ0 = −90° → +90° with q̇(0) = (2, 0, 0, 0, 0) m/s, h = 1e-6 s, surface ignored.
  // Required: max |h(t) − h(0)| ≤ 1e-9 |h(0)|. Also reported relative to the vibration energy
  // T2 + U (a stricter scale, since |h| is dominated by the spin term T0).
  const double rpm = GetParam();
  const Model model = base_model(rpm);
  Workspace ws(model.n), ews(model.n);
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(5), v0 = Eigen::VectorXd::Zero(5);
  v0[0] = 2.0;
  const double h0 = evaluate_energy(model, q0, v0, ews).jacobi;
  double drift = 0.0, vib = 0.0;
  FreeFlightOptions opt;
  opt.step_s = 1e-6;
  opt.end_time_s = model.time_at(M_PI / 2);
  opt.stop_at_contact = false;
  const FreeFlightResult r = integrate_free_flight(model, 0.0, q0, v0, opt, ws,
                                                   [&](double, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
                                                     const EnergyTerms e = evaluate_energy(model, q, v, ews);
                                                     drift = std::max(drift, std::abs(e.jacobi - h0));
                                                     vib = std::max(vib, e.t2 + e.potential);
                                                   });
  EXPECT_NEAR(r.t, opt.end_time_s, 1e-15);
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
  const Model model = base_model(3000.0, 3);
  Workspace ws(model.n);
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(3), v0(3);
  v0 << 4.0, 1.0, 0.5;
  auto run = [&](double h) {
    FreeFlightOptions opt;
    opt.step_s = h;
    opt.end_time_s = 0.01;
    opt.stop_at_contact = false;
    return integrate_free_flight(model, 0.0, q0, v0, opt, ws).q;
  };
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
  const Model model = base_model(550.0);
  Workspace ws(model.n);
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(5), v0 = Eigen::VectorXd::Zero(5);
  v0[0] = 0.1;
  FreeFlightOptions opt;
  opt.end_time_s = model.time_at(M_PI / 2);
  const FreeFlightResult r = integrate_free_flight(model, 0.0, q0, v0, opt, ws);
  ASSERT_EQ(r.end, FreeFlightEnd::contact);
  TipKinematics k(model.n);
  tip_kinematics(model, r.t, r.q, r.qd, k);
  EXPECT_NEAR(k.gap, 0.0, 1e-13);
  EXPECT_GT(k.gap_rate, 0.0);
  EXPECT_LT(std::abs(r.t - r.linear_estimate_t), opt.step_s);
}

TEST(FreeFlight, StopsExactlyAtTheEndAngleWithoutContact) {
  PhysicalParameters pp;
  pp.depth_fraction = 0.02;
  const Model model = make_model(pp);
  Workspace ws(model.n);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(5);
  FreeFlightOptions opt;
  opt.end_time_s = model.time_at(-20.0 * M_PI / 180.0);  // before the −8.1° contact
  const FreeFlightResult r = integrate_free_flight(model, 0.0, z, z, opt, ws);
  EXPECT_EQ(r.end, FreeFlightEnd::end_time);
  EXPECT_DOUBLE_EQ(r.t, opt.end_time_s);
  EXPECT_LT(r.min_gap, 0.0);
}
