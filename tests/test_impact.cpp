// The impact law (SPEC §5): Ċ⁺ = −eĊ⁻, the energy lost relative to the moving constraint, the
// change of T2, and the restitution law with its cap, constant and plastic options.
#include "reference_beam.hpp"
#include "rotbeam/energy.hpp"
#include "rotbeam/impact.hpp"
#include "rotbeam/plane.hpp"

#include <gtest/gtest.h>

using namespace rotbeam;

TEST(Restitution, YigitOnTheNormalSpeedWithCapAndOptions) {
  ImpactLaw law;  // Yigit, cap 1, normal speed
  law.plastic_below_m_s = 0.0;
  EXPECT_NEAR(restitution(law, 1.0319, 5.0), 0.501 * std::pow(1.0319, -0.25), 1e-15);
  EXPECT_NEAR(restitution(law, 1.0319, 5.0), 0.4971, 5e-5);  // SPEC §5 worked value
  EXPECT_EQ(restitution(law, 0.01, 5.0), 1.0);             // e > 1 below 0.0634 m/s: capped
  law.cap = 0.8;
  EXPECT_EQ(restitution(law, 0.1, 0.1), 0.8);
  law.speed = RestitutionSpeed::full;  // Appendix B jump.m
  EXPECT_NEAR(restitution(law, 1.0, 16.0), 0.501 / 2.0, 1e-15);
  law.model = RestitutionModel::constant;
  law.constant = 0.3;
  EXPECT_EQ(restitution(law, 2.0, 2.0), 0.3);
  law.plastic_below_m_s = 0.05;
  EXPECT_EQ(restitution(law, 0.049, 2.0), 0.0);
  EXPECT_EQ(restitution(law, 0.051, 2.0), 0.3);
}

namespace {
struct ImpactCase {
  int n;
  double rpm;
  double e;
  unsigned seed;
};
}  // namespace

class ImpactBalance : public ::testing::TestWithParam<ImpactCase> {};

