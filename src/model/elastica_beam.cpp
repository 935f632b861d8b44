#include "rotbeam/elastica_beam.hpp"
#include "rotbeam/units.hpp"

#include "rotbeam/modal_analysis.hpp"
#include "rotbeam/quadrature.hpp"
#include "rotbeam/detail/quadratic_form.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <boost/math/special_functions/legendre.hpp>
#include <cassert>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace rotbeam {

ElasticaWorkspace::ElasticaWorkspace(int size, int nodes)
    : BeamWorkspace(size),
      phi(nodes), phid(nodes), cos_phi(nodes), sin_phi(nodes),
      x(nodes), y(nodes), xd(nodes), yd(nodes), ax(nodes), ay(nodes), fx(nodes), fy(nodes),
      integrand(nodes, 2 * size + 2), integral(nodes, 2 * size + 2), rate_integrand(nodes, 4), rate_integral(nodes, 4),
      start(2 * size + 2) {}

namespace {

constexpr int K = ElasticaBeam::kPanelPoints;

// The workspace an ElasticaBeam evaluates into is always one it made (make_workspace).
ElasticaWorkspace& own(BeamWorkspace& ws) {
  assert(dynamic_cast<ElasticaWorkspace*>(&ws) != nullptr);
  return static_cast<ElasticaWorkspace&>(ws);
}

// φ at every node, its cosine and sine, the position r(ξ_m) and the Jacobians J = ∂r/∂q, all of
// their running integrals at once.
void geometry(const ElasticaBeam& b, const Eigen::Ref<const Eigen::VectorXd>& q, ElasticaWorkspace& ws) {
  const double L = b.length;
  const int n = b.n;
  ws.phi.noalias() = b.slope * q;
  ws.phi /= L;
  ws.cos_phi = ws.phi.array().cos();
  ws.sin_phi = ws.phi.array().sin();
  // Columns: cos φ, sin φ, −sin φ S_i' (→ ∂x/∂q_i), cos φ S_i' (→ ∂y/∂q_i).
  ws.integrand.col(0) = ws.cos_phi;
  ws.integrand.col(1) = ws.sin_phi;
  ws.integrand.middleCols(2, n) = -(b.slope.array().colwise() * ws.sin_phi.array());
  ws.integrand.middleCols(2 + n, n) = b.slope.array().colwise() * ws.cos_phi.array();
  b.running_integrals(ws.integrand, ws.integral, ws.start);
  ws.x = (ws.integral.col(0) * L).array() + b.hub_radius;
  ws.y = ws.integral.col(1) * L;
}

// M = ρA L Σ_m w_m (J_x,mᵀ J_x,m + J_y,mᵀ J_y,m), from the Jacobians of geometry().
void mass_matrix(const ElasticaBeam& b, ElasticaWorkspace& ws) {
  const double c = b.mass_per_length * b.length;
  const int n = b.n;
  // The weighted Jacobians, in the integrand's columns (geometry() is done with them).
  ws.integrand.middleCols(0, 2 * n) = ws.integral.middleCols(2, 2 * n).array().colwise() * b.node_weight.array();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) {
      const double mij = c * (ws.integrand.col(i).dot(ws.jx().col(j)) + ws.integrand.col(n + i).dot(ws.jy().col(j)));
      ws.mass(i, j) = mij;
      ws.mass(j, i) = mij;
    }
}

