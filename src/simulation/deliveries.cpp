#include "deliveries.hpp"

#include <cmath>

namespace rotbeam {

void Deliveries::start(double, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  last_h_ = ledger_.angular_momentum(q, qd);
}

void Deliveries::step(const StepView& v) {
  const double h = ledger_.angular_momentum(v.q, v.qd);
  MomentumDelivery d;
  d.from_deg = ctx_.relative_angle_deg(v.t0);
  d.span_deg = ctx_.omega() * (v.t - v.t0) * 180.0 / M_PI;
  d.hub_angular_impulse_n_m_s = h - last_h_;
  if (v.phase != Phase::free) {
    d.normal_n_s = v.integrals.integral[LedgerTerm::normal_impulse];
    d.tangential_n_s = -v.integrals.integral[LedgerTerm::tangential_impulse];  // on the surface
    d.hub_angular_impulse_n_m_s -= v.integrals.integral[LedgerTerm::contact_moment];
    d.along_m = ctx_.tip_y(v.t, v.q);
  }
  last_h_ = h;
  ctx_.sink.delivery(d);
}

void Deliveries::impact(const ImpactView& v) {
  MomentumDelivery d;
  d.from_deg = ctx_.relative_angle_deg(v.t);
  d.normal_n_s = std::abs(v.result.impulse);
  d.tangential_n_s = -v.result.tangential_impulse;
  d.hub_angular_impulse_n_m_s = v.momentum_after - last_h_ - v.impulse_moment;
  d.along_m = ctx_.tip_y(v.t, v.q);
  d.impact = true;
  last_h_ = v.momentum_after;
  ctx_.sink.delivery(d);
}

}  // namespace rotbeam
