#include "rotbeam/extensible_beam.hpp"

#include "rotbeam/beam_factory.hpp"
#include "rotbeam/detail/quadratic_form.hpp"

#include <cassert>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace rotbeam {

ExtensibleWorkspace::ExtensibleWorkspace(int coordinates, int n, int nodes)
    : BeamWorkspace(coordinates),
      phi(nodes), phid(nodes), x(nodes), y(nodes), xd(nodes), yd(nodes), ax(nodes), ay(nodes), fx(nodes), fy(nodes),
      cos_phi(nodes), sin_phi(nodes), jx(nodes, coordinates), jy(nodes, coordinates), weighted(nodes, coordinates),
      bend(Eigen::VectorXd::Zero(coordinates)), curvature(nodes) {
  (void)n;
}

namespace {

// The workspace an ExtensibleBeam evaluates into is always one it made (make_workspace).
ExtensibleWorkspace& own(BeamWorkspace& ws) {
  assert(dynamic_cast<ExtensibleWorkspace*>(&ws) != nullptr);
  return static_cast<ExtensibleWorkspace&>(ws);
}

bool exact(const ExtensibleBeam& b) { return b.theory == BeamTheory::elastica; }

// φ at every node, the position r(ξ_m) and the Jacobians ∂r/∂(q, a) (extensible_beam.hpp).
void geometry(const ExtensibleBeam& b, const Eigen::Ref<const Eigen::VectorXd>& qa, ExtensibleWorkspace& ws) {
  const int n = b.n;
  const double L = b.length, a = qa[n];
  const auto q = qa.head(n);
  const ElasticaBeam& g = b.grid;
  ws.phi.noalias() = g.slope * q;
  ws.phi /= L;
  if (exact(b)) {
    // Columns: cos φ, sin φ, −sin φ S_i', cos φ S_i'; running integrals over ξ.
    ws.cos_phi = ws.phi.array().cos();
    ws.sin_phi = ws.phi.array().sin();
    ws.integrand.col(0) = ws.cos_phi;
    ws.integrand.col(1) = ws.sin_phi;
    ws.integrand.middleCols(2, n) = -(g.slope.array().colwise() * ws.sin_phi.array());
    ws.integrand.middleCols(2 + n, n) = g.slope.array().colwise() * ws.cos_phi.array();
    g.running_integrals(ws.integrand, ws.integral, ws.start);
    const double f = 1.0 + a / L;  // 1 + ε
    ws.x = (f * L * ws.integral.col(0)).array() + b.hub_radius;
    ws.y = f * L * ws.integral.col(1);
    ws.jx.leftCols(n) = f * ws.integral.middleCols(2, n);
    ws.jy.leftCols(n) = f * ws.integral.middleCols(2 + n, n);
    ws.jx.col(n) = ws.integral.col(0);  // ∂x/∂a = R_x/L
    ws.jy.col(n) = ws.integral.col(1);
  } else {
    // Columns: φ², φ S_i'.
    ws.integrand.col(0) = ws.phi.cwiseAbs2();
    ws.integrand.middleCols(1, n) = g.slope.array().colwise() * ws.phi.array();
    g.running_integrals(ws.integrand, ws.integral, ws.start);
    ws.x = (g.node_xi * (L + a) - 0.5 * L * ws.integral.col(0)).array() + b.hub_radius;
    ws.y.noalias() = b.shape_nodes * q;
    ws.jx.leftCols(n) = -ws.integral.middleCols(1, n);
    ws.jx.col(n) = g.node_xi;
    ws.jy.leftCols(n) = b.shape_nodes;
    ws.jy.col(n).setZero();
  }
}

// M = ρA L Σ_m w_m (J_x,mᵀ J_x,m + J_y,mᵀ J_y,m).
void mass_matrix(const ExtensibleBeam& b, ExtensibleWorkspace& ws) {
  const Eigen::VectorXd& w = b.grid.node_weight;
  ws.weighted.noalias() = w.asDiagonal() * ws.jx;
  ws.mass.noalias() = ws.jx.transpose() * ws.weighted;
  ws.weighted.noalias() = w.asDiagonal() * ws.jy;
  ws.mass.noalias() += ws.jy.transpose() * ws.weighted;
  ws.mass *= b.mass_per_length * b.length;
}

// φ̇, ṙ and a_q (the relative acceleration without q̈, ä) at every node, after geometry().
void rates(const ExtensibleBeam& b, const Eigen::Ref<const Eigen::VectorXd>& qa,
           const Eigen::Ref<const Eigen::VectorXd>& qad, ExtensibleWorkspace& ws) {
  const int n = b.n;
  const double L = b.length, a = qa[n], ad = qad[n];
  const auto qd = qad.head(n);
  const ElasticaBeam& g = b.grid;
  ws.phid.noalias() = g.slope * qd;
  ws.phid /= L;
  if (exact(b)) {
    ws.rate_integrand.col(0) = -ws.sin_phi.cwiseProduct(ws.phid);
    ws.rate_integrand.col(1) = ws.cos_phi.cwiseProduct(ws.phid);
    ws.rate_integrand.col(2) = -ws.cos_phi.cwiseProduct(ws.phid.cwiseAbs2());
    ws.rate_integrand.col(3) = -ws.sin_phi.cwiseProduct(ws.phid.cwiseAbs2());
    g.running_integrals(ws.rate_integrand, ws.rate_integral, ws.start);
    // r = r_h + f R: ṙ = ḟ R + f Ṙ, a_q = 2ḟ Ṙ + f a_R (f = 1 + a/L, ḟ = ȧ/L).
    const double f = 1.0 + a / L, fd = ad / L;
    ws.xd = fd * L * ws.integral.col(0) + f * L * ws.rate_integral.col(0);
    ws.yd = fd * L * ws.integral.col(1) + f * L * ws.rate_integral.col(1);
    ws.ax = 2.0 * fd * L * ws.rate_integral.col(0) + f * L * ws.rate_integral.col(2);
    ws.ay = 2.0 * fd * L * ws.rate_integral.col(1) + f * L * ws.rate_integral.col(3);
  } else {
    ws.rate_integrand.col(0) = ws.phi.cwiseProduct(ws.phid);
    ws.rate_integrand.col(1) = ws.phid.cwiseAbs2();
    g.running_integrals(ws.rate_integrand, ws.rate_integral, ws.start);
    ws.xd = g.node_xi * ad - L * ws.rate_integral.col(0);
    ws.yd.noalias() = b.shape_nodes * qd;
    ws.ax = -L * ws.rate_integral.col(1);
    ws.ay.setZero();
  }
}

// The bending energy U_b [J] and its gradient into ws.bend (its last entry 0): ½(EI/L³)Σr_i⁴q_i², and
// for the quadratic geometry the thesis's quartic term (EI/2L⁵)∫(y'y'')² dξ (docs/model.md §3).
double bending(const ExtensibleBeam& b, const Eigen::Ref<const Eigen::VectorXd>& qa, ExtensibleWorkspace& ws) {
  const int n = b.n;
  const double L = b.length, c = b.bending_stiffness / (L * L * L);
  const auto q = qa.head(n);
  const Eigen::VectorXd& r4 = b.grid.r4;
  ws.bend.head(n) = c * r4.cwiseProduct(q);
  ws.bend[n] = 0.0;
  double energy = 0.5 * c * r4.dot(q.cwiseAbs2());
  if (!exact(b)) {
    // y' = S'ᵀq = L φ, y'' = S''ᵀq (ξ-derivatives, in metres); p = y'y''.
    ws.curvature.noalias() = b.curvature_nodes * q;
    ws.fx = (L * ws.phi).cwiseProduct(ws.curvature);  // p at the nodes (fx is free until the forces)
    const Eigen::VectorXd& w = b.grid.node_weight;
    const double cq = b.bending_stiffness / std::pow(L, 5);
    energy += 0.5 * cq * w.dot(ws.fx.cwiseAbs2());
    // ∂/∂q_i = cq Σ w p (S_i'' y' + S_i' y'').
    ws.fy = w.cwiseProduct(ws.fx).cwiseProduct(L * ws.phi);
    ws.bend.head(n).noalias() += cq * (b.curvature_nodes.transpose() * ws.fy);
    ws.fy = w.cwiseProduct(ws.fx).cwiseProduct(ws.curvature);
    ws.bend.head(n).noalias() += cq * (b.grid.slope.transpose() * ws.fy);
  }
  return energy;
}

}  // namespace

