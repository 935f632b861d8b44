#include "rotbeam/kinematics.hpp"

#include "rotbeam/detail/quadratic_form.hpp"

#include <cmath>

namespace rotbeam {

double gap(const Model& model, double t, const Eigen::Ref<const Eigen::VectorXd>& q) {
  const ModalIntegrals& mi = *model.integrals;
  const double th = model.theta(t);
  const double x = model.hub_radius + model.length - detail::quadratic_form(mi.isp_tip, q) / (2.0 * model.length);
  const double y = mi.s_tip.dot(q);
  return x * std::cos(th) - y * std::sin(th) - model.surface_distance;
}

void tip_kinematics(const Model& model, double t, const Eigen::Ref<const Eigen::VectorXd>& q,
                    const Eigen::Ref<const Eigen::VectorXd>& qd, TipKinematics& k) {
  const ModalIntegrals& mi = *model.integrals;
  const double L = model.length, w = model.omega;
  const double th = model.theta(t), c = std::cos(th), s = std::sin(th);
  // isp_q = ISP(1) q, kept in grad_y's storage until the end.
  Eigen::VectorXd& isp_q = k.grad_y;
  isp_q.noalias() = mi.isp_tip * q;
  const double q_isp_q = q.dot(isp_q), q_isp_v = qd.dot(isp_q);
  const double v_isp_v = detail::quadratic_form(mi.isp_tip, qd);
  const double s_v = mi.s_tip.dot(qd);
  k.theta = th;
  k.x = model.hub_radius + L - q_isp_q / (2.0 * L);
  k.y = mi.s_tip.dot(q);
  k.xd = -q_isp_v / L;
  k.yd = s_v;
  k.X = k.x * c - k.y * s;
  k.Y = k.x * s + k.y * c;
  k.VX = k.xd * c - k.yd * s - w * k.Y;
  k.VY = k.xd * s + k.yd * c + w * k.X;
  k.gap = k.X - model.surface_distance;
  k.gap_time_partial = -w * k.Y;
  k.grad_gap = -(c / L) * isp_q - s * mi.s_tip;
  k.gap_rate = k.grad_gap.dot(qd) + k.gap_time_partial;
  k.gamma = -(c / L) * v_isp_v + 2.0 * w * ((s / L) * q_isp_v - c * s_v) - w * w * k.X;
  k.gamma_y = -(s / L) * v_isp_v - 2.0 * w * ((c / L) * q_isp_v + s * s_v) - w * w * k.Y;
  k.grad_y = -(s / L) * isp_q + c * mi.s_tip;  // overwrites isp_q last
}

}  // namespace rotbeam
