// Every term of the equations of motion (docs/model.md §3) against numerical differentiation of the
// Lagrangian evaluated by direct quadrature (tests/reference_beam.*).
//
// For L(q, q̇) the Lagrange equations read M q̈ + Ψ = 0 with
//   M = ∂²L/∂q̇²,  Ψ = (∂p/∂q) q̇ − ∂L/∂q,  p = ∂L/∂q̇.
// L is a polynomial of degree ≤ 4 in (q, q̇), so a central difference is exact for the quadratic
// dependence on q̇, and a Richardson-extrapolated central difference (steps δ and δ/2) is exact
// for quartics: the only errors left are round-off and the reference quadrature (~1e-13).
// Splitting L into T2, T1, T0 and −U isolates each term:
//   T2 → D(q,q̇)q̇ (and M),  T1 → 2ωG(q)q̇,  T0 → K_ω(q)q,  −U → K_b(q)q.
#include "lagrangian_differences.hpp"
#include "reference_beam.hpp"
#include "rotbeam/dynamics.hpp"

#include <functional>
#include <gtest/gtest.h>
#include <ostream>

using namespace rotbeam;
using rotbeam::testing::ReferenceBeam;
using rotbeam::testing::Scalar2;
using rotbeam::testing::mass_from_lagrangian;
using rotbeam::testing::psi_from_lagrangian;

namespace {

struct Case {
  int n;
  double rpm;
  double tip_m;
  unsigned seed;
};

// The cases by their values in the test names (printed as bytes, padding included, they changed
// from one build to the next).
void PrintTo(const Case& c, std::ostream* os) {
  *os << c.n << "modes_" << c.rpm << "rpm_tip" << c.tip_m << "m_seed" << c.seed;
}

class LagrangianCheck : public ::testing::TestWithParam<Case> {};

TEST_P(LagrangianCheck, MassMatrixAndEveryForceTermMatchTheLagrangian) {
  const Case c = GetParam();
  BeamParameters pp;
  pp.modes = c.n;
  pp.speed_rpm = c.rpm;
  const ForeshorteningBeam model = make_beam(pp);
  const ReferenceBeam ref(model, c.n <= 5 ? 16 : 24);
  Eigen::VectorXd q, v;
  rotbeam::testing::random_state(model, c.seed, c.tip_m, 2.0, q, v);

  ForeshorteningWorkspace ws(c.n);
  evaluate_dynamics(model, q, v, ws);

  // M = ∂²T2/∂q̇² (T1 is linear and T0, U independent of q̇).
  const double dv = 0.5;
  const Eigen::MatrixXd m_fd = mass_from_lagrangian([&](auto& a, auto& b) { return ref.lagrangian(a, b); }, q, v, dv);
  // Tolerance: 1e-9 of m. The second difference of L (≈ T0 ~ 1e-3…5e-2 J) loses ~1e-16·L/dv²
  // ≈ 1e-16 kg, far below; the reference quadrature is good to ~1e-13 relative.
  EXPECT_LE((ws.mass - m_fd).cwiseAbs().maxCoeff(), 1e-9 * model.mass) << "M(q)";

  const double dq = 2e-4;  // the extrapolated difference is exact for quartics; this only sets round-off
  const Scalar2 t2 = [&](auto& a, auto& b) { return ref.t2(a, b); };
  const Scalar2 t1 = [&](auto& a, auto& b) { return ref.t1(a, b); };
  const Scalar2 t0 = [&](auto& a, auto&) { return ref.t0(a); };
  const Scalar2 u = [&](auto& a, auto&) { return -ref.potential(a); };
  const Eigen::VectorXd fore = psi_from_lagrangian(t2, q, v, dq, dv);
  const Eigen::VectorXd gyro = psi_from_lagrangian(t1, q, v, dq, dv);
  const Eigen::VectorXd centri = psi_from_lagrangian(t0, q, v, dq, dv);
  const Eigen::VectorXd bend = psi_from_lagrangian(u, q, v, dq, dv);
  // Each term is compared relative to the size of the total Ψ (and of the term itself), at 1e-7:
  // round-off of the differences is ~1e-16·L/dq ≈ 1e-13…1e-11 N against Ψ ≈ 1e-3…10 N.
  const double scale = std::max({ws.psi.cwiseAbs().maxCoeff(), ws.bending.cwiseAbs().maxCoeff(), 1e-12});
  auto check = [&](const Eigen::VectorXd& got, const Eigen::VectorXd& want, const char* what) {
    const double err = (got - want).cwiseAbs().maxCoeff();
    const double size = std::max(want.cwiseAbs().maxCoeff(), 1e-3 * scale);
    EXPECT_LE(err, 1e-7 * size) << what << "\n got  " << got.transpose() << "\n want " << want.transpose();
  };
  check(ws.foreshortening, fore, "D(q,q̇)q̇");
  check(ws.gyroscopic, gyro, "2ωG(q)q̇");
  check(ws.centrifugal, centri, "K_ω(q)q");
  check(ws.bending, bend, "K_b(q)q");
  check(ws.psi, fore + gyro + centri + bend, "Ψ");
}

INSTANTIATE_TEST_SUITE_P(
    RandomStates, LagrangianCheck,
    ::testing::Values(Case{2, 550, 0.01, 1}, Case{2, 3000, 0.03, 2}, Case{5, 550, 0.005, 3}, Case{5, 550, 0.03, 4},
                      Case{5, 3000, 0.02, 5}, Case{10, 550, 0.03, 6}, Case{10, 3000, 0.01, 7}));

}  // namespace

