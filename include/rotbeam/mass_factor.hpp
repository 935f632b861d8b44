// The Cholesky factor of a mass matrix M(q) (docs/model.md §3): Eigen's LLT, at a size fixed at compile
// time for n ≤ 8 (the factorisation and the solves unroll and touch no heap; at n = 5 they were a
// seventh of a whole pass in the dynamic-size LLT), Eigen's dynamic-size LLT above. One object serves
// every size up to the workspace's n, so a beam model's workspace keeps one.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <tuple>

namespace rotbeam {

class MassFactor {
public:
  /// The largest n with a fixed-size path.
  static constexpr int kFixedUpTo = 8;

  explicit MassFactor(int n = 0) : n_(n), dynamic_(n > kFixedUpTo ? n : 0) {}

  /// Factors the symmetric positive-definite n × n matrix m (its lower triangle is read).
  void compute(const Eigen::MatrixXd& m);

  /// b ← M⁻¹ b for a contiguous vector b of size n (Eigen::VectorXd, a Ref or a Map of one).
  template <class V>
  void solveInPlace(V&& b) const {
    if (n_ <= kFixedUpTo)
      solve_fixed(b.data());
    else
      dynamic_.solveInPlace(b);
  }

  /// B ← M⁻¹ B for an n × k matrix B (column by column).
  void solveColumnsInPlace(Eigen::Ref<Eigen::MatrixXd> b) const {
    if (n_ > kFixedUpTo) return dynamic_.solveInPlace(b);
    for (Eigen::Index c = 0; c < b.cols(); ++c) solve_fixed(b.col(c).data());
  }

  int size() const { return n_; }

private:
  void solve_fixed(double* b) const;

  template <int N>
  using Fixed = Eigen::LLT<Eigen::Matrix<double, N, N>>;
  int n_;
  std::tuple<Fixed<1>, Fixed<2>, Fixed<3>, Fixed<4>, Fixed<5>, Fixed<6>, Fixed<7>, Fixed<8>> fixed_;
  Eigen::LLT<Eigen::MatrixXd> dynamic_;
};

}  // namespace rotbeam
