#include "rotbeam/mass_factor.hpp"

#include <utility>

namespace rotbeam {

namespace {

// Calls f(std::integral_constant<int, N>) for N = n (1 … MassFactor::kFixedUpTo).
template <class F, int... N>
void with_size(int n, F&& f, std::integer_sequence<int, N...>) {
  ((n == N + 1 ? (f(std::integral_constant<int, N + 1>{}), 0) : 0), ...);
}

template <class F>
void with_size(int n, F&& f) {
  with_size(n, std::forward<F>(f), std::make_integer_sequence<int, MassFactor::kFixedUpTo>{});
}

}  // namespace

void MassFactor::compute(const Eigen::MatrixXd& m) {
  if (n_ > kFixedUpTo) {
    dynamic_.compute(m);
    return;
  }
  with_size(n_, [&](auto size) {
    constexpr int N = decltype(size)::value;
    std::get<N - 1>(fixed_).compute(m.topLeftCorner<N, N>());
  });
}

void MassFactor::solve_fixed(double* b) const {
  with_size(n_, [&](auto size) {
    constexpr int N = decltype(size)::value;
    Eigen::Map<Eigen::Matrix<double, N, 1>> v(b);
    std::get<N - 1>(fixed_).solveInPlace(v);
  });
}

}  // namespace rotbeam