// φ̇, the relative velocity ṙ and a_q = J̇q̇ at every node (after geometry()).
void rates(const ElasticaBeam& b, const Eigen::Ref<const Eigen::VectorXd>& qd, ElasticaWorkspace& ws) {
  const double L = b.length;
  ws.phid.noalias() = b.slope * qd;
  ws.phid /= L;
  // ẋ = −L∫ sin φ φ̇ dξ, ẏ = L∫ cos φ φ̇ dξ; a_q,x = −L∫ cos φ φ̇² dξ, a_q,y = −L∫ sin φ φ̇² dξ.
  ws.rate_integrand.col(0) = -ws.sin_phi.cwiseProduct(ws.phid);
  ws.rate_integrand.col(1) = ws.cos_phi.cwiseProduct(ws.phid);
  ws.rate_integrand.col(2) = -ws.cos_phi.cwiseProduct(ws.phid.cwiseAbs2());
  ws.rate_integrand.col(3) = -ws.sin_phi.cwiseProduct(ws.phid.cwiseAbs2());
  b.running_integrals(ws.rate_integrand, ws.rate_integral, ws.start);
  ws.xd = ws.rate_integral.col(0) * L;
  ws.yd = ws.rate_integral.col(1) * L;
  ws.ax = ws.rate_integral.col(2) * L;
  ws.ay = ws.rate_integral.col(3) * L;
}

}  // namespace

void ElasticaBeam::running_integrals(const Eigen::MatrixXd& f, Eigen::MatrixXd& out, Eigen::RowVectorXd& start) const {
  const Eigen::Index cols = f.cols();
  const double half = 0.5 / panels;  // the panel's half-width in ξ
  auto s = start.head(cols);
  s.setZero();
  for (int p = 0; p < panels; ++p) {
    auto fp = f.middleRows<K>(p * K);
    auto op = out.middleRows<K>(p * K);
    op.noalias() = half * running * fp;
    op.rowwise() += s;
    s.noalias() += half * reference_weight.transpose() * fp;
  }
}

double ElasticaBeam::running_integral(const double* f, double* out) const {
  double start = 0.0;
  const double half = 0.5 / panels;  // the panel's half-width in ξ
  for (int p = 0; p < panels; ++p) {
    const Eigen::Map<const Eigen::Matrix<double, K, 1>> fp(f + p * K);
    Eigen::Map<Eigen::Matrix<double, K, 1>> op(out + p * K);
    op.noalias() = running * fp;
    op = (half * op).array() + start;
    start += half * reference_weight.dot(fp);
  }
  return start;
}

std::unique_ptr<BeamWorkspace> ElasticaBeam::make_workspace() const {
  return std::make_unique<ElasticaWorkspace>(n, nodes());
}

void ElasticaBeam::evaluate_mass(const Eigen::Ref<const Eigen::VectorXd>& q, BeamWorkspace& base) const {
  ElasticaWorkspace& ws = own(base);
  geometry(*this, q, ws);
  mass_matrix(*this, ws);
  ws.mass_llt.compute(ws.mass);
}

void ElasticaBeam::evaluate_dynamics(const Eigen::Ref<const Eigen::VectorXd>& q,
                                     const Eigen::Ref<const Eigen::VectorXd>& qd, BeamWorkspace& base) const {
  ElasticaWorkspace& ws = own(base);
  geometry(*this, q, ws);
  mass_matrix(*this, ws);
  ws.mass_llt.compute(ws.mass);
  rates(*this, qd, ws);
  // The inertial acceleration less J q̈: a_q + 2ω k × ṙ − ω² r, weighted by the quadrature.
  const double w2 = centrifugal ? omega * omega : 0.0, cw = coriolis ? 2.0 * omega : 0.0;
  ws.fx = node_weight.cwiseProduct(ws.ax - cw * ws.yd - w2 * ws.x);
  ws.fy = node_weight.cwiseProduct(ws.ay + cw * ws.xd - w2 * ws.y);
  const double c = mass_per_length * length;
  ws.psi.noalias() = ws.jx().transpose() * ws.fx;
  ws.psi.noalias() += ws.jy().transpose() * ws.fy;
  ws.psi *= c;
  ws.psi += (bending_stiffness / (length * length * length)) * r4.cwiseProduct(q);
  if (damped()) ws.psi.noalias() += damping * qd;
}

