// Tip kinematics and the constraint (docs/model.md §4) against finite differences of the gap function.
#include "reference_beam.hpp"
#include "rotbeam/dynamics.hpp"
#include "rotbeam/kinematics.hpp"
#include "rotbeam/plane.hpp"

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <gtest/gtest.h>

using namespace rotbeam;

namespace {
struct Scenario {
  int n;
  double rpm;
  double t;
  unsigned seed;
};
}  // namespace

class KinematicsCheck : public ::testing::TestWithParam<Scenario> {};

TEST_P(KinematicsCheck, GradientsRatesAndGammaMatchFiniteDifferences) {
  const Scenario s = GetParam();
  BeamParameters pp;
  pp.modes = s.n;
  pp.speed_rpm = s.rpm;
  const ForeshorteningBeam model = make_beam(pp);
  const Plane plane = plane_at_depth(model, 0.02);
  Eigen::VectorXd q, v;
  rotbeam::testing::random_state(model, s.seed, 0.02, 2.0, q, v);
  TipKinematics k(s.n);
  tip_kinematics(model, plane, s.t, q, v, k);
  EXPECT_DOUBLE_EQ(k.gap, gap(model, plane, s.t, q));

  // C is quadratic in q: a central difference with any step is exact up to round-off
  // (|C| ≲ 0.13 m, step 1e-3 m: round-off ~1e-13). Tolerance 1e-10.
  const double h = 1e-3;
  for (int i = 0; i < s.n; ++i) {
    Eigen::VectorXd qp = q, qm = q;
    qp[i] += h;
    qm[i] -= h;
    EXPECT_NEAR(k.grad_gap[i], (gap(model, plane, s.t, qp) - gap(model, plane, s.t, qm)) / (2 * h), 1e-10) << "∇C_" << i;
    TipKinematics kp(s.n), km(s.n);
    tip_kinematics(model, plane, s.t, qp, v, kp);
    tip_kinematics(model, plane, s.t, qm, v, km);
    EXPECT_NEAR(k.grad_y[i], (kp.Y - km.Y) / (2 * h), 1e-10) << "∂Y/∂q_" << i;
  }
  // Along a trajectory q(τ) = q + v τ + ½ a τ², t + τ, with an arbitrary a: dC/dτ = Ċ, d²C/dτ² = ∇Cᵀa + γ.
  // Richardson-extrapolated differences with τ = 1e-5 s: truncation ~τ⁴ C⁽⁵⁾ (ω⁵ ~1e12 at 3000 rpm, so
  // ~1e-8 m/s²) and round-off ~1e-16·0.13/τ² ≈ 1e-7 m/s². Tolerance 1e-6 of ω²(r_h + L).
  Eigen::VectorXd a = Eigen::VectorXd::LinSpaced(s.n, 100.0, -300.0);
  auto c_at = [&](double tau) {
    Eigen::VectorXd qt = q + v * tau + 0.5 * a * tau * tau;
    return gap(model, plane, s.t + tau, qt);
  };
  const double tau = 1e-5;
  const double d1 = (c_at(tau) - c_at(-tau)) / (2 * tau), d1h = (c_at(tau / 2) - c_at(-tau / 2)) / tau;
  const double rate = (4 * d1h - d1) / 3;
  const double d2 = (c_at(tau) - 2 * c_at(0) + c_at(-tau)) / (tau * tau);
  const double d2h = (c_at(tau / 2) - 2 * c_at(0) + c_at(-tau / 2)) / (tau * tau / 4);
  const double accel = (4 * d2h - d2) / 3;
  const double scale = model.omega * model.omega * (model.hub_radius + model.length);
  EXPECT_NEAR(k.gap_rate, rate, 1e-9 * model.omega * (model.hub_radius + model.length)) << "Ċ";
  EXPECT_NEAR(k.VX, k.gap_rate, 1e-15);
  EXPECT_NEAR(k.grad_gap.dot(a) + k.gamma, accel, 1e-6 * scale) << "C̈ = ∇Cᵀq̈ + γ";
  // Ÿ_t = (∂Y_t/∂q)ᵀa + γ_Y along the same trajectory (same error budget).
  auto y_traj = [&](double tt) {
    TipKinematics kk(s.n);
    Eigen::VectorXd qt = q + v * tt + 0.5 * a * tt * tt;
    tip_kinematics(model, plane, s.t + tt, qt, v, kk);
    return kk.Y;
  };
  const double y2 = (y_traj(tau) - 2 * y_traj(0) + y_traj(-tau)) / (tau * tau);
  const double y2h = (y_traj(tau / 2) - 2 * y_traj(0) + y_traj(-tau / 2)) / (tau * tau / 4);
  EXPECT_NEAR(k.grad_y.dot(a) + k.bias_ay, (4 * y2h - y2) / 3, 1e-6 * scale) << "Ÿ = (∂Y/∂q)ᵀq̈ + γ_Y";
  // ∂C/∂t alone (q frozen).
  const double dt = 1e-6;
  EXPECT_NEAR(k.gap_time_partial, (gap(model, plane, s.t + dt, q) - gap(model, plane, s.t - dt, q)) / (2 * dt),
              1e-7 * model.omega * (model.hub_radius + model.length));
  // V_Y by differencing Y_t along the same trajectory.
  auto y_at = [&](double t2) {
    TipKinematics kk(s.n);
    Eigen::VectorXd qt = q + v * t2;
    tip_kinematics(model, plane, s.t + t2, qt, v, kk);
    return kk.Y;
  };
  const double y1 = (y_at(tau) - y_at(-tau)) / (2 * tau), y1h = (y_at(tau / 2) - y_at(-tau / 2)) / tau;
  EXPECT_NEAR(k.VY, (4 * y1h - y1) / 3, 1e-9 * model.omega * (model.hub_radius + model.length));
}