std::unique_ptr<BeamWorkspace> ExtensibleBeam::make_workspace() const {
  const int nodes = grid.nodes();
  auto ws = std::make_unique<ExtensibleWorkspace>(n + 1, n, nodes);
  const int columns = exact(*this) ? 2 * n + 2 : n + 1, rate_columns = exact(*this) ? 4 : 2;
  ws->integrand.resize(nodes, columns);
  ws->integral.resize(nodes, columns);
  ws->rate_integrand.resize(nodes, rate_columns);
  ws->rate_integral.resize(nodes, rate_columns);
  ws->start.resize(columns);
  return ws;
}

void ExtensibleBeam::evaluate_mass(const Eigen::Ref<const Eigen::VectorXd>& q, BeamWorkspace& base) const {
  ExtensibleWorkspace& ws = own(base);
  geometry(*this, q, ws);
  mass_matrix(*this, ws);
  ws.mass_llt.compute(ws.mass);
}

void ExtensibleBeam::evaluate_dynamics(const Eigen::Ref<const Eigen::VectorXd>& q,
                                       const Eigen::Ref<const Eigen::VectorXd>& qd, BeamWorkspace& base) const {
  ExtensibleWorkspace& ws = own(base);
  geometry(*this, q, ws);
  mass_matrix(*this, ws);
  ws.mass_llt.compute(ws.mass);
  rates(*this, q, qd, ws);
  bending(*this, q, ws);
  const double w2 = centrifugal ? omega * omega : 0.0, cw = coriolis ? 2.0 * omega : 0.0;
  const Eigen::VectorXd& w = grid.node_weight;
  ws.fx = w.cwiseProduct(ws.ax - cw * ws.yd - w2 * ws.x);
  ws.fy = w.cwiseProduct(ws.ay + cw * ws.xd - w2 * ws.y);
  ws.psi.noalias() = ws.jx.transpose() * ws.fx;
  ws.psi.noalias() += ws.jy.transpose() * ws.fy;
  ws.psi *= mass_per_length * length;
  ws.psi += ws.bend;
  ws.psi[n] += axial_stiffness * q[n];
  if (damped()) ws.psi.noalias() += damping * qd;
}

