// The impact law (docs/model.md §5): Ċ⁺ = −eĊ⁻, the energy lost relative to the moving constraint, the
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
  EXPECT_NEAR(restitution(law, 1.0319, 5.0), 0.4971, 5e-5);  // docs/model.md §5 worked value
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
  // q̇⁻ = 0 at the straight-beam impact: T2 jumps from 0 to ½P²a (docs/model.md §5).
  StraightBeamImpact s;
  const ImpactResult r = s.apply(ImpactLaw{});
  const double t2 = evaluate_energy(s.model, s.q, s.qd, s.ws).t2;
  TipKinematics& tip = s.tip;
  EXPECT_NEAR(t2, 0.5 * r.impulse * r.impulse * r.effective_inverse_mass, 1e-12 * t2);
  EXPECT_NEAR(tip.gap, 0.0, 1e-15);
}

TEST(Impact, PlasticStraightBeamImpactStopsTheTip) {
  // docs/model.md §10: at q = 0 the tip can only move along the beam's local y axis, so e = 0 leaves
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

namespace {
// An approaching tip at a deformed state (so ∇C and ∂V_t/∂q̇ are not parallel) with a chosen slip.
struct FrictionalImpact {
  ForeshorteningBeam model;
  Plane plane;
  ForeshorteningWorkspace ws;
  TipKinematics tip;
  Eigen::VectorXd q, qd;
  double t;
  double a_nn = 0, a_nt = 0, a_tt = 0;  // the inverse-mass couplings, computed here independently
  FrictionalImpact(int n, double rpm, unsigned seed, double slip_boost)
      : model(make_beam([&] {
          BeamParameters p;
          p.modes = n;
          p.speed_rpm = rpm;
          return p;
        }())),
        plane(plane_at_depth(model, 0.02)),
        ws(n),
        tip(n) {
    rotbeam::testing::random_state(model, seed, 0.015, 1.0, q, qd);
    t = model.time_at(-10.0 * M_PI / 180.0);
    tip_kinematics(model, plane, t, q, qd, tip);
    // Change the slip speed along the tangential direction without changing Ċ: add a multiple of
    // the part of ∂V_t/∂q̇ orthogonal (in M⁻¹) to ∇C.
    evaluate_mass(model, q, ws);
    const Eigen::LLT<Eigen::MatrixXd> llt(ws.mass);
    const Eigen::VectorXd mn = llt.solve(tip.grad_gap), mt = llt.solve(tip.grad_tangent);
    a_nn = tip.grad_gap.dot(mn), a_nt = tip.grad_gap.dot(mt), a_tt = tip.grad_tangent.dot(mt);
    const Eigen::VectorXd dir = mt - (a_nt / a_nn) * mn;  // ∇Cᵀ dir = 0
    qd += slip_boost * dir / tip.grad_tangent.dot(dir);
    tip_kinematics(model, plane, t, q, qd, tip);
  }
  double energy(const Eigen::VectorXd& v) {
    const EnergyTerms e = evaluate_energy(model, q, v, ws);
    return e.kinetic + e.potential;
  }
};
}  // namespace

TEST(CoulombImpact, SlidingThroughoutFollowsTheClosedForm) {
  // Slip fast enough never to stop: dP_t = −μ s dp all through, so Ċ⁺ = −eĊ⁻ exactly (a constant
  // slope in p), p = (1 + e)Ċ⁻/α with α = a_nn + μ s a_nt, P_t = −μ s p, V_t⁺ = V_t⁻ − (a_nt + μ s a_tt) p.
  for (double mu : {0.2, 0.8})
    for (double e : {0.0, 0.5, 0.9}) {
      FrictionalImpact c(5, 1000, 7, 5.0);
      ASSERT_GT(c.tip.gap_rate, 0.0);
      const double vn = c.tip.gap_rate, vt = c.tip.slip_speed, s = vt > 0 ? 1.0 : -1.0;
      ImpactLaw law;
      law.model = RestitutionModel::constant;
      law.constant = e;
      law.plastic_below_m_s = 0.0;
      law.friction = ImpactFriction::coulomb;
      const ImpactResult r = apply_impact(c.model, c.plane, law, c.t, c.q, c.qd, c.ws, c.tip, mu);
      const double alpha = c.a_nn + mu * s * c.a_nt, p = (1 + e) * vn / alpha;
      ASSERT_FALSE(r.jammed);
      EXPECT_NEAR(r.vx_after, -e * vn, 1e-11 * vn) << "μ " << mu << " e " << e;
      EXPECT_NEAR(-r.impulse, p, 1e-11 * p);
      EXPECT_NEAR(r.tangential_impulse, -mu * s * p, 1e-11 * p);
      EXPECT_NEAR(r.vy_after, vt - (c.a_nt + mu * s * c.a_tt) * p, 1e-10 * std::abs(vt));
      EXPECT_EQ(r.vy_after > 0, vt > 0) << "still sliding the same way";
    }
}

TEST(CoulombImpact, StickingFromTheStartFollowsTheClosedForm) {
  // No slip at the touch and |a_nt| ≤ μ a_tt: the tip sticks throughout, P_t = (a_nt/a_tt) p, V_t⁺ = 0,
  // and the normal slope is a_nn − a_nt²/a_tt, so Ċ⁺ = −eĊ⁻ again.
  FrictionalImpact probe(5, 1000, 9, 0.0);
  const double vt0 = probe.tip.slip_speed;
  FrictionalImpact c(5, 1000, 9, -vt0);  // cancel the slip
  ASSERT_NEAR(c.tip.slip_speed, 0.0, 1e-12);
  const double mu = 2.0 * std::abs(c.a_nt) / c.a_tt + 0.1, e = 0.6, vn = c.tip.gap_rate;
  ImpactLaw law;
  law.model = RestitutionModel::constant;
  law.constant = e;
  law.plastic_below_m_s = 0.0;
  law.friction = ImpactFriction::coulomb;
  const ImpactResult r = apply_impact(c.model, c.plane, law, c.t, c.q, c.qd, c.ws, c.tip, mu);
  const double p = (1 + e) * vn / (c.a_nn - c.a_nt * c.a_nt / c.a_tt);
  EXPECT_NEAR(-r.impulse, p, 1e-10 * p);
  EXPECT_NEAR(r.tangential_impulse, c.a_nt / c.a_tt * p, 1e-10 * p);
  EXPECT_NEAR(r.vy_after, 0.0, 1e-10 * vn);
  EXPECT_NEAR(r.vx_after, -e * vn, 1e-10 * vn);
}

TEST(CoulombImpact, NoImpactCreatesEnergyAndFrictionStaysInsideTheCone) {
  // Over random states, slips (sliding, stopping, reversing) and laws: the impulse's work on the tip
  // is ≤ 0 and equals the change of E = T + U less the hub's work; |P_t| ≤ μ|P|; the hub's work by
  // the angular-momentum route (ω(ΔH_z − (R × P)_z)) closes the ledger to 1e-10 of the energies.
  int checked = 0;
  for (unsigned seed = 1; seed <= 12; ++seed)
    for (double boost : {-3.0, -0.3, 0.0, 0.3, 3.0})
      for (double mu : {0.1, 0.5, 2.0}) {
        FrictionalImpact c(5, 550 + 200 * seed, seed, boost);
        if (!(c.tip.gap_rate > 0.0)) continue;
        ImpactLaw law;
        law.friction = ImpactFriction::coulomb;
        law.plastic_below_m_s = 0.0;
        const Eigen::VectorXd before = c.qd;
        const double e_before = c.energy(before);
        const double h_before = evaluate_energy(c.model, c.q, before, c.ws).angular_momentum;
        const ImpactResult r = apply_impact(c.model, c.plane, law, c.t, c.q, c.qd, c.ws, c.tip, mu);
        if (r.jammed) continue;
        ++checked;
        const double e_after = c.energy(c.qd);
        const double h_after = evaluate_energy(c.model, c.q, c.qd, c.ws).angular_momentum;
        const Eigen::Vector2d at = tip_position(c.model, c.t, c.q);
        const double hub = c.model.omega * (h_after - h_before - (at.x() * r.impulse_y - at.y() * r.impulse_x));
        const double scale = std::abs(e_before) + std::abs(e_after);
        EXPECT_LE(r.contact_work, 1e-12 * scale) << "seed " << seed << " boost " << boost << " μ " << mu;
        EXPECT_LE(std::abs(r.tangential_impulse), mu * std::abs(r.impulse) * (1 + 1e-12));
        EXPECT_NEAR(e_after - e_before, hub + r.contact_work, 1e-10 * scale);
        EXPECT_LE(r.vx_after, 1e-12 * r.vx_before) << "the tip does not keep approaching";
      }
  EXPECT_GT(checked, 100);
}

TEST(ImpactLedger, HubWorkAtAFrictionlessImpactByTwoRoutes) {
  // The hub's impulsive work ω(ΔH_z − (R × P)_z) equals ΔE − P·(V⁻ + V⁺)/2 (the inertial energy less
  // the impulse's work), and that work is −½(1 − e²)(Ċ⁻)²/a.
  for (double e : {0.0, 0.4, 1.0}) {
    FrictionalImpact c(5, 2000, 3, 0.0);
    ImpactLaw law;
    law.model = RestitutionModel::constant;
    law.constant = e;
    law.plastic_below_m_s = 0.0;
    const Eigen::VectorXd before = c.qd;
    const double vn = c.tip.gap_rate;
    const double e_before = c.energy(before), h_before = evaluate_energy(c.model, c.q, before, c.ws).angular_momentum;
    const ImpactResult r = apply_impact(c.model, c.plane, law, c.t, c.q, c.qd, c.ws, c.tip);
    const double e_after = c.energy(c.qd), h_after = evaluate_energy(c.model, c.q, c.qd, c.ws).angular_momentum;
    const Eigen::Vector2d at = tip_position(c.model, c.t, c.q);
    const double hub = c.model.omega * (h_after - h_before - (at.x() * r.impulse_y - at.y() * r.impulse_x));
    EXPECT_NEAR(r.contact_work, -0.5 * (1 - e * e) * vn * vn / c.a_nn, 1e-12 * vn * vn / c.a_nn);
    EXPECT_NEAR(e_after - e_before, hub + r.contact_work, 1e-10 * (std::abs(e_before) + std::abs(e_after)));
  }
}
