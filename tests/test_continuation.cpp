// The continuation of fixed points (continuation.hpp) on maps whose bifurcations are known in closed
// form: the logistic map's period doubling and its period-2 branch, a fold, a Neimark–Sacker pair,
// and a change of the event count (grazing).
#include "rotbeam/continuation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rotbeam {
namespace {

// Applies f `period` times.
template <class F>
ParametrisedMap iterate(F f) {
  return [f](const Eigen::VectorXd& z, double p, int period) {
    MapValue v;
    v.z = z;
    for (int k = 0; k < period; ++k) v.z = f(v.z, p);
    return v;
  };
}

std::vector<const SpecialPoint*> of_kind(const ContinuationResult& r, SpecialKind kind) {
  std::vector<const SpecialPoint*> out;
  for (const SpecialPoint& s : r.special)
    if (s.kind == kind) out.push_back(&s);
  return out;
}

// x → r x (1 − x): the fixed point 1 − 1/r with multiplier 2 − r loses its stability at r = 3 to the
// 2-cycle x± = ((r + 1) ± √((r − 3)(r + 1))) / 2r, whose multiplier is 4 + 2r − r².
TEST(Continuation, LogisticPeriodDoublingAndItsDoubledBranch) {
  const ParametrisedMap map = iterate([](const Eigen::VectorXd& x, double r) {
    Eigen::VectorXd y(1);
    y[0] = r * x[0] * (1.0 - x[0]);
    return y;
  });
  ContinuationSettings s;
  s.tolerance = 1e-12;
  const ContinuationResult r = continue_fixed_points(map, Eigen::VectorXd::Constant(1, 0.55), 2.5, 3.4, 1, s);
  ASSERT_GE(r.branches.size(), 2u);
  const auto pd = of_kind(r, SpecialKind::period_doubling);
  ASSERT_EQ(pd.size(), 1u);
  // The multiplier is linear in r: interpolation locates the crossing to the Jacobian's error (1e-9).
  EXPECT_NEAR(pd[0]->parameter, 3.0, 1e-6);
  EXPECT_EQ(pd[0]->doubled_branch, 1);
  int doubled = 0, first = 0;
  for (const BranchPoint& p : r.points) {
    const double rr = p.parameter;
    if (p.branch == 0) {
      ++first;
      EXPECT_EQ(p.period, 1);
      // Tolerance: the corrector's 1e-12 relative residual.
      EXPECT_NEAR(p.z[0], 1.0 - 1.0 / rr, 1e-10) << "r = " << rr;
      // Central differences with δ = 1e-5·|z| on a quadratic map: exact but for round-off (1e-10).
      EXPECT_NEAR(p.multipliers[0].re, 2.0 - rr, 1e-7) << "r = " << rr;
      EXPECT_EQ(p.stable, rr < 3.0) << "r = " << rr;
    } else {
      ++doubled;
      EXPECT_EQ(p.period, 2);
      EXPECT_GT(rr, 3.0 - 1e-9);
      const double root = std::sqrt(std::max(0.0, (rr - 3.0) * (rr + 1.0)));
      const double xp = (rr + 1.0 + root) / (2.0 * rr), xm = (rr + 1.0 - root) / (2.0 * rr);
      EXPECT_NEAR(std::min(std::abs(p.z[0] - xp), std::abs(p.z[0] - xm)), 0.0, 1e-9) << "r = " << rr;
      EXPECT_NEAR(p.multipliers[0].re, 4.0 + 2.0 * rr - rr * rr, 1e-6) << "r = " << rr;
      EXPECT_TRUE(p.stable) << "r = " << rr;  // stable up to 1 + √6 = 3.449
    }
  }
  EXPECT_GT(first, 10);
  EXPECT_GT(doubled, 3);
  EXPECT_NEAR(r.points.back().parameter, 3.4, 1e-9);  // the doubled branch runs to the range's end
}

// x → x + (p − x²)/2: the fixed points ±√p meet in a fold at p = 0; +√p is stable (μ = 1 − √p), −√p
// is not (μ = 1 + √p). Started on the upper branch at p = 1 toward p = −1, the continuation turns at
// the fold and comes back along the lower one.
TEST(Continuation, FoldIsTurnedAndLocated) {
  const ParametrisedMap map = iterate([](const Eigen::VectorXd& x, double p) {
    Eigen::VectorXd y(1);
    y[0] = x[0] + 0.5 * (p - x[0] * x[0]);
    return y;
  });
  ContinuationSettings s;
  s.tolerance = 1e-12;
  const ContinuationResult r = continue_fixed_points(map, Eigen::VectorXd::Constant(1, 1.05), 1.0, -1.0, 1, s);
  const auto fold = of_kind(r, SpecialKind::fold);
  ASSERT_EQ(fold.size(), 1u);
  // The cubic Hermite interpolant of p(s) is exact to O(h³) (h ≤ 0.1 and p(s) quadratic near the fold): 1e-4.
  EXPECT_NEAR(fold[0]->parameter, 0.0, 1e-4);
  bool upper = false, lower = false;
  for (const BranchPoint& p : r.points) {
    EXPECT_NEAR(p.z[0] * p.z[0], p.parameter, 1e-9);
    if (p.z[0] > 1e-3) {
      upper = true;
      EXPECT_TRUE(p.stable) << p.parameter;
    }
    if (p.z[0] < -1e-3) {
      lower = true;
      EXPECT_FALSE(p.stable) << p.parameter;
    }
  }
  EXPECT_TRUE(upper && lower);
  ASSERT_EQ(r.branches.size(), 1u);
  EXPECT_NE(r.branches[0].end.find("turned back"), std::string::npos) << r.branches[0].end;
}

// w → (1 + p) R(φ) w − |w|² w about the fixed point c = (1, 1): multipliers (1 + p) e^{±iφ}, through the
// unit circle at p = 0.
TEST(Continuation, NeimarkSackerPairIsLocated) {
  const double phi = 0.7;
  const ParametrisedMap map = iterate([phi](const Eigen::VectorXd& z, double p) {
    const Eigen::Vector2d c(1.0, 1.0);
    const Eigen::Vector2d w = z - c;
    Eigen::Matrix2d R;
    R << std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi);
    Eigen::VectorXd y = c + (1.0 + p) * R * w - w.squaredNorm() * w;
    return y;
  });
  ContinuationSettings s;
  s.tolerance = 1e-12;
  const ContinuationResult r = continue_fixed_points(map, Eigen::Vector2d(1.0, 1.0), -0.2, 0.3, 1, s);
  const auto ns = of_kind(r, SpecialKind::neimark_sacker);
  ASSERT_EQ(ns.size(), 1u);
  EXPECT_NEAR(ns[0]->parameter, 0.0, 1e-6);  // |μ| = 1 + p is linear in p
  EXPECT_NEAR(std::atan2(ns[0]->multiplier.im, ns[0]->multiplier.re), phi, 1e-6);
  EXPECT_TRUE(of_kind(r, SpecialKind::period_doubling).empty());
  EXPECT_TRUE(of_kind(r, SpecialKind::fold).empty());
}

