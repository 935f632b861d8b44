#include "rotbeam/modal_integrals.hpp"

#include "rotbeam/quadrature.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <map>
#include <mutex>

namespace rotbeam {

namespace {
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
constexpr int kPointsPerPanel = 20;
}  // namespace

int default_quadrature_panels(int n) {
  const double r_max = cantilever_root(n);
  return static_cast<int>(std::ceil(4.0 * r_max / 12.0)) + 2;
}

ModalIntegrals compute_modal_integrals(int n, int panels, int points) {
  // The n⁴-sized tables of the thesis's model: its own limit (a ModalBasis takes the elastica's).
  if (n < 1 || n > kMaxModes)
    throw std::invalid_argument("modal integrals: modes must be in 1.." + std::to_string(kMaxModes) + ", got " +
                                std::to_string(n));
  ModalIntegrals mi(n);
  const ModalBasis& basis = mi.basis;
  mi.n = n;
  mi.pairs = n * (n + 1) / 2;
  mi.quadrature_panels = panels;
  mi.quadrature_points = points;
  mi.pair_index.assign(n * n, -1);
  for (int j = 0, p = 0; j < n; ++j)
    for (int l = j; l < n; ++l, ++p) {
      mi.pair_index[j * n + l] = mi.pair_index[l * n + j] = p;
      mi.pair_first.push_back(j);
      mi.pair_second.push_back(l);
    }
  const int np = mi.pairs;

  const QuadratureRule rule = composite_gauss_legendre(0.0, 1.0, panels, points);
  const QuadratureRule& ref = gauss_legendre_reference(points);
  const int g_count = static_cast<int>(rule.size());
  const double panel_width = 1.0 / panels;

  // Per node: ISP(ξ_g) (n² rows), packed P(ξ_g) (np rows), S(ξ_g), ξ_g.
  Eigen::MatrixXd isp_nodes(n * n, g_count), p_nodes(np, g_count), s_nodes(n, g_count);
  Eigen::VectorXd s(n), ds(n), d2s(n);
  Eigen::MatrixXd isp_panel_start = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd isp(n, n);

  auto integrate_dsds = [&](double a, double b, Eigen::MatrixXd& acc) {
    const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
    for (std::size_t k = 0; k < ref.size(); ++k) {
      basis.evaluate(mid + half * ref.nodes[k], nullptr, ds.data(), nullptr);
      acc.noalias() += (half * ref.weights[k]) * ds * ds.transpose();
    }
  };

  for (int g = 0; g < g_count; ++g) {
    const int panel = g / points;
    if (g % points == 0 && panel > 0) integrate_dsds((panel - 1) * panel_width, panel * panel_width, isp_panel_start);
    const double xi = rule.nodes[g];
    isp = isp_panel_start;
    integrate_dsds(panel * panel_width, xi, isp);
    basis.evaluate(xi, s.data(), ds.data(), d2s.data());
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < n; ++k) isp_nodes(i * n + k, g) = isp(i, k);
    for (int p = 0; p < np; ++p) {
      const int i = mi.pair_first[p], j = mi.pair_second[p];
      p_nodes(p, g) = d2s[i] * ds[j] + ds[i] * d2s[j];
    }
    s_nodes.col(g) = s;
  }
  Eigen::MatrixXd isp_tip = isp_panel_start;
  integrate_dsds((panels - 1) * panel_width, 1.0, isp_tip);

  const Eigen::Map<const Eigen::VectorXd> w(rule.weights.data(), g_count);
  const Eigen::Map<const Eigen::VectorXd> xi_nodes(rule.nodes.data(), g_count);

  mi.isp_tip = isp_tip;
  mi.isp_mean = (isp_nodes * w).reshaped(n, n).transpose();
  mi.isp_xi = (isp_nodes * w.cwiseProduct(xi_nodes)).reshaped(n, n).transpose();
  basis.evaluate(1.0, s.data(), nullptr, nullptr);
  mi.s_tip = s;
  mi.s_mean = s_nodes * w;
  mi.s_xi = s_nodes * w.cwiseProduct(xi_nodes);
  mi.r4.resize(n);
  for (int i = 0; i < n; ++i) mi.r4[i] = std::pow(basis.root(i), 4);

  // isp_isp[(i,k)][(j,l)] = Σ_g w_g ISP_ik(ξ_g) ISP_jl(ξ_g), only j ≤ l kept.
  Eigen::MatrixXd isp_pairs(np, g_count);
  for (int p = 0; p < np; ++p) isp_pairs.row(p) = isp_nodes.row(mi.pair_first[p] * n + mi.pair_second[p]);
  const RowMatrix isp_isp = isp_nodes * w.asDiagonal() * isp_pairs.transpose();
  mi.isp_isp.assign(isp_isp.data(), isp_isp.data() + isp_isp.size());

  const RowMatrix p_p = p_nodes * w.asDiagonal() * p_nodes.transpose();
  mi.p_p.assign(p_p.data(), p_p.data() + p_p.size());

  const RowMatrix isp_s = isp_nodes * w.asDiagonal() * s_nodes.transpose();
  mi.isp_s.assign(isp_s.data(), isp_s.data() + isp_s.size());
  return mi;
}

std::shared_ptr<const ModalIntegrals> modal_integrals(int n) {
  static std::mutex mutex;
  static std::map<int, std::shared_ptr<const ModalIntegrals>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  auto mi = std::make_shared<const ModalIntegrals>(compute_modal_integrals(n, default_quadrature_panels(n), kPointsPerPanel));
  cache.emplace(n, mi);
  return mi;
}

}  // namespace rotbeam
