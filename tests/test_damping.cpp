// Modal damping (docs/model.md §11): C = M0 Φ diag(2ζ_iΩ_i) Φᵀ M0 on the linear modes at the hub speed.
// Checked against the closed-form decay of a damped linear oscillator at small amplitude, with the
// modes computed here by an independent route (the generalised eigenproblem of K and M(0)); the
// damping work against the energy ledger in free flight and through contact, with both schemes.
#include "rotbeam/case.hpp"
#include "rotbeam/stepper.hpp"
#include "rotbeam/dynamics.hpp"
#include "rotbeam/plane.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include "test_support.hpp"

#include <gtest/gtest.h>

using namespace rotbeam;

namespace {

// The mass-normalised linear modes of `beam` by the generalised eigenproblem K φ = Ω² M(0) φ.
struct LinearModes {
  Eigen::VectorXd omega;  // Ω_i [rad/s], ascending
  Eigen::MatrixXd phi;    // columns: φ_i with φ_iᵀ M(0) φ_i = 1
};

LinearModes linear_modes(const ForeshorteningBeam& beam) {
  ForeshorteningWorkspace ws(beam.n);
  evaluate_mass(beam, Eigen::VectorXd::Zero(beam.n), ws);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(linear_stiffness(beam), ws.mass);
  return {solver.eigenvalues().cwiseSqrt(), solver.eigenvectors()};
}

// Free flight from (q0, q̇0) to t_end with the adaptive stepper and no surface within reach; returns
// the end state and the damping work.
struct FreeRun {
  Eigen::VectorXd q, qd;
  double damping_work = 0;
};

FreeRun free_flight(const ForeshorteningBeam& beam, const Eigen::VectorXd& q0, const Eigen::VectorXd& qd0,
                    double t_end) {
  const Plane far(100.0);
  PassOptions opt;
  opt.rtol = 1e-12;
  opt.atol = 1e-18;  // q ~ 1e-7 m: the absolute tolerance must not dominate
  const System system{beam, far, default_contact_law()};
  const auto stepper = make_adaptive_stepper(system, opt);
  FilamentState s(beam.n);
  s.q = q0;
  s.qd = qd0;
  stepper->begin_free(s, FreeStart::pass_start);
  FreeRun r;
  while (s.t < t_end) {
    const StepOutcome o = stepper->step(s, t_end);
    EXPECT_EQ(o.status, StepStatus::advanced);
    r.damping_work += o.integrals.integral[LedgerTerm::damping_work];
  }
  r.q = s.q;
  r.qd = s.qd;
  return r;
}

ForeshorteningBeam beam_with(std::vector<double> zeta, double rpm = 550.0) {
  BeamParameters p;
  p.speed_rpm = rpm;
  p.damping_ratio = std::move(zeta);
  return make_beam(p);
}

}  // namespace

TEST(Damping, MatrixIsDiagonalOnTheMassNormalisedModes) {
  // Φᵀ C Φ = diag(2ζ_iΩ_i) with Φ from the independent eigenproblem (1e-9 relative: two eigen
  // solvers on the same 5×5 matrices).
  const std::vector<double> zeta = {0.01, 0.02, 0.03, 0.04, 0.05};
  const ForeshorteningBeam beam = beam_with(zeta, 1000.0);
  const LinearModes m = linear_modes(beam);
  const Eigen::MatrixXd d = m.phi.transpose() * beam.damping * m.phi;
  for (int i = 0; i < beam.n; ++i)
    for (int j = 0; j < beam.n; ++j) {
      const double expected = i == j ? 2.0 * zeta[i] * m.omega[i] : 0.0;
      EXPECT_NEAR(d(i, j), expected, 1e-9 * 2.0 * zeta[i] * m.omega[i]) << i << "," << j;
    }
  EXPECT_FALSE(beam_with({}).damped());
  EXPECT_FALSE(beam_with({0.0}).damped());
  EXPECT_THROW(beam_with({0.01, 0.02}), std::invalid_argument);
  EXPECT_THROW(beam_with({-0.01}), std::invalid_argument);
}

TEST(Damping, SmallVibrationDecaysAsTheDampedOscillator) {
  // One mode started alone at amplitude ε = 1e-8 m (1.6e-7 L): at linear order m q̈ + C q̇ + K q = 0,
  // so its modal coordinate follows a(t) = ε e^{−ζΩt}(cos Ω_d t + ζ/√(1−ζ²) sin Ω_d t) and the others
  // stay at rest (the quadratic terms leak ~1e-6 ε at this amplitude, growing with ε). Checked after 2–20 periods for modes 1 and 3 with different ratios, at 550 and
  // 2000 rpm, to 1e-5 ε (the quadratic terms are ~ε/L ~ 1e-6 of the linear ones). A damping rate off
  // by a factor, a sign, or the modes' transform (C diagonal in q instead of in the modes) fails.
  const std::vector<double> zeta = {0.02, 0.01, 0.05, 0.03, 0.04};
  for (double rpm : {550.0, 2000.0})
    for (int k : {0, 2}) {
      const ForeshorteningBeam beam = beam_with(zeta, rpm);
      const LinearModes m = linear_modes(beam);
      const double eps = 1e-8;
      const double omega = m.omega[k], z = zeta[k], wd = omega * std::sqrt(1.0 - z * z);
      const double t_end = 4.0 * M_PI / omega * (k == 0 ? 1.0 : 10.0);  // 2 or 20 periods
      // Mass-normalised modal coordinates a = Φᵀ M(0) q, M(0) = m·1.
      const Eigen::VectorXd q0 = eps * m.phi.col(k).normalized();
      const double a0 = (m.phi.transpose() * q0 * beam.mass)[k];
      const FreeRun r = free_flight(beam, q0, Eigen::VectorXd::Zero(beam.n), t_end);
      const Eigen::VectorXd a = beam.mass * m.phi.transpose() * r.q;
      const double expected = a0 * std::exp(-z * omega * t_end) * (std::cos(wd * t_end) + z / std::sqrt(1 - z * z) * std::sin(wd * t_end));
      EXPECT_NEAR(a[k], expected, 1e-5 * std::abs(a0)) << rpm << " rpm, mode " << k + 1;
      for (int j = 0; j < beam.n; ++j)
        if (j != k) EXPECT_LE(std::abs(a[j]), 1e-5 * std::abs(a0)) << rpm << " rpm, mode " << k + 1 << " leaks into " << j + 1;
      EXPECT_LT(r.damping_work, 0.0);
    }
}