void ElasticaBeam::tip(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                       HubFrameTip& out) const {
  const double L = length;
  double cx = 0, sy = 0, vx = 0, vy = 0, qx = 0, qy = 0;
  out.dx_dq.setZero();
  out.dy_dq.setZero();
  for (int m = 0; m < nodes(); ++m) {
    const double phi = slope.row(m).dot(q) / L, rate = slope.row(m).dot(qd) / L;
    const double c = std::cos(phi), s = std::sin(phi), w = node_weight[m];
    cx += w * c;
    sy += w * s;
    vx -= w * s * rate;
    vy += w * c * rate;
    qx -= w * c * rate * rate;
    qy -= w * s * rate * rate;
    out.dx_dq.noalias() -= (w * s) * slope.row(m).transpose();
    out.dy_dq.noalias() += (w * c) * slope.row(m).transpose();
  }
  out.x = hub_radius + L * cx;
  out.y = L * sy;
  out.xd = L * vx;
  out.yd = L * vy;
  out.x_quadratic = L * qx;
  out.y_quadratic = L * qy;
}

Eigen::Vector2d ElasticaBeam::tip_position(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  double cx = 0, sy = 0;
  for (int m = 0; m < nodes(); ++m) {
    const double phi = slope.row(m).dot(q) / length;
    cx += node_weight[m] * std::cos(phi);
    sy += node_weight[m] * std::sin(phi);
  }
  return {hub_radius + length * cx, length * sy};
}

void ElasticaBeam::shape(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& xi,
                         Eigen::Ref<Eigen::MatrixXd> positions) const {
  if (positions.rows() != xi.size() || positions.cols() != 2)
    throw std::invalid_argument("shape: positions must be " + std::to_string(xi.size()) + " x 2");
  const ModalBasis& basis = *this->basis;
  const QuadratureRule& gauss = gauss_legendre_reference(K);
  const double max_panel = 1.0 / panels;
  std::vector<double> ds(static_cast<std::size_t>(n));
  double at = 0.0, cx = 0.0, sy = 0.0;  // ∫₀^at cos φ dξ, ∫₀^at sin φ dξ
  for (Eigen::Index k = 0; k < xi.size(); ++k) {
    if (!(xi[k] >= at && xi[k] <= 1.0))
      throw std::invalid_argument("shape: the points ξ must ascend within [0, 1] (ξ = " + std::to_string(xi[k]) + ")");
    const int parts = static_cast<int>(std::ceil((xi[k] - at) / max_panel));
    for (int p = 0; p < parts; ++p) {
      const double a = at + (xi[k] - at) * p / parts, b = at + (xi[k] - at) * (p + 1) / parts;
      for (std::size_t g = 0; g < gauss.nodes.size(); ++g) {
        basis.evaluate(0.5 * (a + b) + 0.5 * (b - a) * gauss.nodes[g], nullptr, ds.data(), nullptr);
        double phi = 0.0;
        for (int i = 0; i < n; ++i) phi += q[i] * ds[static_cast<std::size_t>(i)];
        phi /= length;
        cx += 0.5 * (b - a) * gauss.weights[g] * std::cos(phi);
        sy += 0.5 * (b - a) * gauss.weights[g] * std::sin(phi);
      }
    }
    at = xi[k];
    positions(k, 0) = hub_radius + length * cx;
    positions(k, 1) = length * sy;
  }
}

double ElasticaBeam::tip_deflection(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  return std::abs(tip_position(q).y());
}

EnergyTerms ElasticaBeam::energy(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                                 BeamWorkspace& base) const {
  ElasticaWorkspace& ws = own(base);
  geometry(*this, q, ws);
  rates(*this, qd, ws);
  const double c = mass_per_length * length;  // ρA ∫ … ds = ρA L Σ w …
  EnergyTerms e;
  e.t2 = 0.5 * c * node_weight.dot(ws.xd.cwiseAbs2() + ws.yd.cwiseAbs2());  // ½ρA∫|ṙ|² = ½q̇ᵀMq̇
  e.spin_inertia = c * node_weight.dot(ws.x.cwiseAbs2() + ws.y.cwiseAbs2());
  e.relative_momentum = c * node_weight.dot(ws.x.cwiseProduct(ws.yd) - ws.y.cwiseProduct(ws.xd));
  const double s0 = centrifugal ? 1.0 : 0.0, s1 = coriolis ? 1.0 : 0.0;
  e.t0 = s0 * 0.5 * omega * omega * e.spin_inertia;
  e.t1 = s1 * omega * e.relative_momentum;
  e.angular_momentum = s0 * omega * e.spin_inertia + s1 * e.relative_momentum;
  e.potential = 0.5 * bending_stiffness / (length * length * length) * r4.dot(q.cwiseAbs2());
  e.kinetic = e.t0 + e.t1 + e.t2;
  e.jacobi = e.t2 - e.t0 + e.potential;
  return e;
}

