// Energies and hub angular momentum (SPEC §3, §7) against direct quadrature (tests/reference_beam.*).
#include "reference_beam.hpp"
#include "rotbeam/energy.hpp"

#include <gtest/gtest.h>

using namespace rotbeam;

TEST(Energy, EveryTermMatchesDirectQuadrature) {
  // Tolerance 1e-12 relative to each term's size (both routes are exact quadratures to ~1e-14).
  for (int n : {2, 5, 10}) {
    for (double rpm : {550.0, 3000.0}) {
      PhysicalParameters pp;
      pp.modes = n;
      pp.speed_rpm = rpm;
      const Model model = make_model(pp);
      const rotbeam::testing::ReferenceBeam ref(model, 24);
      Workspace ws(n);
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
  const Model model = make_model(PhysicalParameters{});
  Workspace ws(model.n);
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
