#include "rotbeam/impact.hpp"
#include "rotbeam/rigid_contact.hpp"

#include "rotbeam/detail/quadratic_form.hpp"
#include "rotbeam/surface.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rotbeam {

double restitution(const ImpactLaw& law, double normal_speed, double full_speed) {
  if (normal_speed < law.plastic_below_m_s) return 0.0;
  double e = law.constant;
  if (law.model == RestitutionModel::yigit) {
    const double v = law.speed == RestitutionSpeed::normal ? normal_speed : full_speed;
    e = 0.501 * std::pow(v, -0.25);
  }
  return std::min(e, law.cap);
}

double linear_sliding_load(double p, double v0, double v1) {
  const double a0 = std::abs(v0), a1 = std::abs(v1);
  if (v0 * v1 >= 0.0) return 0.5 * p * (a0 + a1);
  return 0.5 * p * (a0 * a0 + a1 * a1) / (a0 + a1);
}

namespace {

// The normal and tangential impulses of a planar impact with Coulomb friction and an energetic
// coefficient of restitution e (Stronge's method), for approach speed vn0 > 0 and slip vt0.
struct CoulombImpulse {
  double p = 0;            // normal impulse magnitude (pushing the tip out of the surface) [N s]
  double pt = 0;           // tangential impulse along the tangent [N s]
  double slip_work = 0;    // ∫ V_t dP_t (≤ 0) [J]
  double normal_work = 0;  // ∫ Ċ dp over compression and restitution, (1 − e²) times the compression's [J]
  double sliding_load = 0; // ∫ |V_t| dp [N m] (V_t keeps its sign within a segment)
  bool jammed = false;
};

CoulombImpulse coulomb_impulse(double ann, double ant, double att, double mu, double e, double vn0, double vt0) {
  CoulombImpulse r;
  // Velocities below this count as zero slip (as in the slip decision, far below any physical slip).
  const double v_tol = 1e-12 * (std::abs(vn0) + std::abs(vt0));
  double vn = vn0, vt = vt0, w_compression = 0.0, w_restitution = 0.0;
  bool compressing = true;
  for (int segment = 0; segment < 16; ++segment) {
    double dvn, dvt, dpt;  // per unit normal impulse
    if (std::abs(vt) > v_tol) {
      const double s = vt > 0 ? 1.0 : -1.0;
      dvn = -(ann + mu * s * ant), dvt = -(ant + mu * s * att), dpt = -mu * s;
    } else if (std::abs(ant) <= mu * att) {
      vt = 0.0;
      dvn = -(ann - ant * ant / att), dvt = 0.0, dpt = ant / att;
    } else {
      const double s = ant > 0 ? -1.0 : 1.0;
      dvn = -(ann + mu * s * ant), dvt = -(ant + mu * s * att), dpt = -mu * s;
    }
    // The segment ends where V_t reaches 0 (sliding toward it), where compression ends, or where the
    // restitution work reaches −e² times the compression work.
    double dp = INFINITY;
    if (dvt != 0.0 && std::abs(vt) > v_tol && vt * dvt < 0.0) dp = -vt / dvt;
    bool ends = false;
    if (compressing) {
      if (dvn < 0.0 && -vn / dvn <= dp) dp = -vn / dvn, ends = false;
    } else {
      // ∫ Ċ dp over the segment = vn Δ + ½ dvn Δ² (vn ≤ 0 here); the smallest Δ ≥ 0 that brings the
      // restitution work to its target (≤ 0), or, where it cannot, the Δ at which Ċ returns to 0.
      const double target = -e * e * w_compression - w_restitution;
      double delta = INFINITY;
      if (std::abs(dvn) <= 1e-300) {
        if (vn < 0.0) delta = target / vn;
      } else {
        const double disc = vn * vn + 2.0 * dvn * target;
        if (disc < 0.0) {
          delta = -vn / dvn;
        } else {
          const double r1 = (-vn - std::sqrt(disc)) / dvn, r2 = (-vn + std::sqrt(disc)) / dvn;
          delta = std::min(r1 >= 0.0 ? r1 : INFINITY, r2 >= 0.0 ? r2 : INFINITY);
        }
      }
      if (delta <= dp) dp = delta, ends = true;
    }
    if (!std::isfinite(dp)) {
      r.jammed = true;
      return r;
    }
    dp = std::max(dp, 0.0);
    const double work = vn * dp + 0.5 * dvn * dp * dp;
    (compressing ? w_compression : w_restitution) += work;
    r.slip_work += dpt * (vt * dp + 0.5 * dvt * dp * dp);
    r.sliding_load += std::abs(vt * dp + 0.5 * dvt * dp * dp);
    r.p += dp;
    r.pt += dpt * dp;
    vn += dvn * dp;
    vt += dvt * dp;
    if (compressing && std::abs(vn) <= v_tol) {
      vn = 0.0;
      compressing = false;
      if (e == 0.0) ends = true;
    }
    if (ends) {
      r.normal_work = w_compression + w_restitution;
      return r;
    }
  }
  r.jammed = true;
  return r;
}

}  // namespace

