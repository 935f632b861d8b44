#include "rotbeam/foreshortening_beam.hpp"
#include "rotbeam/units.hpp"

#include "rotbeam/dynamics.hpp"
#include "rotbeam/energy.hpp"
#include "rotbeam/modal_analysis.hpp"
#include "rotbeam/quadrature.hpp"
#include "rotbeam/detail/quadratic_form.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace rotbeam {

namespace {
// The workspace a ForeshorteningBeam evaluates into is always one it made (make_workspace).
ForeshorteningWorkspace& own(BeamWorkspace& ws) {
  assert(dynamic_cast<ForeshorteningWorkspace*>(&ws) != nullptr);
  return static_cast<ForeshorteningWorkspace&>(ws);
}
}  // namespace

std::unique_ptr<BeamWorkspace> ForeshorteningBeam::make_workspace() const {
  return std::make_unique<ForeshorteningWorkspace>(n);
}

void ForeshorteningBeam::evaluate_mass(const Eigen::Ref<const Eigen::VectorXd>& q, BeamWorkspace& ws) const {
  rotbeam::evaluate_mass(*this, q, own(ws));
  ws.mass_llt.compute(ws.mass);
}

void ForeshorteningBeam::evaluate_dynamics(const Eigen::Ref<const Eigen::VectorXd>& q,
                                           const Eigen::Ref<const Eigen::VectorXd>& qd, BeamWorkspace& ws) const {
  rotbeam::evaluate_dynamics(*this, q, qd, own(ws));
}

void ForeshorteningBeam::tip(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                             HubFrameTip& out) const {
  const ModalIntegrals& mi = *integrals;
  const double L = length;
  out.dx_dq.noalias() = mi.isp_tip * q;  // ISP(1) q, scaled below
  out.x = hub_radius + L - q.dot(out.dx_dq) / (2.0 * L);
  out.xd = -qd.dot(out.dx_dq) / L;
  out.dx_dq *= -1.0 / L;
  out.y = mi.s_tip.dot(q);
  out.yd = mi.s_tip.dot(qd);
  out.dy_dq = mi.s_tip;
  out.x_quadratic = -detail::quadratic_form(mi.isp_tip, qd) / L;
  out.y_quadratic = 0.0;
}

Eigen::Vector2d ForeshorteningBeam::tip_position(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  const ModalIntegrals& mi = *integrals;
  return {hub_radius + length - detail::quadratic_form(mi.isp_tip, q) / (2.0 * length), mi.s_tip.dot(q)};
}

void ForeshorteningBeam::shape(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& xi,
                               Eigen::Ref<Eigen::MatrixXd> positions) const {
  if (positions.rows() != xi.size() || positions.cols() != 2)
    throw std::invalid_argument("shape: positions must be " + std::to_string(xi.size()) + " x 2");
  const ModalBasis& basis = integrals->basis;
  const QuadratureRule& gauss = gauss_legendre_reference(8);
  const double max_panel = 1.0 / (n + 2);
  std::vector<double> s(n), ds(n);
  const auto slope = [&](double eta) {  // Σ q_i S_i'(η)
    basis.evaluate(eta, nullptr, ds.data(), nullptr);
    double v = 0.0;
    for (int i = 0; i < n; ++i) v += q[i] * ds[i];
    return v;
  };
  double at = 0.0, integral = 0.0;  // ∫₀^at (Σ q_i S_i')² dη
  for (Eigen::Index k = 0; k < xi.size(); ++k) {
    if (!(xi[k] >= at && xi[k] <= 1.0))
      throw std::invalid_argument("shape: the points ξ must ascend within [0, 1] (ξ = " + std::to_string(xi[k]) + ")");
    const int panels = static_cast<int>(std::ceil((xi[k] - at) / max_panel));
    for (int p = 0; p < panels; ++p) {
      const double a = at + (xi[k] - at) * p / panels, b = at + (xi[k] - at) * (p + 1) / panels;
      for (std::size_t g = 0; g < gauss.nodes.size(); ++g) {
        const double v = slope(0.5 * (a + b) + 0.5 * (b - a) * gauss.nodes[g]);
        integral += 0.5 * (b - a) * gauss.weights[g] * v * v;
      }
    }
    at = xi[k];
    basis.evaluate(at, s.data(), nullptr, nullptr);
    double y = 0.0;
    for (int i = 0; i < n; ++i) y += q[i] * s[i];
    positions(k, 0) = hub_radius + at * length - integral / (2.0 * length);
    positions(k, 1) = y;
  }
}

