#include "reference_beam.hpp"

#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <random>

namespace rotbeam::testing {

namespace {
using Gauss30 = boost::math::quadrature::gauss<double, 30>;

// Composite 30-point Gauss–Legendre nodes/weights on [a, b] with `panels` panels.
void gauss_nodes(double a, double b, int panels, std::vector<double>& x, std::vector<double>& w) {
  x.clear();
  w.clear();
  const auto& absc = Gauss30::abscissa();
  const auto& wts = Gauss30::weights();
  const double width = (b - a) / panels;
  for (int p = 0; p < panels; ++p) {
    const double mid = a + (p + 0.5) * width, half = 0.5 * width;
    for (std::size_t k = 0; k < absc.size(); ++k) {
      const double sgns[2] = {1.0, -1.0};
      for (double sg : sgns) {
        if (sg < 0 && absc[k] == 0.0) continue;
        x.push_back(mid + sg * half * absc[k]);
        w.push_back(half * wts[k]);
      }
    }
  }
}
}  // namespace

ReferenceBeam::ReferenceBeam(const ForeshorteningBeam& model, int panels) : model_(model) {
  const int n = model.n;
  const ModalBasis& basis = model.integrals->basis;
  gauss_nodes(0.0, 1.0, panels, xi_, w_);
  std::vector<double> xin, win;
  Eigen::VectorXd s(n), ds(n), d2s(n);
  for (double xi : xi_) {
    basis.evaluate(xi, s.data(), ds.data(), d2s.data());
    s_.push_back(s);
    d2s_.push_back(d2s);
    p_.push_back(d2s * ds.transpose() + ds * d2s.transpose());
    Eigen::MatrixXd isp = Eigen::MatrixXd::Zero(n, n);
    gauss_nodes(0.0, xi, std::max(1, static_cast<int>(std::ceil(xi * panels))), xin, win);
    for (std::size_t k = 0; k < xin.size(); ++k) {
      basis.evaluate(xin[k], nullptr, ds.data(), nullptr);
      isp += win[k] * ds * ds.transpose();
    }
    isp_.push_back(isp);
  }
}

double ReferenceBeam::t0(const Eigen::VectorXd& q) const {
  const double L = model_.length;
  double sum = 0.0;
  for (std::size_t g = 0; g < xi_.size(); ++g) {
    const double x = model_.hub_radius + xi_[g] * L - q.dot(isp_[g] * q) / (2.0 * L);
    const double y = s_[g].dot(q);
    sum += w_[g] * (x * x + y * y);
  }
  return 0.5 * model_.omega * model_.omega * model_.mass * sum;
}

double ReferenceBeam::t1(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  const double L = model_.length;
  double sum = 0.0;
  for (std::size_t g = 0; g < xi_.size(); ++g) {
    const double x = model_.hub_radius + xi_[g] * L - q.dot(isp_[g] * q) / (2.0 * L);
    const double y = s_[g].dot(q);
    const double xd = -q.dot(isp_[g] * v) / L, yd = s_[g].dot(v);
    sum += w_[g] * (x * yd - y * xd);
  }
  return model_.omega * model_.mass * sum;
}

double ReferenceBeam::t2(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  const double L = model_.length;
  double sum = 0.0;
  for (std::size_t g = 0; g < xi_.size(); ++g) {
    const double xd = -q.dot(isp_[g] * v) / L, yd = s_[g].dot(v);
    sum += w_[g] * (xd * xd + yd * yd);
  }
  return 0.5 * model_.mass * sum;
}

double ReferenceBeam::potential(const Eigen::VectorXd& q) const {
  const double L = model_.length;
  double sum = 0.0;
  for (std::size_t g = 0; g < xi_.size(); ++g) {
    const double x2 = -q.dot(p_[g] * q) / (2.0 * L);  // x'' = −qᵀ P q/(2L)
    const double y2 = d2s_[g].dot(q);
    sum += w_[g] * (x2 * x2 + y2 * y2);
  }
  return 0.5 * model_.bending_stiffness / (L * L * L) * sum;
}

double ReferenceBeam::angular_momentum(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  const double w = model_.omega;
  return (2.0 * t0(q) / (w * w)) * w + t1(q, v) / w;
}

ReferenceElastica::ReferenceElastica(const ElasticaBeam& model, int panels) : model_(model) {
  const int n = model.n;
  const ModalBasis basis(n);
  gauss_nodes(0.0, 1.0, panels, xi_, w_);
  Eigen::VectorXd ds(n), d2s(n);
  std::vector<double> xin, win;
  for (double xi : xi_) {
    basis.evaluate(xi, nullptr, nullptr, d2s.data());
    d2s_.push_back(d2s);
    gauss_nodes(0.0, xi, std::max(1, static_cast<int>(std::ceil(xi * panels))), xin, win);
    std::vector<Eigen::VectorXd> slopes;
    for (double x : xin) {
      basis.evaluate(x, nullptr, ds.data(), nullptr);
      slopes.push_back(ds);
    }
    inner_w_.push_back(win);
    inner_ds_.push_back(std::move(slopes));
  }
  gauss_nodes(0.0, 1.0, panels, xin, tip_w_);
  for (double x : xin) {
    basis.evaluate(x, nullptr, ds.data(), nullptr);
    tip_ds_.push_back(ds);
  }
}

void ReferenceElastica::point(std::size_t g, const Eigen::VectorXd& q, const Eigen::VectorXd* v, double& x, double& y,
                              double& xd, double& yd) const {
  const double L = model_.length;
  double c = 0, s = 0, vc = 0, vs = 0;
  for (std::size_t k = 0; k < inner_w_[g].size(); ++k) {
    const double phi = inner_ds_[g][k].dot(q) / L;
    const double rate = v ? inner_ds_[g][k].dot(*v) / L : 0.0;
    c += inner_w_[g][k] * std::cos(phi);
    s += inner_w_[g][k] * std::sin(phi);
    vc += inner_w_[g][k] * std::cos(phi) * rate;
    vs += inner_w_[g][k] * std::sin(phi) * rate;
  }
  x = model_.hub_radius + L * c;
  y = L * s;
  xd = -L * vs;
  yd = L * vc;
}

double ReferenceElastica::t0(const Eigen::VectorXd& q) const {
  if (!model_.centrifugal) return 0.0;
  double sum = 0.0, x, y, xd, yd;
  for (std::size_t g = 0; g < xi_.size(); ++g) {
    point(g, q, nullptr, x, y, xd, yd);
    sum += w_[g] * (x * x + y * y);
  }
  return 0.5 * model_.omega * model_.omega * model_.mass * sum;
}

double ReferenceElastica::t1(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  if (!model_.coriolis) return 0.0;
  double sum = 0.0, x, y, xd, yd;
  for (std::size_t g = 0; g < xi_.size(); ++g) {
    point(g, q, &v, x, y, xd, yd);
    sum += w_[g] * (x * yd - y * xd);
  }
  return model_.omega * model_.mass * sum;
}

double ReferenceElastica::t2(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  double sum = 0.0, x, y, xd, yd;
  for (std::size_t g = 0; g < xi_.size(); ++g) {
    point(g, q, &v, x, y, xd, yd);
    sum += w_[g] * (xd * xd + yd * yd);
  }
  return 0.5 * model_.mass * sum;
}

double ReferenceElastica::potential(const Eigen::VectorXd& q) const {
  const double L = model_.length;
  double sum = 0.0;
  for (std::size_t g = 0; g < xi_.size(); ++g) {
    const double curvature = d2s_[g].dot(q);  // L² φ'
    sum += w_[g] * curvature * curvature;
  }
  return 0.5 * model_.bending_stiffness / (L * L * L) * sum;
}

Eigen::Vector2d ReferenceElastica::tip(const Eigen::VectorXd& q) const {
  const double L = model_.length;
  double c = 0, s = 0;
  for (std::size_t k = 0; k < tip_w_.size(); ++k) {
    const double phi = tip_ds_[k].dot(q) / L;
    c += tip_w_[k] * std::cos(phi);
    s += tip_w_[k] * std::sin(phi);
  }
  return {model_.hub_radius + L * c, L * s};
}

void random_state(const ForeshorteningBeam& model, unsigned seed, double tip_deflection_m, double speed, Eigen::VectorXd& q,
                  Eigen::VectorXd& v) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = model.n;
  q.resize(n);
  v.resize(n);
  for (int i = 0; i < n; ++i) {
    const double decay = 1.0 / ((i + 1.0) * (i + 1.0));
    q[i] = u(rng) * decay;
    v[i] = speed * u(rng) / (i + 1.0);
  }
  const double tip = std::abs(model.integrals->s_tip.dot(q));
  q *= tip_deflection_m / tip;
}

}  // namespace rotbeam::testing