TEST(Damping, WorkIsTheLossOfTheLinearOscillatorsEnergy) {
  // At small amplitude the damping work over a free flight equals the loss of ½ȧ² + ½Ω²a² summed over
  // the modes (mass-normalised), ζ = 0.05 on every mode, two modes excited (1e-6 relative).
  const ForeshorteningBeam beam = beam_with({0.05}, 1000.0);
  const LinearModes m = linear_modes(beam);
  Eigen::VectorXd qd0 = 1e-4 * (m.phi.col(0) + 0.5 * m.phi.col(1));
  const FreeRun r = free_flight(beam, Eigen::VectorXd::Zero(beam.n), qd0, 0.02);
  auto energy = [&](const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
    const Eigen::VectorXd a = beam.mass * m.phi.transpose() * q, ad = beam.mass * m.phi.transpose() * qd;
    return 0.5 * ad.squaredNorm() + 0.5 * (m.omega.array().square() * a.array().square()).sum();
  };
  const double loss = energy(r.q, r.qd) - energy(Eigen::VectorXd::Zero(beam.n), qd0);
  EXPECT_NEAR(r.damping_work, loss, 1e-6 * std::abs(loss));
}

TEST(Damping, LedgerClosesThroughContactWithBothSchemes) {
  // hub work + friction + damping + impact losses = ΔE over whole passes with impacts and contact,
  // on cases beyond the base case: adaptive within 5e-8 of the largest term (the tolerance's level,
  // as undamped), the thesis scheme within 5e-3 (its trapezoidal contact integrals, as undamped).
  // The Jacobi audit closes too, with the damping work in it.
  const std::vector<std::vector<std::string>> cases = {
      {"beam.damping_ratio=0.02"},
      {"beam.damping_ratio=[0.01,0.02,0.03,0.04,0.05]", "hub.speed_rpm=1000", "surface.friction=0.1"},
      {"beam.damping_ratio=0.05", "hub.speed_rpm=2000", "surface.depth_fraction=0.04", "impact.restitution=0.5"},
      {"beam.damping_ratio=0.03", "initial.modal_velocity=[1,0,0,0,0]", "simulation.end_angle_deg=120"},
  };
  for (const auto& sets : cases)
    for (const char* scheme : {"adaptive", "thesis"}) {
      std::vector<std::string> all = sets;
      all.push_back(std::string("simulation.scheme=") + scheme);
      all.push_back("output.interval_s=1e30");
      const PassResult r = run_case(build_case(load_config_string("", all)));
      ASSERT_FALSE(r.failure) << sets[0];
      const PassSummary& s = r.summary;
      EXPECT_LT(s.ledger[LedgerTerm::damping_work], 0.0);
      const double scale = std::max({std::abs(s.ledger[LedgerTerm::hub_work]), std::abs(s.ledger[LedgerTerm::friction_work]), std::abs(s.ledger[LedgerTerm::impact_loss]),
                                     std::abs(s.ledger[LedgerTerm::damping_work]), std::abs(s.ledger.energy_change_j)});
      const double residual =
          std::abs(s.ledger.energy_change_j - (s.ledger[LedgerTerm::hub_work] + s.ledger[LedgerTerm::friction_work] + s.ledger[LedgerTerm::damping_work] + s.ledger[LedgerTerm::impact_loss])) / scale;
      const bool adaptive = std::string(scheme) == "adaptive";
      EXPECT_LE(residual, adaptive ? 5e-8 : 5e-3) << sets[0] << " " << scheme;
      EXPECT_LE(s.energy_audit_residual, adaptive ? 1e-7 : 5e-3) << sets[0] << " " << scheme;
    }
}

TEST(Damping, ConfigurationNamesTheKey) {
  auto message = [](const std::vector<std::string>& sets) {
    try {
      load_config_string("", sets);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message({"beam.damping_ratio=[0.01,0.02]"}).find("beam.damping_ratio = [0.01, 0.02]: must be one number or beam.modes = 5 values"), std::string::npos);
  EXPECT_NE(message({"beam.damping_ratio=-0.1"}).find("beam.damping_ratio = -0.1: must be in [0, 10]"), std::string::npos);
  EXPECT_NE(message({"beam.damping_ratio=[0.1,-0.1,0,0,0]"}).find("beam.damping_ratio"), std::string::npos);
  EXPECT_NE(message({"beam.damping_ratio=high"}).find("beam.damping_ratio = \"high\": must be a number or an array"), std::string::npos);
  const Config c = load_config_string("", {"beam.damping_ratio=0.02"});
  EXPECT_EQ(c.to_json()["beam"]["damping_ratio"], 0.02);
}