double ForeshorteningBeam::tip_deflection(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  return std::abs(integrals->s_tip.dot(q));
}

EnergyTerms ForeshorteningBeam::energy(const Eigen::Ref<const Eigen::VectorXd>& q,
                                       const Eigen::Ref<const Eigen::VectorXd>& qd, BeamWorkspace& ws) const {
  return evaluate_energy(*this, q, qd, own(ws));
}

double ForeshorteningBeam::angular_momentum_rate(const Eigen::Ref<const Eigen::VectorXd>& q,
                                                 const Eigen::Ref<const Eigen::VectorXd>& qd,
                                                 const Eigen::Ref<const Eigen::VectorXd>& qdd, BeamWorkspace& ws) const {
  return rotbeam::angular_momentum_rate(*this, q, qd, qdd, own(ws));
}

double ForeshorteningBeam::dissipation(const Eigen::Ref<const Eigen::VectorXd>& qd) const {
  return damped() ? detail::quadratic_form(damping, qd) : 0.0;
}

bool ForeshorteningBeam::free_flight_jacobian(const Eigen::Ref<const Eigen::VectorXd>& q,
                                              const Eigen::Ref<const Eigen::VectorXd>& qd, BeamWorkspace& ws,
                                              Eigen::Ref<Eigen::VectorXd> qdd, Eigen::Ref<Eigen::MatrixXd> jq,
                                              Eigen::Ref<Eigen::MatrixXd> jqd) const {
  rotbeam::free_flight_jacobian(*this, q, qd, own(ws), qdd, jq, jqd);
  return true;
}

Linearization ForeshorteningBeam::linearization() const {
  Linearization lin;
  lin.mass = mass * Eigen::MatrixXd::Identity(n, n);
  lin.stiffness = linear_stiffness(*this);
  lin.damping = damped() ? damping : Eigen::MatrixXd::Zero(n, n);
  return lin;
}

double ForeshorteningBeam::tip_excursion_bound(const Eigen::Ref<const Eigen::VectorXd>& q,
                                               const Eigen::Ref<const Eigen::VectorXd>& qd, BeamWorkspace& ws) const {
  if (!excursion_valid) return INFINITY;
  const double h = energy(q, qd, ws).jacobi;
  const double big_h = std::max(h - excursion_v0, 0.0);
  const double w2 = centrifugal ? omega * omega : 0.0;
  const double beta = w2 * mass * excursion_mu * excursion_mu / (2.0 * length * length);
  const double e_now = 0.5 * detail::quadratic_form(linear_stiffness_, q);
  if (4.0 * beta * big_h >= 1.0 || 2.0 * beta * e_now > 1.0) return INFINITY;
  const double e1 = 2.0 * big_h / (1.0 + std::sqrt(1.0 - 4.0 * beta * big_h));
  const double y = std::sqrt(2.0 * e1 * excursion_tip_compliance);
  const double x = excursion_mu * e1 / length;
  return std::hypot(x, y);
}

ForeshorteningBeam make_beam(const BeamParameters& p, double theta0_rad) {
  ForeshorteningBeam m;
  static_cast<BeamConstants&>(m) = beam_constants(p, theta0_rad, kMaxModes);
  m.integrals = modal_integrals(p.modes);
  m.linear_stiffness_ = linear_stiffness(m);
  m.damping = modal_damping_matrix(m.mass * Eigen::MatrixXd::Identity(m.n, m.n), m.linear_stiffness_, p.damping_ratio);
  // The excursion bound's constants (tip_excursion_bound).
  const Eigen::LLT<Eigen::MatrixXd> k_llt(m.linear_stiffness_);
  if (k_llt.info() == Eigen::Success) {
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> g(m.integrals->isp_tip, m.linear_stiffness_);
    if (g.info() == Eigen::Success) {
      m.excursion_valid = true;
      m.excursion_mu = std::max(g.eigenvalues().maxCoeff(), 0.0);
      m.excursion_tip_compliance = m.integrals->s_tip.dot(k_llt.solve(m.integrals->s_tip));
      const double rh = m.hub_radius, L = m.length;
      m.excursion_v0 = -0.5 * (m.centrifugal ? m.omega * m.omega : 0.0) * m.mass * (rh * rh + rh * L + L * L / 3.0);
    }
  }
  return m;
}

}  // namespace rotbeam
