#include "rotbeam/quadrature.hpp"

#include <boost/math/special_functions/legendre.hpp>
#include <map>
#include <mutex>
#include <stdexcept>

namespace rotbeam {

const QuadratureRule& gauss_legendre_reference(int points) {
  static std::mutex mutex;
  static std::map<int, QuadratureRule> cache;
  if (points < 1) throw std::invalid_argument("gauss_legendre_reference: points must be >= 1");
  std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find(points);
  if (it != cache.end()) return it->second;
  QuadratureRule rule;
  const std::vector<double> zeros = boost::math::legendre_p_zeros<double>(points);  // non-negative zeros
  for (double x : zeros) {
    const double dp = boost::math::legendre_p_prime(points, x);
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    rule.nodes.push_back(x);
    rule.weights.push_back(w);
    if (x != 0.0) {
      rule.nodes.push_back(-x);
      rule.weights.push_back(w);
    }
  }
  return cache.emplace(points, std::move(rule)).first->second;
}

QuadratureRule composite_gauss_legendre(double a, double b, int panels, int points) {
  if (panels < 1) throw std::invalid_argument("composite_gauss_legendre: panels must be >= 1");
  const QuadratureRule& ref = gauss_legendre_reference(points);
  QuadratureRule rule;
  rule.nodes.reserve(static_cast<std::size_t>(panels) * ref.size());
  rule.weights.reserve(rule.nodes.capacity());
  const double width = (b - a) / panels;
  for (int p = 0; p < panels; ++p) {
    const double lo = a + p * width, half = 0.5 * width, mid = lo + half;
    for (std::size_t k = 0; k < ref.size(); ++k) {
      rule.nodes.push_back(mid + half * ref.nodes[k]);
      rule.weights.push_back(half * ref.weights[k]);
    }
  }
  return rule;
}

}  // namespace rotbeam