namespace {

// What apply_impact and apply_tangential_impact share after the impulse (p normal as P along ∇C,
// pt tangential) was applied to qd: the velocities after, the impulse on the tip, its works.
void finish_impact(const BeamModel& beam, const Surface& surface, double t, const Eigen::Ref<const Eigen::VectorXd>& q,
                   const Eigen::Ref<const Eigen::VectorXd>& qd, BeamWorkspace& ws, TipKinematics& tip, double p, double pt,
                   bool coulomb, double coulomb_work, double v_before_x, double v_before_y, double t2_before,
                   const CoulombImpulse* segments, ImpactResult& r) {
  tip_kinematics(beam, surface, t, q, qd, tip);
  r.vx_after = tip.gap_rate;
  r.vy_after = tip.slip_speed;
  r.impulse = p;
  r.tangential_impulse = pt;
  r.impulse_x = p * tip.normal_x + pt * tip.tangent_x;
  r.impulse_y = p * tip.normal_y + pt * tip.tangent_y;
  // The tip velocity changes linearly with a fixed-direction impulse, so the impulse's work on the tip is
  // P·(V⁻ + V⁺)/2 in the inertial frame; for a surface at rest and no friction it equals
  // −½(1 − e²)(Ċ⁻)²/a. A Coulomb impulse turns as the tip slides, sticks or reverses: its work is
  // summed over the segments, −∫Ċ dp + ∫V_t dP_t (+ P·V_s for a moving surface).
  r.surface_work = r.impulse_x * tip.surface_vx + r.impulse_y * tip.surface_vy;
  if (coulomb)
    r.contact_work = coulomb_work + r.surface_work;
  else
    r.contact_work = 0.5 * (r.impulse_x * (v_before_x + tip.VX) + r.impulse_y * (v_before_y + tip.VY));
  r.delta_t2 = 0.5 * detail::quadratic_form(ws.mass, qd) - t2_before;
  // The heat and the load–distance: exact over a Coulomb impulse's segments (V_t is linear in p within
  // each and keeps its sign); without friction V_t changes linearly with p over the whole impulse.
  if (segments) {
    r.frictional_heat = -segments->slip_work;
    r.sliding_load = segments->sliding_load;
  } else {
    r.frictional_heat = 0.0;
    r.sliding_load = linear_sliding_load(std::abs(p), r.vy_before, r.vy_after);
  }
}

}  // namespace