INSTANTIATE_TEST_SUITE_P(States, KinematicsCheck,
                         ::testing::Values(Scenario{2, 550, 0.024, 1}, Scenario{5, 550, 0.0248, 2},
                                           Scenario{5, 3000, 0.0046, 3}, Scenario{10, 3000, 0.003, 4}));

TEST(Kinematics, StraightBeamTipFollowsTheHub) {
  // q = 0: X_t = (r_h + L) cos θ, Y_t = (r_h + L) sin θ, V = ω(r_h + L)(−sin θ, cos θ) exactly.
  const ForeshorteningBeam model = make_beam(BeamParameters{});
  const Plane plane = plane_at_depth(model, 0.02);
  const Eigen::VectorXd z = Eigen::VectorXd::Zero(model.n);
  TipKinematics k(model.n);
  const double t = 0.01, th = model.theta(t), R = model.hub_radius + model.length;
  tip_kinematics(model, plane, t, z, z, k);
  EXPECT_NEAR(k.X, R * std::cos(th), 1e-16);
  EXPECT_NEAR(k.Y, R * std::sin(th), 1e-16);
  EXPECT_NEAR(k.VX, -model.omega * R * std::sin(th), 1e-14);
  EXPECT_NEAR(k.VY, model.omega * R * std::cos(th), 1e-14);
}

TEST(Kinematics, TheDrawnShapeIsTheModelsCentreline) {
  // BeamModel::shape (the pictures' and animations' filament) against independent routes: at ξ = 1
  // the model's tip_position (1e-15 m: the same integral by another rule), at ξ = 0 the clamp
  // (r_h, 0), and inside y = Σ q_i S_i(ξ) with the foreshortening (1/2L)∫₀^ξ (Σ q_i S_i')² by
  // adaptive Gauss–Kronrod (1e-14 m). Many points in one call equal one point per call.
  using GK = boost::math::quadrature::gauss_kronrod<double, 31>;
  for (int n : {3, 5, 12}) {
    BeamParameters p;
    p.modes = n;
    const ForeshorteningBeam model = make_beam(p);
    const ModalBasis& b = model.integrals->basis;
    Eigen::VectorXd q(n);
    for (int i = 0; i < n; ++i) q[i] = 4e-3 * std::cos(1.3 * i + 0.4) / (1 + i);
    Eigen::VectorXd xi = Eigen::VectorXd::LinSpaced(41, 0.0, 1.0);
    Eigen::MatrixXd r(xi.size(), 2);
    model.shape(q, xi, r);
    const Eigen::Vector2d tip = model.tip_position(q);
    EXPECT_NEAR(r(40, 0), tip.x(), 1e-15) << n;
    EXPECT_NEAR(r(40, 1), tip.y(), 1e-15) << n;
    EXPECT_DOUBLE_EQ(r(0, 0), model.hub_radius);
    EXPECT_NEAR(r(0, 1), 0.0, 1e-17);  // S_i(0) = 0 up to rounding
    for (int k : {7, 20, 33}) {
      const double x = xi[k];
      double y = 0.0;
      for (int i = 0; i < n; ++i) y += q[i] * b.shape(i, x, 0);
      const double u = GK::integrate(
                           [&](double s) {
                             double v = 0.0;
                             for (int i = 0; i < n; ++i) v += q[i] * b.shape(i, s, 1);
                             return v * v;
                           },
                           0.0, x, 12, 1e-15) /
                       (2.0 * model.length);
      EXPECT_NEAR(r(k, 1), y, 1e-14) << n << " ξ = " << x;
      EXPECT_NEAR(r(k, 0), model.hub_radius + x * model.length - u, 1e-14) << n << " ξ = " << x;
      Eigen::MatrixXd one(1, 2);
      model.shape(q, xi.segment(k, 1), one);
      EXPECT_NEAR(one(0, 0), r(k, 0), 1e-15);
      EXPECT_NEAR(one(0, 1), r(k, 1), 1e-15);
    }
    Eigen::VectorXd backwards(2);
    backwards << 0.5, 0.2;
    Eigen::MatrixXd two(2, 2);
    EXPECT_THROW(model.shape(q, backwards, two), std::invalid_argument);
  }
}