// x → (x + p)/2 with one "impact" per period while x > 0.5: the fixed point x = p grazes at p = 0.5.
TEST(Continuation, GrazingIsWhereTheEventCountChanges) {
  const ParametrisedMap map = [](const Eigen::VectorXd& z, double p, int period) {
    MapValue v;
    v.z = z;
    for (int k = 0; k < period; ++k) v.z[0] = 0.5 * (v.z[0] + p);
    v.metrics.impacts = z[0] > 0.5 ? period : 0;
    return v;
  };
  ContinuationSettings s;
  s.tolerance = 1e-12;
  const ContinuationResult r = continue_fixed_points(map, Eigen::VectorXd::Constant(1, 0.2), 0.2, 0.9, 1, s);
  const auto g = of_kind(r, SpecialKind::grazing);
  ASSERT_EQ(g.size(), 1u);
  const BranchPoint& a = r.points[static_cast<std::size_t>(g[0]->before)];
  const BranchPoint& b = r.points[static_cast<std::size_t>(g[0]->before) + 1];
  EXPECT_LE(a.parameter, 0.5);
  EXPECT_GE(b.parameter, 0.5);
  EXPECT_EQ(a.metrics.impacts, 0);
  EXPECT_EQ(b.metrics.impacts, 1);
  EXPECT_NEAR(r.points.back().parameter, 0.9, 1e-12);
}