void ExtensibleBeam::tip(const Eigen::Ref<const Eigen::VectorXd>& qa, const Eigen::Ref<const Eigen::VectorXd>& qad,
                         HubFrameTip& out) const {
  const double L = length, a = qa[n], ad = qad[n];
  const auto q = qa.head(n), qd = qad.head(n);
  out.dx_dq.setZero();
  out.dy_dq.setZero();
  // Sums over the nodes: ∫₀¹ of the geometry's integrands.
  double i0 = 0, i1 = 0, v0 = 0, v1 = 0, v2 = 0, v3 = 0;
  for (int m = 0; m < grid.nodes(); ++m) {
    const auto slope = grid.slope.row(m);
    const double phi = slope.dot(q) / L, rate = slope.dot(qd) / L, w = grid.node_weight[m];
    if (exact(*this)) {
      const double c = std::cos(phi), s = std::sin(phi);
      i0 += w * c;
      i1 += w * s;
      v0 -= w * s * rate;
      v1 += w * c * rate;
      v2 -= w * c * rate * rate;
      v3 -= w * s * rate * rate;
      out.dx_dq.head(n).noalias() -= (w * s) * slope.transpose();
      out.dy_dq.head(n).noalias() += (w * c) * slope.transpose();
    } else {
      i0 += w * phi * phi;
      v0 += w * phi * rate;
      v2 += w * rate * rate;
      out.dx_dq.head(n).noalias() -= (w * phi) * slope.transpose();
    }
  }
  if (exact(*this)) {
    const double f = 1.0 + a / L, fd = ad / L;
    out.x = hub_radius + f * L * i0;
    out.y = f * L * i1;
    out.xd = fd * L * i0 + f * L * v0;
    out.yd = fd * L * i1 + f * L * v1;
    out.dx_dq.head(n) *= f;
    out.dy_dq.head(n) *= f;
    out.dx_dq[n] = i0;
    out.dy_dq[n] = i1;
    out.x_quadratic = 2.0 * fd * L * v0 + f * L * v2;
    out.y_quadratic = 2.0 * fd * L * v1 + f * L * v3;
  } else {
    out.x = hub_radius + L + a - 0.5 * L * i0;
    out.y = s_tip.dot(q);
    out.xd = ad - L * v0;
    out.yd = s_tip.dot(qd);
    out.dx_dq[n] = 1.0;
    out.dy_dq.head(n) = s_tip;
    out.dy_dq[n] = 0.0;
    out.x_quadratic = -L * v2;
    out.y_quadratic = 0.0;
  }
}

