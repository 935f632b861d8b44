#include "rotbeam/gap_field.hpp"

#include <cmath>

namespace rotbeam {

void fill_contact_geometry(const GapField& f, const SurfaceMotion& m, TipKinematics& k) {
  const Eigen::Vector2d& g = f.gradient;
  const double norm = g.norm();
  const Eigen::Vector2d n = g / norm, tangent(-n.y(), n.x());
  const Eigen::Vector2d v(k.VX, k.VY), bias(k.bias_ax, k.bias_ay);
  k.gap = f.value;
  k.grad_gap = g.x() * k.grad_x + g.y() * k.grad_y;
  k.gap_time_partial = g.x() * k.frame_vx + g.y() * k.frame_vy;
  k.gap_rate = g.dot(v);
  k.gamma = g.dot(bias) + v.dot(f.hessian * v);
  k.normal_x = n.x(), k.normal_y = n.y();
  k.tangent_x = tangent.x(), k.tangent_y = tangent.y();
  k.surface_vx = -m.spin * (k.Y - m.centre.y());
  k.surface_vy = m.spin * (k.X - m.centre.x());
  const Eigen::Vector2d relative(k.VX - k.surface_vx, k.VY - k.surface_vy);
  k.slip_speed = relative.dot(tangent);
  k.grad_tangent = tangent.x() * k.grad_x + tangent.y() * k.grad_y;
  k.gamma_tangent = tangent.dot(bias) - m.spin * v.dot(n) - relative.dot(n) * tangent.dot(f.hessian * v) / norm;
}

}  // namespace rotbeam