// x → (x + p)/2 (the fixed point x = p) cannot be evaluated below p = 0.05 nor inside (0.42, 0.47). With a
// reseed that knows the fixed point, the start is found further on and followed back toward `from`
// until the map fails, the branch stalls at the band and restarts past it, and the range's end is
// reached: no point lies where the map fails, and every point is x = p.
TEST(Continuation, StartSearchBackwardBranchAndRestartsPastAFailingBand) {
  const auto fails = [](double p) { return p < 0.05 || (p > 0.42 && p < 0.47); };
  const ParametrisedMap map = [fails](const Eigen::VectorXd& z, double p, int period) {
    MapValue v;
    if (fails(p)) {
      v.failure = NumericalFailure{FailureKind::non_finite, 0.0, 0.0, "no map here"};
      return v;
    }
    v.z = z;
    for (int k = 0; k < period; ++k) v.z[0] = 0.5 * (v.z[0] + p);
    return v;
  };
  int reseeds = 0;
  const ReseedFunction reseed = [&reseeds](double p, const Eigen::VectorXd&) -> std::optional<Reseed> {
    ++reseeds;
    return Reseed{Eigen::VectorXd::Constant(1, p), 1, "exact"};
  };
  ContinuationSettings s;
  s.tolerance = 1e-12;
  const ContinuationResult r = continue_fixed_points(map, Eigen::VectorXd::Constant(1, 0.3), 0.0, 1.0, 1, s, {}, reseed);
  ASSERT_FALSE(r.points.empty());
  EXPECT_FALSE(r.failure);
  EXPECT_GE(r.branches.size(), 3u);  // back toward from, forward to the band, restarted past it
  EXPECT_NE(r.branches[0].start.find("found at p = "), std::string::npos) << r.branches[0].start;
  EXPECT_NE(r.branches[0].start.find("followed back"), std::string::npos) << r.branches[0].start;
  EXPECT_NE(r.branches.back().start.find("restarted"), std::string::npos) << r.branches.back().start;
  double lowest = 1, highest = 0;
  bool before_band = false, after_band = false;
  for (const BranchPoint& p : r.points) {
    EXPECT_FALSE(fails(p.parameter)) << p.parameter;
    EXPECT_NEAR(p.z[0], p.parameter, 1e-10);
    EXPECT_NEAR(p.multipliers[0].re, 0.5, 1e-8);
    lowest = std::min(lowest, p.parameter);
    highest = std::max(highest, p.parameter);
    before_band |= p.parameter > 0.40 && p.parameter <= 0.42;
    after_band |= p.parameter >= 0.47 && p.parameter < 0.5;
  }
  EXPECT_LT(lowest, 0.06);   // followed back to the failure below 0.05 (within the first try's 1 %)
  EXPECT_EQ(highest, 1.0);   // the last step lands on `to`
  EXPECT_TRUE(before_band && after_band);
  EXPECT_LE(reseeds, 15);    // 0.01, … 0.06 at the start, 0.43 … 0.48 past the band
}

TEST(Continuation, RejectsAnEmptyRange) {
  const ParametrisedMap map = iterate([](const Eigen::VectorXd& x, double) { return x; });
  EXPECT_THROW(continue_fixed_points(map, Eigen::VectorXd::Zero(1), 1.0, 1.0, 1, {}), std::invalid_argument);
  EXPECT_THROW(continue_fixed_points(map, Eigen::VectorXd::Zero(1), 0.0, 1.0, 0, {}), std::invalid_argument);
}

// A map that cannot be evaluated at the start: no point, and the branch says why.
TEST(Continuation, NoStartPointSaysWhy) {
  const ParametrisedMap map = [](const Eigen::VectorXd&, double, int) {
    MapValue v;
    v.failure = NumericalFailure{};
    v.failure->message = "boom";
    return v;
  };
  const ContinuationResult r = continue_fixed_points(map, Eigen::VectorXd::Ones(2), 0.0, 1.0, 1, {});
  EXPECT_TRUE(r.points.empty());
  ASSERT_EQ(r.branches.size(), 1u);
  EXPECT_NE(r.branches[0].end.find("boom"), std::string::npos);
}

}  // namespace
}  // namespace rotbeam