Eigen::Vector2d ExtensibleBeam::tip_position(const Eigen::Ref<const Eigen::VectorXd>& qa) const {
  const double L = length, a = qa[n];
  const auto q = qa.head(n);
  double i0 = 0, i1 = 0;
  for (int m = 0; m < grid.nodes(); ++m) {
    const double phi = grid.slope.row(m).dot(q) / L, w = grid.node_weight[m];
    if (exact(*this)) {
      i0 += w * std::cos(phi);
      i1 += w * std::sin(phi);
    } else {
      i0 += w * phi * phi;
    }
  }
  if (exact(*this)) return {hub_radius + (L + a) * i0, (L + a) * i1};
  return {hub_radius + L + a - 0.5 * L * i0, s_tip.dot(q)};
}

void ExtensibleBeam::shape(const Eigen::Ref<const Eigen::VectorXd>& qa, const Eigen::Ref<const Eigen::VectorXd>& xi,
                           Eigen::Ref<Eigen::MatrixXd> positions) const {
  inextensible->shape(qa.head(n), xi, positions);
  const double a = qa[n];
  if (exact(*this)) {
    const double f = 1.0 + a / length;
    positions.col(0) = (f * (positions.col(0).array() - hub_radius) + hub_radius).matrix();
    positions.col(1) *= f;
  } else {
    positions.col(0) += a * xi;
  }
}

double ExtensibleBeam::tip_deflection(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  return std::abs(tip_position(q).y());
}

EnergyTerms ExtensibleBeam::energy(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                                   BeamWorkspace& base) const {
  ExtensibleWorkspace& ws = own(base);
  geometry(*this, q, ws);
  rates(*this, q, qd, ws);
  const Eigen::VectorXd& w = grid.node_weight;
  const double c = mass_per_length * length;
  EnergyTerms e;
  e.t2 = 0.5 * c * w.dot(ws.xd.cwiseAbs2() + ws.yd.cwiseAbs2());
  e.spin_inertia = c * w.dot(ws.x.cwiseAbs2() + ws.y.cwiseAbs2());
  e.relative_momentum = c * w.dot(ws.x.cwiseProduct(ws.yd) - ws.y.cwiseProduct(ws.xd));
  const double s0 = centrifugal ? 1.0 : 0.0, s1 = coriolis ? 1.0 : 0.0;
  e.t0 = s0 * 0.5 * omega * omega * e.spin_inertia;
  e.t1 = s1 * omega * e.relative_momentum;
  e.angular_momentum = s0 * omega * e.spin_inertia + s1 * e.relative_momentum;
  e.potential = bending(*this, q, ws) + 0.5 * axial_stiffness * q[n] * q[n];
  e.kinetic = e.t0 + e.t1 + e.t2;
  e.jacobi = e.t2 - e.t0 + e.potential;
  return e;
}

double ExtensibleBeam::angular_momentum_rate(const Eigen::Ref<const Eigen::VectorXd>& q,
                                             const Eigen::Ref<const Eigen::VectorXd>& qd,
                                             const Eigen::Ref<const Eigen::VectorXd>& qdd, BeamWorkspace& base) const {
  ExtensibleWorkspace& ws = own(base);
  geometry(*this, q, ws);
  rates(*this, q, qd, ws);
  const Eigen::VectorXd& w = grid.node_weight;
  const double c = mass_per_length * length;
  double rate = 0.0;
  if (centrifugal) rate += 2.0 * omega * c * w.dot(ws.x.cwiseProduct(ws.xd) + ws.y.cwiseProduct(ws.yd));
  if (coriolis) {
    ws.fx.noalias() = ws.jx * qdd;
    ws.fx += ws.ax;
    ws.fy.noalias() = ws.jy * qdd;
    ws.fy += ws.ay;
    rate += c * w.dot(ws.x.cwiseProduct(ws.fy) - ws.y.cwiseProduct(ws.fx));
  }
  return rate;
}

