// Composite Gauss–Legendre quadrature on an interval (used once, to precompute the ξ-integrals).
#pragma once

#include <vector>

namespace rotbeam {

/// Nodes and weights of a composite Gauss–Legendre rule: `panels` equal panels on [a, b],
/// `points` Legendre nodes per panel (nodes from Boost.Math's legendre_p_zeros).
/// Integrates polynomials of degree 2·points − 1 exactly on each panel.
struct QuadratureRule {
  std::vector<double> nodes;
  std::vector<double> weights;
  std::size_t size() const { return nodes.size(); }
};

QuadratureRule composite_gauss_legendre(double a, double b, int panels, int points);

/// Gauss–Legendre nodes/weights on [−1, 1] with `points` nodes (cached per point count).
const QuadratureRule& gauss_legendre_reference(int points);

}  // namespace rotbeam