TEST_P(ImpactBalance, ReversesTheNormalVelocityAndLosesTheRightEnergy) {
  const ImpactCase c = GetParam();
  BeamParameters pp;
  pp.modes = c.n;
  pp.speed_rpm = c.rpm;
  const ForeshorteningBeam model = make_beam(pp);
  const Plane plane = plane_at_depth(model, 0.02);
  Eigen::VectorXd q, v;
  rotbeam::testing::random_state(model, c.seed, 0.015, 1.0, q, v);
  ForeshorteningWorkspace ws(c.n);
  TipKinematics tip(c.n);
  // Pick the time when the tip approaches: V_X > 0 near θ ≈ −10°.
  const double t = model.time_at(-10.0 * M_PI / 180.0);
  tip_kinematics(model, plane, t, q, v, tip);
  ASSERT_GT(tip.gap_rate, 0.0);
  ImpactLaw law;
  law.model = RestitutionModel::constant;
  law.constant = c.e;
  law.plastic_below_m_s = 0.0;

  // T_rel = ½ (q̇ − q̇_s)ᵀ M (q̇ − q̇_s), q̇_s = −(∂C/∂t / a) M⁻¹∇C (velocity that keeps Ċ = 0).
  auto t_rel = [&](const Eigen::VectorXd& qd) {
    evaluate_mass(model, q, ws);
    Eigen::LLT<Eigen::MatrixXd> llt(ws.mass);
    TipKinematics k(c.n);
    tip_kinematics(model, plane, t, q, qd, k);
    const Eigen::VectorXd mg = llt.solve(k.grad_gap);
    const double a = k.grad_gap.dot(mg);
    const Eigen::VectorXd rel = qd + (k.gap_time_partial / a) * mg;
    return 0.5 * rel.dot(ws.mass * rel);
  };
  const double t_rel_before = t_rel(v);
  const double vx_before = tip.gap_rate;
  const double t2_before = evaluate_energy(model, q, v, ws).t2;
  Eigen::VectorXd qd = v;
  const ImpactResult r = apply_impact(model, plane, law, t, q, qd, ws, tip);
  // 1e-12 relative: one Cholesky solve and a few dot products of O(1) numbers.
  EXPECT_NEAR(r.vx_after, -c.e * vx_before, 1e-12 * vx_before);
  EXPECT_NEAR(r.vx_before, vx_before, 0.0);
  EXPECT_NEAR(r.restitution, c.e, 0.0);
  const double loss = 0.5 * (1 - c.e * c.e) * vx_before * vx_before / r.effective_inverse_mass;
  EXPECT_NEAR(t_rel_before - t_rel(qd), loss, 1e-10 * t_rel_before + 1e-18) << "T_rel loss";
  EXPECT_NEAR(r.relative_energy_loss, loss, 1e-12 * loss + 1e-18);
  const double t2_after = evaluate_energy(model, q, qd, ws).t2;
  EXPECT_NEAR(t2_after - t2_before, -loss - r.impulse * tip.gap_time_partial, 1e-10 * (t2_before + t2_after))
      << "ΔT2 = −loss − P ∂C/∂t";
  EXPECT_NEAR(r.delta_t2, t2_after - t2_before, 1e-12 * (t2_before + t2_after));
  EXPECT_LT(r.impulse, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Cases, ImpactBalance,
                         ::testing::Values(ImpactCase{2, 550, 0.5, 1}, ImpactCase{5, 550, 0.0, 2},
                                           ImpactCase{5, 3000, 1.0, 3}, ImpactCase{10, 1000, 0.3, 4}));

namespace {
// The impact of the straight beam at the geometric contact angle of the base case.
struct StraightBeamImpact {
  ForeshorteningBeam model = make_beam(BeamParameters{});
  const Plane plane = plane_at_depth(model, 0.02);
  ForeshorteningWorkspace ws{model.n};
  TipKinematics tip{model.n};
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.n);
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(model.n);
  ImpactResult apply(const ImpactLaw& law) {
    return apply_impact(model, plane, law, model.time_at(plane.first_contact_angle(model.tip_radius(), model.theta0)),
                        q, qd, ws, tip);
  }
};
}  // namespace

TEST(Impact, RigidStartImpactSetsTheBeamVibrating) {
  // q̇⁻ = 0 at the straight-beam impact: T2 jumps from 0 to ½P²a (SPEC §5).
  StraightBeamImpact s;
  const ImpactResult r = s.apply(ImpactLaw{});
  const double t2 = evaluate_energy(s.model, s.q, s.qd, s.ws).t2;
  TipKinematics& tip = s.tip;
  EXPECT_NEAR(t2, 0.5 * r.impulse * r.impulse * r.effective_inverse_mass, 1e-12 * t2);
  EXPECT_NEAR(tip.gap, 0.0, 1e-15);
}

TEST(Impact, PlasticStraightBeamImpactStopsTheTip) {
  // SPEC §10: at q = 0 the tip can only move along the beam's local y axis, so e = 0 leaves
  // V_X = V_Y = 0 (to round-off of ω(r_h + L) ≈ 0.7 m/s).
  StraightBeamImpact s;
  ImpactLaw law;
  law.model = RestitutionModel::constant;
  law.constant = 0.0;
  s.apply(law);
  EXPECT_NEAR(s.tip.VX, 0.0, 1e-14);
  EXPECT_NEAR(s.tip.VY, 0.0, 1e-13);
}

TEST(Impact, RecedingTipIsNotAnImpact) {
  const ForeshorteningBeam model = make_beam(BeamParameters{});
  const Plane plane = plane_at_depth(model, 0.02);
  ForeshorteningWorkspace ws(model.n);
  TipKinematics tip(model.n);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(model.n);
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(model.n);
  // Past θ = 0 the straight tip moves away from the surface (V_X < 0).
  EXPECT_THROW(apply_impact(model, plane, ImpactLaw{}, model.time_at(0.1), q, qd, ws, tip), std::domain_error);
}
