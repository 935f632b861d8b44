#include "rotbeam/kinematics.hpp"

#include "rotbeam/surface.hpp"

#include <cmath>

namespace rotbeam {

void tip_kinematics(const BeamModel& beam, const Surface& surface, double t, const Eigen::Ref<const Eigen::VectorXd>& q,
                    const Eigen::Ref<const Eigen::VectorXd>& qd, TipKinematics& k) {
  const HubMotion hub = beam.hub_motion();
  const double w = hub.omega;
  const double th = hub.theta(t), c = std::cos(th), s = std::sin(th);
  beam.tip(q, qd, k.hub);
  const HubFrameTip& r = k.hub;
  k.t = t;
  k.theta = th;
  k.X = r.x * c - r.y * s;
  k.Y = r.x * s + r.y * c;
  k.frame_vx = -w * k.Y;
  k.frame_vy = w * k.X;
  k.VX = r.xd * c - r.yd * s + k.frame_vx;
  k.VY = r.xd * s + r.yd * c + k.frame_vy;
  k.grad_x = c * r.dx_dq - s * r.dy_dq;
  k.grad_y = s * r.dx_dq + c * r.dy_dq;
  // R(θ)(r_quadratic + 2ω J ṙ − ω² r), J ṙ = (−ẏ, ẋ).
  const double bx = r.x_quadratic - 2.0 * w * r.yd - w * w * r.x;
  const double by = r.y_quadratic + 2.0 * w * r.xd - w * w * r.y;
  k.bias_ax = c * bx - s * by;
  k.bias_ay = s * bx + c * by;
  surface.contact_geometry(k);
}

Eigen::Vector2d tip_position(const BeamModel& beam, double t, const Eigen::Ref<const Eigen::VectorXd>& q) {
  const double th = beam.theta(t), c = std::cos(th), s = std::sin(th);
  const Eigen::Vector2d r = beam.tip_position(q);
  return {r.x() * c - r.y() * s, r.x() * s + r.y() * c};
}

double gap(const BeamModel& beam, const Surface& surface, double t, const Eigen::Ref<const Eigen::VectorXd>& q) {
  return surface.gap(tip_position(beam, t, q), t);
}

}  // namespace rotbeam