double ElasticaBeam::angular_momentum_rate(const Eigen::Ref<const Eigen::VectorXd>& q,
                                           const Eigen::Ref<const Eigen::VectorXd>& qd,
                                           const Eigen::Ref<const Eigen::VectorXd>& qdd, BeamWorkspace& base) const {
  ElasticaWorkspace& ws = own(base);
  geometry(*this, q, ws);
  rates(*this, qd, ws);
  const double c = mass_per_length * length;
  double rate = 0.0;
  if (centrifugal) rate += 2.0 * omega * c * node_weight.dot(ws.x.cwiseProduct(ws.xd) + ws.y.cwiseProduct(ws.yd));
  if (coriolis) {
    // ẍ = J_x q̈ + a_q,x, ÿ = J_y q̈ + a_q,y.
    ws.fx.noalias() = ws.jx() * qdd;
    ws.fx += ws.ax;
    ws.fy.noalias() = ws.jy() * qdd;
    ws.fy += ws.ay;
    rate += c * node_weight.dot(ws.x.cwiseProduct(ws.fy) - ws.y.cwiseProduct(ws.fx));
  }
  return rate;
}

double ElasticaBeam::dissipation(const Eigen::Ref<const Eigen::VectorXd>& qd) const {
  return damped() ? detail::quadratic_form(damping, qd) : 0.0;
}

double ElasticaBeam::tip_excursion_bound(const Eigen::Ref<const Eigen::VectorXd>& q,
                                         const Eigen::Ref<const Eigen::VectorXd>& qd, BeamWorkspace& ws) const {
  const double h = energy(q, qd, ws).jacobi;
  const double big_h = std::max(h - excursion_v0, 0.0);  // U never exceeds it
  const double phi2 = 2.0 * excursion_mu * big_h / length;  // ∫φ² ds [m]
  return std::min(std::hypot(0.5 * phi2, std::sqrt(length * phi2)), 2.0 * length);
}

