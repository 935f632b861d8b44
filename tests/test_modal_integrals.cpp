// The precomputed ξ-integrals (docs/model.md §3): convergence of the composite rule and spot checks
// against adaptive quadrature.
#include "rotbeam/modal_integrals.hpp"

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <gtest/gtest.h>

using namespace rotbeam;

namespace {
double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}
double max_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}
}  // namespace

class IntegralConvergence : public ::testing::TestWithParam<int> {};

TEST_P(IntegralConvergence, DoublingThePanelsChangesNothingBeyond1e13) {
  // The default rule against one with twice the panels: the largest change of any entry, relative
  // to the largest entry of its array, must be ≤ 1e-13 (round-off of sums of O(10²…10⁵) terms).
  const int n = GetParam();
  const int panels = default_quadrature_panels(n);
  const ModalIntegrals a = compute_modal_integrals(n, panels, 20);
  const ModalIntegrals b = compute_modal_integrals(n, 2 * panels, 20);
  const ModalIntegrals coarse = compute_modal_integrals(n, std::max(1, panels / 3), 20);
  struct Item { const char* name; const std::vector<double>& x; const std::vector<double>& y; const std::vector<double>& c; };
  for (const Item& it : {Item{"isp_isp", a.isp_isp, b.isp_isp, coarse.isp_isp}, Item{"p_p", a.p_p, b.p_p, coarse.p_p},
                         Item{"isp_s", a.isp_s, b.isp_s, coarse.isp_s}}) {
    const double rel = max_diff(it.x, it.y) / max_abs(it.y);
    const double rel_coarse = max_diff(it.c, it.y) / max_abs(it.y);
    std::printf("n = %2d  %-8s default vs doubled: %.2e   (a third of the panels: %.2e)\n", n, it.name, rel, rel_coarse);
    EXPECT_LE(rel, 1e-13) << it.name;
  }
  EXPECT_LE((a.isp_tip - b.isp_tip).cwiseAbs().maxCoeff() / b.isp_tip.cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LE((a.isp_xi - b.isp_xi).cwiseAbs().maxCoeff() / b.isp_xi.cwiseAbs().maxCoeff(), 1e-13);
}

INSTANTIATE_TEST_SUITE_P(Modes, IntegralConvergence, ::testing::Values(2, 5, 10, 30));

TEST(ModalIntegrals, SpotChecksAgainstAdaptiveQuadrature) {
  // Independent route: ISP by nested adaptive Gauss–Kronrod. Tolerance 1e-11 relative to the
  // largest entry (the nested adaptive rule is itself good to ~1e-12 here).
  const int n = 5;
  auto mi = modal_integrals(n);
  const ModalBasis& b = mi->basis;
  using GK = boost::math::quadrature::gauss_kronrod<double, 31>;
  auto isp = [&](int i, int k, double xi) {
    if (xi <= 0) return 0.0;
    return GK::integrate([&](double s) { return b.shape(i, s, 1) * b.shape(k, s, 1); }, 0.0, xi, 10, 1e-14);
  };
  const double scale_isp = max_abs(mi->isp_isp);
  const int cases[][4] = {{0, 0, 0, 0}, {0, 1, 2, 3}, {4, 4, 4, 4}, {1, 3, 0, 4}, {2, 2, 1, 1}};
  for (const auto& c : cases) {
    const double ref = GK::integrate([&](double x) { return isp(c[0], c[1], x) * isp(c[2], c[3], x); }, 0.0, 1.0, 10, 1e-13);
    const double got = mi->isp_isp[(c[0] * n + c[1]) * mi->pairs + mi->pair(c[2], c[3])];
    EXPECT_NEAR(got, ref, 1e-11 * scale_isp) << c[0] << c[1] << c[2] << c[3];
  }
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      EXPECT_NEAR(mi->isp_tip(i, k), isp(i, k, 1.0), 1e-11 * mi->isp_tip.cwiseAbs().maxCoeff());
      const double ref_xi = GK::integrate([&](double x) { return x * isp(i, k, x); }, 0.0, 1.0, 10, 1e-13);
      EXPECT_NEAR(mi->isp_xi(i, k), ref_xi, 1e-11 * mi->isp_xi.cwiseAbs().maxCoeff());
      for (int j = 0; j < n; ++j) {
        const double ref_s = GK::integrate([&](double x) { return isp(i, k, x) * b.shape(j, x); }, 0.0, 1.0, 10, 1e-13);
        EXPECT_NEAR(mi->isp_s[(i * n + k) * n + j], ref_s, 1e-11 * max_abs(mi->isp_s));
      }
    }
  const double ref_s_mean = GK::integrate([&](double x) { return b.shape(0, x); }, 0.0, 1.0, 10, 1e-14);
  EXPECT_NEAR(mi->s_mean[0], ref_s_mean, 1e-13);
  // P-tensor entry.
  auto p = [&](int i, int j, double x) { return b.shape(i, x, 2) * b.shape(j, x, 1) + b.shape(i, x, 1) * b.shape(j, x, 2); };
  const double ref_p = GK::integrate([&](double x) { return p(0, 1, x) * p(2, 4, x); }, 0.0, 1.0, 10, 1e-13);
  EXPECT_NEAR(mi->p_p[mi->pair(0, 1) * mi->pairs + mi->pair(2, 4)], ref_p, 1e-11 * max_abs(mi->p_p));
}

TEST(ModalIntegrals, CachedPerModeCount) {
  EXPECT_EQ(modal_integrals(5).get(), modal_integrals(5).get());
  EXPECT_NE(modal_integrals(5).get(), modal_integrals(6).get());
}

TEST(ModalIntegrals, TheThesisSixteenPointRuleIsInexact) {
  // Evidence for docs/deviations.md: one 16-point Gauss–Legendre rule on [0, 1] (as Appendix B's
  // sysMatrices.m) against the converged default, on the integrals of the nonlinear terms.
  // Measured (largest entry error over the largest entry): ∫P⊗P 5e-2 at n = 5 and 0.18 at n = 10.
  for (int n : {5, 10}) {
    const ModalIntegrals exact = compute_modal_integrals(n, default_quadrature_panels(n), 20);
    const ModalIntegrals g16 = compute_modal_integrals(n, 1, 16);
    const double rel_pp = max_diff(exact.p_p, g16.p_p) / max_abs(exact.p_p);
    const double rel_isp = max_diff(exact.isp_isp, g16.isp_isp) / max_abs(exact.isp_isp);
    std::printf("n = %2d: 16-point rule error, ∫P⊗P %.2e, ∫ISP⊗ISP %.2e\n", n, rel_pp, rel_isp);
    EXPECT_GT(rel_pp, n == 5 ? 1e-6 : 1e-2);
  }
}
