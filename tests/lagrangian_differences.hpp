// Mass matrix and Ψ of a Lagrangian L(q, q̇) by numerical differentiation, for the tests of the
// equations of motion (docs/model.md §3):
//   M = ∂²L/∂q̇²,  Ψ = (∂p/∂q) q̇ − ∂L/∂q,  p = ∂L/∂q̇.
// A central difference is exact for L's quadratic dependence on q̇; a Richardson-extrapolated central
// difference (steps δ and δ/2) leaves O(δ⁴) for the dependence on q.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <functional>

namespace rotbeam::testing {

using Scalar2 = std::function<double(const Eigen::VectorXd&, const Eigen::VectorXd&)>;

// ∂f/∂x_i by Richardson-extrapolated central differences along direction d.
inline double directional(const std::function<double(double)>& f, double delta) {
  const double d1 = (f(delta) - f(-delta)) / (2 * delta);
  const double d2 = (f(delta / 2) - f(-delta / 2)) / delta;
  return (4 * d2 - d1) / 3;
}

inline Eigen::VectorXd momentum(const Scalar2& lag, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double dv) {
  Eigen::VectorXd p(q.size());
  for (int i = 0; i < q.size(); ++i) {
    Eigen::VectorXd vp = v, vm = v;
    vp[i] += dv;
    vm[i] -= dv;
    p[i] = (lag(q, vp) - lag(q, vm)) / (2 * dv);  // exact: L is quadratic in q̇
  }
  return p;
}

// Ψ_i = Σ_j ∂p_i/∂q_j q̇_j − ∂L/∂q_i.
inline Eigen::VectorXd psi_from_lagrangian(const Scalar2& lag, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double dq,
                                    double dv) {
  const int n = static_cast<int>(q.size());
  Eigen::VectorXd psi(n);
  const double vn = std::max(v.norm(), 1e-30);
  for (int i = 0; i < n; ++i) {
    auto p_along_v = [&](double e) {
      Eigen::VectorXd qe = q + (e / vn) * v;
      return momentum(lag, qe, v, dv)[i];
    };
    const double dp = v.norm() > 0 ? vn * directional(p_along_v, dq) : 0.0;
    auto l_along_qi = [&](double e) {
      Eigen::VectorXd qe = q;
      qe[i] += e;
      return lag(qe, v);
    };
    psi[i] = dp - directional(l_along_qi, dq);
  }
  return psi;
}

// M = ∂²L/∂q̇² by central second differences (exact: L is quadratic in q̇).
inline Eigen::MatrixXd mass_from_lagrangian(const Scalar2& lag, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double dv) {
  const int n = static_cast<int>(q.size());
  Eigen::MatrixXd m(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      auto at = [&](double a, double b) {
        Eigen::VectorXd vv = v;
        vv[i] += a;
        vv[j] += b;
        return lag(q, vv);
      };
      m(i, j) = (at(dv, dv) - at(dv, -dv) - at(-dv, dv) + at(-dv, -dv)) / (4 * dv * dv);
    }
  return m;
}

}  // namespace rotbeam::testing