ElasticaBeam make_elastica(const BeamParameters& p, double theta0_rad, int panels) {
  const BeamConstants constants = beam_constants(p, theta0_rad, kMaxElasticaModes);
  if (panels < 0) throw std::invalid_argument("panels must be >= 0, got " + std::to_string(panels));
  ElasticaBeam b;
  static_cast<BeamConstants&>(b) = constants;
  b.panels = panels > 0 ? panels : b.n + 2;

  // Legendre nodes on [−1, 1], ascending, and the running-integral matrix: with the Lagrange basis
  // ℓ_m = Σ_l (2l+1)/2 w_m P_l(x_m) P_l (exact, as ℓ_m P_l has degree ≤ 2K − 2) and
  // ∫_{−1}^{x} P_l = (P_{l+1}(x) − P_{l−1}(x))/(2l + 1), ∫_{−1}^{x} P_0 = x + 1.
  const QuadratureRule& ref = gauss_legendre_reference(K);
  std::vector<int> order(K);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int c) { return ref.nodes[a] < ref.nodes[c]; });
  Eigen::Matrix<double, K, 1> x_ref;
  for (int m = 0; m < K; ++m) {
    x_ref[m] = ref.nodes[order[m]];
    b.reference_weight[m] = ref.weights[order[m]];
  }
  for (int j = 0; j < K; ++j)
    for (int m = 0; m < K; ++m) {
      double sum = 0.5 * (x_ref[j] + 1.0);
      for (int l = 1; l < K; ++l)
        sum += 0.5 * boost::math::legendre_p(l, x_ref[m]) *
               (boost::math::legendre_p(l + 1, x_ref[j]) - boost::math::legendre_p(l - 1, x_ref[j]));
      b.running(j, m) = b.reference_weight[m] * sum;
    }

  const int nodes = b.panels * K;
  b.node_xi.resize(nodes);
  b.node_weight.resize(nodes);
  b.slope.resize(nodes, b.n);
  b.basis = std::make_shared<const ModalBasis>(b.n);
  const ModalBasis& basis = *b.basis;
  std::vector<double> ds(static_cast<std::size_t>(b.n));
  for (int pnl = 0; pnl < b.panels; ++pnl)
    for (int m = 0; m < K; ++m) {
      const int k = pnl * K + m;
      b.node_xi[k] = (pnl + 0.5 * (x_ref[m] + 1.0)) / b.panels;
      b.node_weight[k] = 0.5 * b.reference_weight[m] / b.panels;
      basis.evaluate(b.node_xi[k], nullptr, ds.data(), nullptr);
      for (int i = 0; i < b.n; ++i) b.slope(k, i) = ds[static_cast<std::size_t>(i)];
    }
  b.r4.resize(b.n);
  for (int i = 0; i < b.n; ++i) b.r4[i] = std::pow(basis.root(i), 4);

  // The linearisation about q = 0 from the same nodes: J_x(0) = 0, J_y(0) = S(ξ) (the running
  // integral of S'), and ∂²T0/∂q² = −mω²[Σ w (r_h/L(1 − ξ) + (1 − ξ²)/2) S'S'ᵀ − Σ w S Sᵀ]
  // (the double integral ∫(r_h + s)∫₀ˢψψᵀ ds with the order of integration exchanged).
  Eigen::MatrixXd s_nodes(nodes, b.n);
  for (int i = 0; i < b.n; ++i) b.running_integral(b.slope.col(i).data(), s_nodes.col(i).data());
  const Eigen::VectorXd distal = ((b.hub_radius / b.length) * (1.0 - b.node_xi.array()) +
                                  0.5 * (1.0 - b.node_xi.array().square())).matrix();
  const Eigen::MatrixXd weighted_s = b.node_weight.asDiagonal() * s_nodes;
  const Eigen::MatrixXd weighted_slope = b.node_weight.asDiagonal() * b.slope;
  b.linear.mass = b.mass * (s_nodes.transpose() * weighted_s);
  b.linear.mass = 0.5 * (b.linear.mass + b.linear.mass.transpose()).eval();
  const Eigen::MatrixXd isp_one = b.slope.transpose() * weighted_slope;  // ISP(1)
  Eigen::MatrixXd bending = Eigen::MatrixXd::Zero(b.n, b.n);
  bending.diagonal() = (b.bending_stiffness / std::pow(b.length, 3)) * b.r4;
  Eigen::MatrixXd k = bending;
  if (b.centrifugal)
    k += b.mass * b.omega * b.omega *
         (b.slope.transpose() * (distal.asDiagonal() * weighted_slope) - s_nodes.transpose() * weighted_s);
  b.linear.stiffness = 0.5 * (k + k.transpose());
  b.damping = modal_damping_matrix(b.linear.mass, b.linear.stiffness, p.damping_ratio);
  b.linear.damping = b.damped() ? b.damping : Eigen::MatrixXd::Zero(b.n, b.n);

  // The excursion bound's constants.
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> g(0.5 * (isp_one + isp_one.transpose()), bending,
                                                              Eigen::EigenvaluesOnly);
  b.excursion_mu = std::max(g.eigenvalues().maxCoeff(), 0.0);
  const double rh = b.hub_radius, L = b.length;
  b.excursion_v0 = -0.5 * (b.centrifugal ? b.omega * b.omega : 0.0) * b.mass * (rh * rh + rh * L + L * L / 3.0);
  return b;
}

}  // namespace rotbeam