double ExtensibleBeam::dissipation(const Eigen::Ref<const Eigen::VectorXd>& qd) const {
  return damped() ? detail::quadratic_form(damping, qd) : 0.0;
}

double ExtensibleBeam::tip_excursion_bound(const Eigen::Ref<const Eigen::VectorXd>&, const Eigen::Ref<const Eigen::VectorXd>&,
                                           BeamWorkspace&) const {
  return INFINITY;
}

void ExtensibleBeam::rest_state(Eigen::Ref<Eigen::VectorXd> q) const {
  q.setZero();
  q[n] = rest_stretch;
}

ExtensibleBeam make_extensible(const BeamParameters& p, double theta0_rad) {
  BeamParameters inextensible = p;
  inextensible.axial = BeamAxial::inextensible;
  ExtensibleBeam b;
  static_cast<BeamConstants&>(b) = beam_constants(p, theta0_rad, max_modes(p.theory));
  b.theory = p.theory;
  b.inextensible = make_beam_model(inextensible, theta0_rad);
  b.grid = make_elastica(inextensible, theta0_rad);
  const int n = b.n, nodes = b.grid.nodes();
  const double L = b.length;
  b.axial_stiffness = p.youngs_modulus_pa * M_PI * p.diameter_m * p.diameter_m / 4.0 / L;
  const double w2 = b.centrifugal ? b.omega * b.omega : 0.0;
  const double k_axial = b.axial_stiffness - b.mass * w2 / 3.0;
  if (!(k_axial > 0.0))
    throw std::invalid_argument("the centrifugal load overcomes the filament's axial stiffness (m omega^2/3 >= EA/L): "
                                "no steady stretch exists at this speed");
  // The straight filament turning steadily: (EA/L − mω²/3) a = mω²(r_h/2 + L/3).
  b.rest_stretch = b.mass * w2 * (0.5 * b.hub_radius + L / 3.0) / k_axial;

  const ModalBasis& basis = *b.grid.basis;
  b.shape_nodes.resize(nodes, n);
  b.curvature_nodes.resize(nodes, n);
  std::vector<double> s(static_cast<std::size_t>(n)), d2s(static_cast<std::size_t>(n));
  for (int m = 0; m < nodes; ++m) {
    basis.evaluate(b.grid.node_xi[m], s.data(), nullptr, d2s.data());
    for (int i = 0; i < n; ++i) {
      b.shape_nodes(m, i) = s[static_cast<std::size_t>(i)];
      b.curvature_nodes(m, i) = d2s[static_cast<std::size_t>(i)];
    }
  }
  basis.evaluate(1.0, s.data(), nullptr, nullptr);
  b.s_tip = Eigen::Map<const Eigen::VectorXd>(s.data(), n);

  // The linearisation about the straight filament: block-diagonal, the bending block the
  // inextensible theory's, the stretch's M = ρA L∫ξ² dξ = m/3 and K = EA/L − mω²/3.
  const Linearization bend = b.inextensible->linearization();
  b.linear.mass = Eigen::MatrixXd::Zero(n + 1, n + 1);
  b.linear.stiffness = Eigen::MatrixXd::Zero(n + 1, n + 1);
  b.linear.damping = Eigen::MatrixXd::Zero(n + 1, n + 1);
  b.linear.mass.topLeftCorner(n, n) = bend.mass;
  b.linear.stiffness.topLeftCorner(n, n) = bend.stiffness;
  b.linear.damping.topLeftCorner(n, n) = bend.damping;
  b.linear.mass(n, n) = b.mass / 3.0;
  b.linear.stiffness(n, n) = k_axial;
  // Modal damping: the bending modes as the inextensible theory damps them; the stretch's mode with a
  // single beam.damping_ratio (a list names the bending modes only).
  if (p.damping_ratio.size() == 1) b.linear.damping(n, n) = 2.0 * p.damping_ratio[0] * std::sqrt(k_axial * b.mass / 3.0);
  if (!p.damping_ratio.empty()) b.damping = b.linear.damping;
  return b;
}

}  // namespace rotbeam
