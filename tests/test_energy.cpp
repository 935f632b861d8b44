// Energies and hub angular momentum (docs/model.md §3, §7) against direct quadrature (tests/reference_beam.*).
#include "reference_beam.hpp"
#include "rotbeam/energy.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

using namespace rotbeam;

TEST(Energy, EveryTermMatchesDirectQuadrature) {
  // Tolerance 1e-12 relative to each term's size (both routes are exact quadratures to ~1e-14).
  for (int n : {2, 5, 10}) {
    for (double rpm : {550.0, 3000.0}) {
      BeamParameters pp;
      pp.modes = n;
      pp.speed_rpm = rpm;
      const ForeshorteningBeam model = make_beam(pp);
      const rotbeam::testing::ReferenceBeam ref(model, 24);
      ForeshorteningWorkspace ws(n);
      for (unsigned seed = 1; seed <= 3; ++seed) {
        Eigen::VectorXd q, v;
        rotbeam::testing::random_state(model, seed, 0.01 * seed, 1.5, q, v);
        const EnergyTerms e = evaluate_energy(model, q, v, ws);
        EXPECT_NEAR(e.t0, ref.t0(q), 1e-12 * std::abs(ref.t0(q)));
        EXPECT_NEAR(e.t1, ref.t1(q, v), 1e-12 * std::abs(ref.t0(q)));
        EXPECT_NEAR(e.t2, ref.t2(q, v), 1e-12 * std::abs(ref.t2(q, v)));
        EXPECT_NEAR(e.potential, ref.potential(q), 1e-12 * std::abs(ref.potential(q)));
        EXPECT_NEAR(e.angular_momentum, ref.angular_momentum(q, v), 1e-12 * std::abs(ref.angular_momentum(q, v)));
        EXPECT_NEAR(e.jacobi, e.t2 - e.t0 + e.potential, 1e-15 * std::abs(e.t0));
        EXPECT_NEAR(e.kinetic, e.t0 + e.t1 + e.t2, 1e-15 * std::abs(e.t0));
      }
    }
  }
}

TEST(Energy, StraightBeamClosedForms) {
  // q = 0: J = m (r_h² + r_h L + L²/3), H_z = ω J, U = T2 = T1 = 0 (exact up to 1e-15 relative).
  const ForeshorteningBeam model = make_beam(BeamParameters{});
  ForeshorteningWorkspace ws(model.n);
  const Eigen::VectorXd z = Eigen::VectorXd::Zero(model.n);
  const EnergyTerms e = evaluate_energy(model, z, z, ws);
  const double L = model.length, rh = model.hub_radius;
  const double j = model.mass * (rh * rh + rh * L + L * L / 3);
  EXPECT_NEAR(e.spin_inertia, j, 1e-15 * j);
  EXPECT_NEAR(e.angular_momentum, model.omega * j, 1e-15 * model.omega * j);
  EXPECT_EQ(e.potential, 0.0);
  EXPECT_EQ(e.t2, 0.0);
  EXPECT_EQ(e.t1, 0.0);
}

#include "rotbeam/pass.hpp"
#include "rotbeam/plane.hpp"

TEST(HubTorque, WorkOfTheHubEqualsTheChangeOfInertialEnergyInFreeFlight) {
  // The history's τ comes from dH_z/dt; independently, in free flight the inertial energy
  // E = T0 + T1 + T2 + U changes only by the hub's work ∫τω dt. Free pass (surface out of reach),
  // q̇(0) = (2, 1, 0, 0, 0) m/s, adaptive rtol 1e-12, every step sampled; trapezoidal ∫τω dt.
  // Tolerance 1e-6 of the largest |E − E(0)| (the trapezoidal error over ~µs steps is ~1e-8 of it).
  BeamParameters p;
  p.speed_rpm = 3000;
  const ForeshorteningBeam model = make_beam(p);
  const Plane plane(1.0);
  InitialConditions ic;
  ic.rigid_start = false;
  ic.q0 = Eigen::VectorXd::Zero(5);
  ic.qd0 = Eigen::VectorXd::Zero(5);
  ic.qd0 << 2.0, 1.0, 0.0, 0.0, 0.0;
  PassOptions opt;
  opt.rtol = 1e-12;
  opt.atol = 1e-15;
  opt.output_interval_s = 0.0;
  opt.max_step_s = 1e-6;  // rows (steps) ~µs apart whatever the scheme's own step: the trapezoid's error stays ~1e-8
  const PassResult r = run_pass({model, plane, default_contact_law()}, ic, opt);
  ASSERT_FALSE(r.failure);
  ForeshorteningWorkspace ws(5);
  auto energy = [&](const HistoryRow& row) {
    const EnergyTerms e = evaluate_energy(model, row.q, row.qd, ws);
    return e.kinetic + e.potential;
  };
  const double e0 = energy(r.history.front());
  double work = 0.0, worst = 0.0, scale = 0.0;
  for (std::size_t i = 1; i < r.history.size(); ++i) {
    const HistoryRow &a = r.history[i - 1], &b = r.history[i];
    work += 0.5 * (a.hub_torque + b.hub_torque) * model.omega * (b.t - a.t);
    const double de = energy(b) - e0;
    scale = std::max(scale, std::abs(de));
    worst = std::max(worst, std::abs(de - work));
  }
  std::printf("%zu rows: max |ΔE − ∫τω dt| = %.3e J against max |ΔE| = %.3e J\n", r.history.size(), worst, scale);
  EXPECT_GT(scale, 1e-6);
  EXPECT_LT(worst, 1e-6 * scale);
}
