// The cantilever basis (docs/model.md §2): roots, boundary conditions, the beam ODE, orthonormality.
#include "rotbeam/modal_basis.hpp"

#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <gtest/gtest.h>

using namespace rotbeam;

TEST(ModalBasis, FirstFiveRootsMatchTheClassicalValues) {
  // Published to 10 decimals; tolerance 1e-9 (the table's last digit).
  const double expected[5] = {1.8751040687, 4.6940911330, 7.8547574382, 10.9955407349, 14.1371683910};
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(cantilever_root(i + 1), expected[i], 1e-9) << "root " << i + 1;
}

TEST(ModalBasis, RootsSolveTheFrequencyEquationUpTo40) {
  // cos r cosh r + 1 = 0 is evaluated as cos r + sech r (same roots, no overflow); a root error δ
  // gives |f| ≈ |sin r| δ, so 1e-14 absolute means δ ≲ 1e-14.
  for (int i = 1; i <= kMaxModes; ++i) {
    const double r = cantilever_root(i);
    EXPECT_NEAR(std::cos(r) + 1.0 / std::cosh(r), 0.0, 1e-14) << "root " << i;
    EXPECT_NEAR(r, (2.0 * i - 1.0) * M_PI / 2.0, 0.31) << "root " << i << " is not the i-th";
    if (i > 1) EXPECT_GT(r, cantilever_root(i - 1) + 2.0);
  }
}

TEST(ModalBasis, ClampedFreeBoundaryConditionsHold) {
  // S(0) = S'(0) = 0 and S''(1) = S'''(1) = 0, relative to r^k (the scale of the k-th derivative).
  // Tolerance 1e-12 of that scale: the scaled form has no cancellation beyond O(1) terms.
  ModalBasis b(30);
  for (int i = 0; i < 30; ++i) {
    const double r = b.root(i);
    EXPECT_NEAR(b.shape(i, 0.0, 0), 0.0, 1e-12);
    EXPECT_NEAR(b.shape(i, 0.0, 1) / r, 0.0, 1e-12);
    EXPECT_NEAR(b.shape(i, 1.0, 2) / (r * r), 0.0, 1e-12) << "mode " << i + 1;
    EXPECT_NEAR(b.shape(i, 1.0, 3) / (r * r * r), 0.0, 1e-12) << "mode " << i + 1;
    EXPECT_NEAR(std::abs(b.shape(i, 1.0, 0)), 2.0, 1e-12) << "tip amplitude of a normalised cantilever mode is 2";
  }
}

TEST(ModalBasis, SatisfiesTheBeamEquationAndMatchesTheTextbookFormForLowModes) {
  // S'''' = r⁴ S (checked by a 5-point finite difference of S'' with h = 1e-3: error O(h²r⁴) ≈ 1e-6·r²
  // relative), and for r ≲ 8 the textbook form cosh − cos − σ(sinh − sin) has no harmful cancellation.
  ModalBasis b(8);
  for (int i = 0; i < 8; ++i) {
    const double r = b.root(i);
    for (double xi : {0.1, 0.37, 0.5, 0.81, 0.95}) {
      EXPECT_NEAR(b.shape(i, xi, 4), std::pow(r, 4) * b.shape(i, xi, 0), 1e-10 * std::pow(r, 4));
      const double h = 1e-3;
      const double fd4 = (-b.shape(i, xi + 2 * h, 2) + 16 * b.shape(i, xi + h, 2) - 30 * b.shape(i, xi, 2) +
                          16 * b.shape(i, xi - h, 2) - b.shape(i, xi - 2 * h, 2)) / (12 * h * h);
      EXPECT_NEAR(fd4, b.shape(i, xi, 4), 1e-6 * std::pow(r, 6)) << "mode " << i + 1;
      if (i < 3) {
        const double sg = (std::sinh(r) - std::sin(r)) / (std::cosh(r) + std::cos(r));
        const double textbook = std::cosh(r * xi) - std::cos(r * xi) - sg * (std::sinh(r * xi) - std::sin(r * xi));
        EXPECT_NEAR(b.shape(i, xi, 0), textbook, 1e-12);
      }
    }
  }
}

namespace {
// Composite 30-point Gauss–Legendre on 64 panels of [a, b].
struct GK {
  template <class F>
  static double integrate(F f, double a, double b, int, double) {
    const int panels = 64;
    double sum = 0;
    for (int p = 0; p < panels; ++p)
      sum += boost::math::quadrature::gauss<double, 30>::integrate(f, a + (b - a) * p / panels,
                                                                   a + (b - a) * (p + 1) / panels);
    return sum;
  }
};
}  // namespace

TEST(ModalBasis, OrthonormalUpTo30Modes) {
  // ∫S_iS_j = δ_ij and ∫S_i''S_j'' = r_i⁴ δ_ij, by Boost's 30-point Gauss rule on 64 panels
  // (independent of the library's quadrature; resolves frequencies up to 2 r_30 ≈ 186 with a
  // large margin). Tolerance 1e-10 relative (to 1 and to r_i² r_j² respectively).
  const int n = 30;
  ModalBasis b(n);

  for (int i = 0; i < n; ++i)
    for (int j = i; j < n; ++j) {
      const double ss = GK::integrate([&](double x) { return b.shape(i, x) * b.shape(j, x); }, 0.0, 1.0, 15, 1e-14);
      const double dd =
          GK::integrate([&](double x) { return b.shape(i, x, 2) * b.shape(j, x, 2); }, 0.0, 1.0, 15, 1e-14);
      const double scale = std::pow(b.root(i) * b.root(j), 2);
      EXPECT_NEAR(ss, i == j ? 1.0 : 0.0, 1e-10) << i << "," << j;
      EXPECT_NEAR(dd / scale, i == j ? 1.0 : 0.0, 1e-10) << i << "," << j;
    }
}
