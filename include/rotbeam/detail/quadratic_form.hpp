// xᵀ A y for a dense square A without the temporary that Eigen's `x.dot(A * y)` creates.
#pragma once

#include <Eigen/Core>

namespace rotbeam::detail {

inline double bilinear_form(const Eigen::MatrixXd& a, const Eigen::Ref<const Eigen::VectorXd>& x,
                            const Eigen::Ref<const Eigen::VectorXd>& y) {
  double sum = 0.0;
  for (Eigen::Index j = 0; j < a.cols(); ++j) sum += y[j] * x.dot(a.col(j));
  return sum;
}

inline double quadratic_form(const Eigen::MatrixXd& a, const Eigen::Ref<const Eigen::VectorXd>& x) {
  return bilinear_form(a, x, x);
}

}  // namespace rotbeam::detail
