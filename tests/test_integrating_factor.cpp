// The adaptive scheme's integrating factor (integrating_factor.hpp) and the early end of a pass that
// can no longer touch (simulation.end_when_clear, BeamModel::tip_excursion_bound), each against an
// independent route: the matrix exponential of the linear modal system, the linear system's own
// acceleration (whose remainder must vanish), passes without the factor at a tight tolerance, the
// energies of the model evaluated directly, and whole passes that run to their end angle.
#include "rotbeam/case.hpp"
#include "rotbeam/dynamics.hpp"
#include "rotbeam/foreshortening_beam.hpp"
#include "rotbeam/integrating_factor.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <unsupported/Eigen/MatrixFunctions>

using namespace rotbeam;

namespace {

PassResult run(std::vector<std::string> sets, double interval = 1e30) {
  sets.push_back("output.interval_s=" + std::to_string(interval));
  return run_case(build_case(load_config_string("", sets)));
}

// A linear system with every kind of mode: stiff and soft, undamped, under-, critically and
// over-damped, and one with negative stiffness; a non-scalar mass matrix.
Linearization mixed_system() {
  Linearization lin;
  const int n = 5;
  Eigen::MatrixXd r = Eigen::MatrixXd::Random(n, n);
  lin.mass = r * r.transpose() + n * Eigen::MatrixXd::Identity(n, n);  // positive definite
  // K and C diagonal in the M-orthonormal modes Φ: K = M Φ Λ Φᵀ M, C = M Φ D Φᵀ M.
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> g(Eigen::MatrixXd::Identity(n, n), lin.mass);
  const Eigen::MatrixXd phi = g.eigenvectors();  // Φᵀ M Φ = 1
  const Eigen::VectorXd omega2 = (Eigen::VectorXd(n) << 4e6, 2.5e3, 900.0, 100.0, -50.0).finished();
  const Eigen::VectorXd two_sigma = (Eigen::VectorXd(n) << 0.0, 10.0, 60.0, 40.0, 3.0).finished();  // 60 = 2·30: critical
  lin.stiffness = lin.mass * phi * omega2.asDiagonal() * phi.transpose() * lin.mass;
  lin.damping = lin.mass * phi * two_sigma.asDiagonal() * phi.transpose() * lin.mass;
  lin.stiffness = 0.5 * (lin.stiffness + lin.stiffness.transpose()).eval();
  lin.damping = 0.5 * (lin.damping + lin.damping.transpose()).eval();
  return lin;
}

// The physical state (q, q̇) after τ of the linear system M q̈ + C q̇ + K q = 0, by the matrix
// exponential of its first-order form (Eigen's MatrixFunctions: an independent route).
void linear_flow(const Linearization& lin, double tau, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                 Eigen::VectorXd& q_out, Eigen::VectorXd& qd_out) {
  const int n = static_cast<int>(q.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  a.topRightCorner(n, n).setIdentity();
  const Eigen::MatrixXd minv = lin.mass.inverse();
  a.bottomLeftCorner(n, n) = -minv * lin.stiffness;
  a.bottomRightCorner(n, n) = -minv * lin.damping;
  Eigen::VectorXd y(2 * n);
  y << q, qd;
  const Eigen::VectorXd z = (a * tau).exp() * y;
  q_out = z.head(n);
  qd_out = z.tail(n);
}

}  // namespace

TEST(IntegratingFactor, PropagatesTheLinearSystemAsItsMatrixExponential) {
  // v = (η, η̇) at τ = 0 and q(τ) = V E(τ) v must be the linear flow: every mode kind, several τ.
  // Tolerance 1e-9 of the state's size: the matrix exponential's own rounding at |A|τ ≈ 20.
  // A wrong sign of σ, Ω² or the off-diagonal entries of E fails it by orders of magnitude.
  const Linearization lin = mixed_system();
  IntegratingFactor f(lin);
  const int n = f.size();
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(n, 1e-3, -2e-3), qd = Eigen::VectorXd::LinSpaced(n, 0.3, 0.1);
  Eigen::VectorXd v(2 * n), q1(n), qd1(n), q2(n), qd2(n);
  f.to_integration(q.data(), qd.data(), v.data());
  for (double tau : {0.0, 1e-5, 3e-4, 0.01, 0.05}) {
    f.at(tau);
    f.to_physical(v.data(), q1.data(), qd1.data());
    linear_flow(lin, tau, q, qd, q2, qd2);
    const double scale = std::max(q2.cwiseAbs().maxCoeff(), 1e-3);
    const double vscale = std::max(qd2.cwiseAbs().maxCoeff(), 0.3);
    EXPECT_LE((q1 - q2).cwiseAbs().maxCoeff(), 1e-9 * scale) << "τ = " << tau;
    EXPECT_LE((qd1 - qd2).cwiseAbs().maxCoeff(), 1e-9 * vscale) << "τ = " << tau;
  }
}

TEST(IntegratingFactor, TheLinearSystemLeavesNoRemainder) {
  // With q̈ the linear system's own acceleration, dv/dt must vanish (to rounding, 1e-12 of the
  // scale |v|·Ω_max): the factor carries all of the linear motion. A wrong Ω² or σ term leaves a
  // remainder of the size of the acceleration itself.
  const Linearization lin = mixed_system();
  IntegratingFactor f(lin);
  const int n = f.size();
  Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(2 * n, -1e-3, 2e-3), q(n), qd(n), dv(2 * n);
  for (double tau : {0.0, 2e-4, 0.03}) {
    f.at(tau);
    f.to_physical(v.data(), q.data(), qd.data());
    const Eigen::VectorXd qdd = -lin.mass.ldlt().solve(lin.stiffness * q + lin.damping * qd);
    f.derivative(qdd.data(), dv.data());
    const double scale = v.cwiseAbs().maxCoeff() * f.highest_frequency() * std::exp(f.largest_decay_rate() * tau);
    EXPECT_LE(dv.cwiseAbs().maxCoeff(), 1e-12 * scale) << "τ = " << tau;
  }
}

TEST(IntegratingFactor, PassesEqualThoseWithoutItAtATightTolerance) {
  // Base case, 3000 rpm with frictional impacts, a flexible start, a damped filament, 8 modes: with
  // and without the factor at rtol 1e-11 the counts are equal and the last separation and the
  // normal impulse agree to 1e-8 relative (measured ≤ 1e-9; the two schemes' own errors at 1e-11).
  const std::vector<std::vector<std::string>> cases = {
      {},
      {"hub.speed_rpm=3000", "impact.friction=coulomb"},
      {"initial.modal_velocity=[0.5,0.2,0,0,0]", "surface.friction=0.2"},
      {"beam.damping_ratio=0.02", "hub.speed_rpm=1500"},
      {"beam.modes=8", "surface.depth_fraction=0.01"},
  };
  for (const auto& sets : cases) {
    std::vector<std::string> with = sets, without = sets;
    with.push_back("simulation.rtol=1e-11");
    with.push_back("simulation.integrating_factor=true");
    without.push_back("simulation.rtol=1e-11");
    without.push_back("simulation.integrating_factor=false");
    const PassResult a = run(with), b = run(without);
    const std::string name = sets.empty() ? "base" : sets[0];
    ASSERT_FALSE(a.failure) << name;
    ASSERT_FALSE(b.failure) << name;
    EXPECT_EQ(a.summary.impacts, b.summary.impacts) << name;
    EXPECT_EQ(a.summary.contact_episodes, b.summary.contact_episodes) << name;
    EXPECT_NEAR(a.summary.last_separation_deg, b.summary.last_separation_deg,
                1e-8 * std::abs(b.summary.last_separation_deg)) << name;
    EXPECT_NEAR(a.summary.ledger[LedgerTerm::normal_impulse], b.summary.ledger[LedgerTerm::normal_impulse], 1e-8 * b.summary.ledger[LedgerTerm::normal_impulse])
        << name;
  }
}

TEST(IntegratingFactor, TakesFewerStepsAtTheSameTolerance) {
  // The point of the factor: at the default rtol the base case takes 2.5× fewer steps (measured
  // 17 472 → 6 829 at 5 modes; 81 044 → 22 677 at 10). Guard: at least 2× at 5 modes.
  const PassResult a = run({}), b = run({"simulation.integrating_factor=false"});
  EXPECT_LT(2 * a.summary.steps, b.summary.steps);
}

TEST(IntegratingFactor, AutoUsesItForUndampedFilamentsOnly) {
  // "auto" (the default): the factor for an undamped filament (the steps of `true`), plain pairs
  // with damping (the steps of `false`): with ζ = 0.2 the factor takes 1.3× the plain pair's steps
  // (measured 5 051 against 3 961), because it turns the damped modes' forced, slowly varying
  // response into fast oscillation of its variables.
  const PassResult undamped = run({}), undamped_on = run({"simulation.integrating_factor=true"});
  EXPECT_EQ(undamped.summary.steps, undamped_on.summary.steps);
  const PassResult damped = run({"beam.damping_ratio=0.2"}),
                   damped_off = run({"beam.damping_ratio=0.2", "simulation.integrating_factor=false"}),
                   damped_on = run({"beam.damping_ratio=0.2", "simulation.integrating_factor=true"});
  EXPECT_EQ(damped.summary.steps, damped_off.summary.steps);
  EXPECT_GT(damped_on.summary.steps, damped_off.summary.steps);
  EXPECT_THROW(load_config_string("", {"simulation.integrating_factor=\"sometimes\""}), ConfigError);
}

TEST(ExcursionBound, TheEffectivePotentialIsAboveItsQuadraticLowerBound) {
  // V(q) − V(0) ≥ E − βE² (foreshortening_beam.hpp) with V = U − T0 from the model's own energies
  // (energy.cpp) at random shapes up to |y_t|/L ≈ 0.5 and at 550–5000 rpm; and μ is the largest
  // ratio qᵀISP(1)q / qᵀKq (attained by the top generalised eigenvector, never exceeded by random
  // shapes). The bound has slack (the quartic bending energy is dropped), so a β off by 2 still
  // holds here: what fails is a correction of the wrong sign, a wrong V(0) (checked against the
  // energy at q = 0) or a wrong μ (checked against the ratio).
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (double rpm : {550.0, 2000.0, 5000.0}) {
    BeamParameters p;
    p.speed_rpm = rpm;
    const ForeshorteningBeam beam = make_beam(p);
    auto ws = beam.make_workspace();
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(beam.n);
    const double v0 = beam.energy(zero, zero, *ws).jacobi;
    EXPECT_NEAR(v0, beam.excursion_v0, 1e-12 * std::abs(v0));
    const Eigen::MatrixXd k = linear_stiffness(beam);
    const double beta = beam.omega * beam.omega * beam.mass * beam.excursion_mu * beam.excursion_mu /
                        (2.0 * beam.length * beam.length);
    for (int trial = 0; trial < 200; ++trial) {
      Eigen::VectorXd q(beam.n);
      for (int i = 0; i < beam.n; ++i) q[i] = normal(rng) / (1.0 + i * i);
      q *= (0.5 * beam.length * (trial + 1) / 200.0) / std::abs(beam.integrals->s_tip.dot(q));
      const double e = 0.5 * q.dot(k * q);
      const double v = beam.energy(q, zero, *ws).jacobi - v0;
      EXPECT_GE(v, e - beta * e * e - 1e-12 * std::abs(v0)) << rpm << " rpm, trial " << trial;
      EXPECT_LE(q.dot(beam.integrals->isp_tip * q), beam.excursion_mu * 2.0 * e * (1.0 + 1e-12));
    }
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> g(beam.integrals->isp_tip, k);
    const Eigen::VectorXd top = g.eigenvectors().col(beam.n - 1);
    EXPECT_NEAR(top.dot(beam.integrals->isp_tip * top) / top.dot(k * top), beam.excursion_mu, 1e-12 * beam.excursion_mu);
  }
}

TEST(ExcursionBound, HoldsForTheRestOfRealFreeFlights) {
  // After the last separation of whole passes (base; 3000 rpm; damped; a flexible start), the tip's
  // distance from its undeformed position never exceeds the bound computed at the first row after
  // it, at any later row; the bound is also not uselessly loose (within 4× of the largest distance).
  const std::vector<std::vector<std::string>> cases = {
      {}, {"hub.speed_rpm=3000"}, {"beam.damping_ratio=0.05"}, {"initial.modal_velocity=[0.5,0.2,0,0,0]"}};
  for (const auto& sets : cases) {
    const Case c = build_case(load_config_string("", [&] {
      auto all = sets;
      all.push_back("output.interval_s=2e-5");
      return all;
    }()));
    const PassResult r = run_case(c);
    ASSERT_FALSE(r.failure);
    const double t_sep = c.beam->time_at(r.summary.last_separation_deg * M_PI / 180.0);
    auto ws = c.beam->make_workspace();
    double bound = NAN, largest = 0.0;
    for (const HistoryRow& row : r.history) {
      if (row.t <= t_sep + 1e-9) continue;
      if (std::isnan(bound)) bound = c.beam->tip_excursion_bound(row.q, row.qd, *ws);
      const Eigen::Vector2d tip = c.beam->tip_position(row.q);
      largest = std::max(largest, std::hypot(tip.x() - c.beam->tip_radius(), tip.y()));
    }
    const std::string name = sets.empty() ? "base" : sets[0];
    ASSERT_TRUE(std::isfinite(bound)) << name;
    EXPECT_LE(largest, bound) << name;
    EXPECT_GT(4.0 * largest, bound) << name;
  }
}

TEST(EndWhenClear, EndsEarlyWithTheSameContactAndSaysWhere) {
  // The pass ended early has the very same contact (the trajectory is the same until then): equal
  // counts and bit-equal last separation, impulse and peak force; it ends after the last
  // separation and before the end angle, with a `clear` event; the full pass never comes as near
  // the surface after that angle as the bound allowed. Several speeds, depths and frictions.
  const std::vector<std::vector<std::string>> cases = {
      {}, {"hub.speed_rpm=3000"}, {"surface.depth_fraction=0.01", "surface.friction=0"},
      {"hub.speed_rpm=1200", "surface.depth_fraction=0.03", "surface.friction=0.8"}};
  for (const auto& sets : cases) {
    const std::string name = sets.empty() ? "base" : sets[0];
    std::vector<std::string> early = sets;
    early.push_back("simulation.end_when_clear=true");
    const PassResult a = run(early, 1e-5), b = run(sets, 1e-5);
    ASSERT_FALSE(a.failure) << name;
    ASSERT_FALSE(b.failure) << name;
    EXPECT_EQ(a.summary.impacts, b.summary.impacts) << name;
    EXPECT_EQ(a.summary.contact_episodes, b.summary.contact_episodes) << name;
    EXPECT_EQ(a.summary.last_separation_deg, b.summary.last_separation_deg) << name;
    EXPECT_EQ(a.summary.ledger[LedgerTerm::normal_impulse], b.summary.ledger[LedgerTerm::normal_impulse]) << name;
    EXPECT_EQ(a.summary.peak_normal_force_n, b.summary.peak_normal_force_n) << name;
    ASSERT_TRUE(std::isfinite(a.summary.ended_clear_deg)) << name;
    EXPECT_GT(a.summary.ended_clear_deg, a.summary.last_separation_deg) << name;
    EXPECT_LT(a.summary.ended_clear_deg, 90.0) << name;
    EXPECT_TRUE(std::isnan(b.summary.ended_clear_deg)) << name;
    EXPECT_LT(a.summary.steps, b.summary.steps) << name;
    int clear_events = 0;
    for (const PassEvent& e : a.events) clear_events += e.kind == EventKind::clear;
    EXPECT_EQ(clear_events, 1) << name;
    for (const HistoryRow& row : b.history)
      if (row.theta * 180.0 / M_PI > a.summary.ended_clear_deg) EXPECT_LT(row.gap, 0.0) << name;
  }
}

TEST(EndWhenClear, IsRefusedWithRevolutions) {
  EXPECT_THROW(load_config_string("", {"simulation.end_when_clear=true", "simulation.revolutions=3"}), ConfigError);
}