ImpactResult apply_impact(const BeamModel& beam, const Surface& surface, const ImpactLaw& law, double t,
                          const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> qd,
                          BeamWorkspace& ws, TipKinematics& tip, double mu) {
  tip_kinematics(beam, surface, t, q, qd, tip);
  const double vx = tip.gap_rate;
  if (!(vx > 0.0))
    throw std::domain_error("impact requested for a tip that is not approaching the surface (V_X = " +
                            std::to_string(vx) + " m/s)");
  ImpactResult r;
  r.vx_before = vx;
  r.vy_before = tip.slip_speed;
  const double v_before_x = tip.VX, v_before_y = tip.VY;
  beam.evaluate_mass(q, ws);
  Eigen::VectorXd& minv_grad = ws.scratch;
  minv_grad = tip.grad_gap;
  ws.mass_llt.solveInPlace(minv_grad);
  const double a = tip.grad_gap.dot(minv_grad);
  const double e = restitution(law, vx, std::hypot(tip.VX - tip.surface_vx, tip.VY - tip.surface_vy));
  const double t2_before = 0.5 * detail::quadratic_form(ws.mass, qd);
  double p = -(1.0 + e) * vx / a, pt = 0.0, coulomb_work = 0.0;
  bool coulomb = law.friction == ImpactFriction::coulomb && mu > 0.0;
  CoulombImpulse c;
  Eigen::VectorXd& minv_t = ws.scratch2;
  double ant = 0.0, att = 0.0;
  if (coulomb) {
    minv_t = tip.grad_tangent;
    ws.mass_llt.solveInPlace(minv_t);
    ant = tip.grad_gap.dot(minv_t);
    att = tip.grad_tangent.dot(minv_t);
    // ∇C ∥ ∂V_t/∂q̇ (the straight beam on the plane): normal and tangential impulses move the tip along
    // one line, friction has no motion of its own to act on, and the frictionless law decides (as the
    // locked-tip analysis does, rigid_contact.cpp).
    coulomb = a * att - ant * ant > 1e-12 * a * att;
  }
  if (coulomb) {
    c = coulomb_impulse(a, ant, att, mu, e, vx, tip.slip_speed);
    if (c.jammed) {
      r.jammed = true;
      tip_kinematics(beam, surface, t, q, qd, tip);
      return r;
    }
    p = -c.p;
    pt = c.pt;
    coulomb_work = -c.normal_work + c.slip_work;
    qd += p * minv_grad + pt * minv_t;
  } else {
    qd += p * minv_grad;
  }
  r.restitution = e;
  r.effective_inverse_mass = a;
  r.relative_energy_loss = coulomb ? -coulomb_work : 0.5 * (1.0 - e * e) * vx * vx / a;
  finish_impact(beam, surface, t, q, qd, ws, tip, p, pt, coulomb, coulomb_work, v_before_x, v_before_y, t2_before,
                coulomb ? &c : nullptr, r);
  return r;
}

ImpactResult apply_tangential_impact(const BeamModel& beam, const Surface& surface, double t,
                                     const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> qd,
                                     BeamWorkspace& ws, TipKinematics& tip, double mu) {
  tip_kinematics(beam, surface, t, q, qd, tip);
  ImpactResult r;
  r.tangential = true;
  r.vx_before = tip.gap_rate;
  r.vy_before = tip.slip_speed;
  const double v_before_x = tip.VX, v_before_y = tip.VY;
  beam.evaluate_mass(q, ws);
  const ContactMobility m = contact_mobility(tip, ws);
  const Eigen::VectorXd& minv_grad = ws.scratch;
  const Eigen::VectorXd& minv_t = ws.scratch2;
  const double a = m.nn, ant = m.nt, att = m.tt;
  r.effective_inverse_mass = a;
  const CoulombImpulse c = mu > 0.0 && a * att - ant * ant > 1e-12 * a * att
                               ? coulomb_impulse(a, ant, att, mu, 0.0, std::max(r.vx_before, 0.0), tip.slip_speed)
                               : CoulombImpulse{0, 0, 0, 0, true};
  if (c.jammed) {
    r.jammed = true;
    return r;
  }
  const double t2_before = 0.5 * detail::quadratic_form(ws.mass, qd);
  const double coulomb_work = -c.normal_work + c.slip_work;
  qd += -c.p * minv_grad + c.pt * minv_t;
  r.restitution = 0.0;
  r.relative_energy_loss = -coulomb_work;
  finish_impact(beam, surface, t, q, qd, ws, tip, -c.p, c.pt, true, coulomb_work, v_before_x, v_before_y, t2_before, &c,
                r);
  return r;
}

}  // namespace rotbeam