// The elastica (docs/model.md §11) by the same route: its T and U from ReferenceElastica (positions
// integrated afresh at every node from the modal basis), differentiated numerically. Its L is not
// a polynomial, so the extrapolated difference leaves O(δ⁴) ≈ (2e-5/0.06)⁴ ≈ 1e-14 relative;
// round-off ~1e-16·T/δ. Each rotation term is isolated by the model's switches:
//   Ψ(none) ↔ T2 − U,  Ψ(centrifugal) − Ψ(none) ↔ T0,  Ψ(coriolis) − Ψ(none) ↔ T1.
namespace {

struct ElasticaCase {
  int n;
  double rpm;
  double tip_m;
  unsigned seed;
};

void PrintTo(const ElasticaCase& c, std::ostream* os) {
  *os << c.n << "modes_" << c.rpm << "rpm_tip" << c.tip_m << "m_seed" << c.seed;
}

class ElasticaLagrangianCheck : public ::testing::TestWithParam<ElasticaCase> {};

TEST_P(ElasticaLagrangianCheck, MassMatrixAndEveryForceTermMatchTheLagrangian) {
  const ElasticaCase c = GetParam();
  BeamParameters pp;
  pp.modes = c.n;
  pp.speed_rpm = c.rpm;
  Eigen::VectorXd q, v;
  rotbeam::testing::random_state(make_beam(pp), c.seed, c.tip_m, 2.0, q, v);
  auto model = [&](bool centrifugal, bool coriolis) {
    BeamParameters p = pp;
    p.centrifugal = centrifugal;
    p.coriolis = coriolis;
    return make_elastica(p);
  };
  const ElasticaBeam full = model(true, true), none = model(false, false), cent = model(true, false),
                     cor = model(false, true);
  const int panels = c.n + 6;
  const rotbeam::testing::ReferenceElastica ref_full(full, panels), ref_none(none, panels), ref_cent(cent, panels),
      ref_cor(cor, panels);
  auto psi = [&](const ElasticaBeam& m) {
    auto ws = m.make_workspace();
    m.evaluate_dynamics(q, v, *ws);
    return std::make_pair(Eigen::VectorXd(ws->psi), Eigen::MatrixXd(ws->mass));
  };
  const auto [psi_full, mass] = psi(full);
  const Eigen::VectorXd psi_none = psi(none).first, psi_cent = psi(cent).first, psi_cor = psi(cor).first;

  const double dv = 0.5;
  const Eigen::MatrixXd m_fd =
      mass_from_lagrangian([&](auto& a, auto& b) { return ref_full.lagrangian(a, b); }, q, v, dv);
  EXPECT_LE((mass - m_fd).cwiseAbs().maxCoeff(), 1e-9 * full.mass) << "M(q)";

  const double dq = 2e-5;
  const Scalar2 inertia = [&](auto& a, auto& b) { return ref_none.t2(a, b) - ref_none.potential(a); };
  const Scalar2 t0 = [&](auto& a, auto&) { return ref_cent.t0(a); };
  const Scalar2 t1 = [&](auto& a, auto& b) { return ref_cor.t1(a, b); };
  const Scalar2 lag = [&](auto& a, auto& b) { return ref_full.lagrangian(a, b); };
  const Eigen::VectorXd want_none = psi_from_lagrangian(inertia, q, v, dq, dv);
  const Eigen::VectorXd want_cent = psi_from_lagrangian(t0, q, v, dq, dv);
  const Eigen::VectorXd want_cor = psi_from_lagrangian(t1, q, v, dq, dv);
  const Eigen::VectorXd want_full = psi_from_lagrangian(lag, q, v, dq, dv);
  const double scale = std::max(psi_full.cwiseAbs().maxCoeff(), psi_none.cwiseAbs().maxCoeff());
  auto check = [&](const Eigen::VectorXd& got, const Eigen::VectorXd& want, const char* what) {
    const double err = (got - want).cwiseAbs().maxCoeff();
    const double size = std::max(want.cwiseAbs().maxCoeff(), 1e-3 * scale);
    EXPECT_LE(err, 1e-7 * size) << what << "\n got  " << got.transpose() << "\n want " << want.transpose();
  };
  check(psi_none, want_none, "T2 and U");
  check(psi_cent - psi_none, want_cent, "T0 (centrifugal)");
  check(psi_cor - psi_none, want_cor, "T1 (Coriolis)");
  check(psi_full, want_full, "Ψ");
  // The energies themselves against the reference (1e-12 relative: two quadratures).
  auto ws = full.make_workspace();
  const EnergyTerms e = full.energy(q, v, *ws);
  EXPECT_NEAR(e.t0, ref_full.t0(q), 1e-12 * std::abs(e.t0));
  EXPECT_NEAR(e.t1, ref_full.t1(q, v), 1e-12 * std::abs(e.t0));
  EXPECT_NEAR(e.t2, ref_full.t2(q, v), 1e-12 * std::abs(e.t2));
  EXPECT_NEAR(e.potential, ref_full.potential(q), 1e-12 * std::abs(e.potential));
  EXPECT_LE((full.tip_position(q) - ref_full.tip(q)).norm(), 1e-14 * full.length);
}

INSTANTIATE_TEST_SUITE_P(
    RandomStates, ElasticaLagrangianCheck,
    ::testing::Values(ElasticaCase{2, 550, 0.01, 1}, ElasticaCase{3, 3000, 0.03, 2}, ElasticaCase{5, 550, 0.03, 4},
                      ElasticaCase{5, 3000, 0.04, 5}, ElasticaCase{8, 3000, 0.02, 7}, ElasticaCase{10, 550, 0.03, 6}));

}  // namespace
