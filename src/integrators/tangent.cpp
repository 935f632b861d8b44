#include "rotbeam/tangent.hpp"

#include "rotbeam/contact_law.hpp"
#include "rotbeam/impact.hpp"

#include <cmath>
#include <exception>

namespace rotbeam {

namespace {
// Central-difference steps relative to the filament's scales: q by 1e-6 L, q̇ by 1e-6 ωL, t by 1e-7
// of a revolution. q̈ is a polynomial of low degree in q̇ and a smooth rational function of q, so the
// truncation error (∝ step²) and the round-off (∝ ε/step) both stay near 1e-10 of the derivative.
constexpr double kRelativeStep = 1e-6;
constexpr double kTimeStepPerRevolution = 1e-7;
}  // namespace

TangentWorkspace::TangentWorkspace(const BeamModel& beam)
    : n(beam.modes()),
      ws(beam.make_workspace()),
      tip(beam.modes()),
      force(n),
      q(n),
      qd(n),
      a_plus(n),
      a_minus(n),
      qd_plus(n),
      qd_minus(n),
      jump(2 * n, 2 * n),
      jump_t(2 * n),
      grad_h(2 * n),
      f_minus(2 * n),
      f_plus(2 * n),
      saltation(2 * n, 2 * n),
      episode_jacobian(kEpisodeParameters, 2 * n),
      parameter_field(n, kEpisodeParameters) {
  const double L = beam.beam_length(), omega = std::abs(beam.hub_motion().omega);
  q_step = kRelativeStep * L;
  qd_step = kRelativeStep * L * (omega > 0.0 ? omega : 1.0);
}

void phase_acceleration(const System& system, Phase phase, const ContactEpisode& episode, double t,
                        const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                        TangentWorkspace& tw, Eigen::Ref<Eigen::VectorXd> qdd) {
  ++tw.field_evaluations;
  if (phase == Phase::free) {
    acceleration(system.beam, q, qd, nullptr, *tw.ws, qdd);
    return;
  }
  system.law.evaluate(system, episode, t, q, qd, *tw.ws, tw.tip, tw.force);
  qdd = tw.force - tw.ws->psi;
  tw.ws->mass_llt.solveInPlace(qdd);
}

void phase_jacobian(const System& system, Phase phase, const ContactEpisode& episode, double t,
                    const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                    TangentWorkspace& tw, Eigen::Ref<Eigen::MatrixXd> jq, Eigen::Ref<Eigen::MatrixXd> jqd) {
  const int n = tw.n;
  if (phase == Phase::free && tw.closed_form &&
      system.beam.free_flight_jacobian(q, qd, *tw.ws, tw.a_plus, jq, jqd)) {
    ++tw.closed_form_evaluations;
    return;
  }
  // A compliant force grows like δ^{3/2} from the surface, and its regularised friction turns over
  // within v_ε of V_t = 0: inside it the steps move the penetration δ and the slip speed V_t by at
  // most 1e-3 of themselves, so the differences stay on one side of δ = 0 and resolve both
  // curvatures (≈ 1e-6 relative error); round-off stays below 1e-9 of the entries.
  double h_q = tw.q_step, h_qd = tw.qd_step;
  if (phase != Phase::free && system.law.kind(phase) == PhaseKind::force) {
    tip_kinematics(system.beam, system.surface, t, q, qd, tw.tip);
    const double slope = tw.tip.grad_gap.norm();
    if (tw.tip.gap > 0.0 && slope > 0.0)
      h_q = std::min(h_q, std::max(1e-3 * tw.tip.gap / slope, 1e-6 * tw.q_step));
    const double v_slope = tw.tip.grad_tangent.norm();
    if (v_slope > 0.0) {
      const double omega = std::abs(system.beam.hub_motion().omega);
      const double v = std::max(1e-3 * std::abs(tw.tip.slip_speed), 1e-6 * tw.qd_step);
      const double r = std::min(1.0, v / (tw.qd_step * v_slope));
      h_qd *= r;
      h_q = std::min(h_q, std::max(v / std::max(omega * v_slope, 1e-300), 1e-6 * tw.q_step));
    }
  }
  tw.q = q;
  tw.qd = qd;
  // Column j of ∂q̈/∂x for x = q (moved) or q̇, from its value x0_j and the step h.
  const auto column = [&](Eigen::VectorXd& moved, double x0, int j, double h, auto&& out) {
    moved[j] = x0 + h;
    phase_acceleration(system, phase, episode, t, tw.q, tw.qd, tw, tw.a_plus);
    moved[j] = x0 - h;
    phase_acceleration(system, phase, episode, t, tw.q, tw.qd, tw, tw.a_minus);
    moved[j] = x0;
    out = (tw.a_plus - tw.a_minus) / (2.0 * h);
  };
  for (int j = 0; j < n; ++j) column(tw.q, q[j], j, h_q, jq.col(j));
  for (int j = 0; j < n; ++j) column(tw.qd, qd[j], j, h_qd, jqd.col(j));
}

namespace {

double root_function(const System& system, const EventSurface& surface, double t,
                     const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                     TangentWorkspace& tw) {
  if (surface.gap) return gap(system.beam, system.surface, t, q);
  return system.law.root_value(surface.phase, surface.root, system, surface.episode, t, q, qd, *tw.ws, tw.tip);
}

// q̇⁺ of the law's impact at (t, q, q̇⁻) into out; false where the law finds no impact there.
bool jump_velocity(const System& system, double t, const Eigen::Ref<const Eigen::VectorXd>& q,
                   const Eigen::Ref<const Eigen::VectorXd>& qd_minus, TangentWorkspace& tw,
                   Eigen::Ref<Eigen::VectorXd> out) {
  out = qd_minus;
  try {
    const ImpactResult r = system.law.momentum_jump(system, t, q, out, *tw.ws, tw.tip);
    return !r.jammed;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

bool saltation_matrix(const System& system, const EventSurface& surface, const EventSide& before,
                      const EventSide& after, bool impact, TangentWorkspace& tw) {
  const int n = tw.n;
  const double omega = std::abs(system.beam.hub_motion().omega);
  const double dt = kTimeStepPerRevolution * (omega > 0.0 ? 2.0 * M_PI / omega : 1e-2);
  const double t = before.t;

  // The fields on both sides.
  phase_acceleration(system, before.phase, before.episode, t, before.q, before.qd, tw, tw.a_minus);
  tw.f_minus << before.qd, tw.a_minus;
  phase_acceleration(system, after.phase, after.episode, after.t, after.q, after.qd, tw, tw.a_plus);
  tw.f_plus << after.qd, tw.a_plus;

  // ∇ₓh, and ḣ⁻ as the derivative of h along the flow before the event (so ∂h/∂t is in it).
  tw.q = before.q;
  tw.qd = before.qd;
  for (int j = 0; j < n; ++j) {
    tw.q[j] = before.q[j] + tw.q_step;
    const double hp = root_function(system, surface, t, tw.q, tw.qd, tw);
    tw.q[j] = before.q[j] - tw.q_step;
    const double hm = root_function(system, surface, t, tw.q, tw.qd, tw);
    tw.q[j] = before.q[j];
    tw.grad_h[j] = (hp - hm) / (2.0 * tw.q_step);
  }
  for (int j = 0; j < n; ++j) {
    if (surface.gap) {
      tw.grad_h[n + j] = 0.0;
      continue;
    }
    tw.qd[j] = before.qd[j] + tw.qd_step;
    const double hp = root_function(system, surface, t, tw.q, tw.qd, tw);
    tw.qd[j] = before.qd[j] - tw.qd_step;
    const double hm = root_function(system, surface, t, tw.q, tw.qd, tw);
    tw.qd[j] = before.qd[j];
    tw.grad_h[n + j] = (hp - hm) / (2.0 * tw.qd_step);
  }
  tw.q = before.q + dt * before.qd;
  tw.qd = before.qd + dt * tw.a_minus;
  const double h_ahead = root_function(system, surface, t + dt, tw.q, tw.qd, tw);
  tw.q = before.q - dt * before.qd;
  tw.qd = before.qd - dt * tw.a_minus;
  const double h_behind = root_function(system, surface, t - dt, tw.q, tw.qd, tw);
  const double h_rate = (h_ahead - h_behind) / (2.0 * dt);
  tw.h_rate = h_rate;
  if (!(std::abs(h_rate) > 0.0) || !std::isfinite(h_rate)) return false;

  // ∂g/∂x and ∂g/∂t of the impact (g = identity otherwise).
  tw.jump.setIdentity();
  tw.jump_t.setZero();
  if (impact) {
    tw.q = before.q;
    for (int j = 0; j < n; ++j) {
      tw.q[j] = before.q[j] + tw.q_step;
      if (!jump_velocity(system, t, tw.q, before.qd, tw, tw.qd_plus)) return false;
      tw.q[j] = before.q[j] - tw.q_step;
      if (!jump_velocity(system, t, tw.q, before.qd, tw, tw.qd_minus)) return false;
      tw.q[j] = before.q[j];
      tw.jump.block(n, j, n, 1) = (tw.qd_plus - tw.qd_minus) / (2.0 * tw.q_step);
    }
    tw.qd = before.qd;
    for (int j = 0; j < n; ++j) {
      tw.qd[j] = before.qd[j] + tw.qd_step;
      if (!jump_velocity(system, t, before.q, tw.qd, tw, tw.qd_plus)) return false;
      tw.qd[j] = before.qd[j] - tw.qd_step;
      if (!jump_velocity(system, t, before.q, tw.qd, tw, tw.qd_minus)) return false;
      tw.qd[j] = before.qd[j];
      tw.jump.block(n, n + j, n, 1) = (tw.qd_plus - tw.qd_minus) / (2.0 * tw.qd_step);
    }
    if (!jump_velocity(system, t + dt, before.q, before.qd, tw, tw.qd_plus)) return false;
    if (!jump_velocity(system, t - dt, before.q, before.qd, tw, tw.qd_minus)) return false;
    tw.jump_t.tail(n) = (tw.qd_plus - tw.qd_minus) / (2.0 * dt);
  }

  // S = ∂g/∂x + (f⁺ − ∂g/∂x f⁻ − ∂g/∂t) ∇ₓhᵀ / ḣ⁻ (f_minus is kept for episode_sensitivity).
  tw.f_plus.noalias() -= tw.jump * tw.f_minus;
  tw.f_plus -= tw.jump_t;
  tw.saltation = tw.jump;
  tw.saltation.noalias() += (tw.f_plus / h_rate) * tw.grad_h.transpose();
  return tw.saltation.allFinite();
}

bool episode_sensitivity(const System& system, const EventSide& before, TangentWorkspace& tw) {
  const int n = tw.n;
  ContactEpisode plus, minus;
  if (!system.law.episode_at_touch(system, before.t, before.q, before.qd, plus, tw.tip)) return false;
  const auto column = [&](int c, double h) {
    for (int k = 0; k < kEpisodeParameters; ++k)
      tw.episode_jacobian(k, c) = (plus.parameter[k] - minus.parameter[k]) / (2.0 * h);
  };
  tw.q = before.q;
  tw.qd = before.qd;
  for (int j = 0; j < n; ++j) {
    tw.q[j] = before.q[j] + tw.q_step;
    system.law.episode_at_touch(system, before.t, tw.q, tw.qd, plus, tw.tip);
    tw.q[j] = before.q[j] - tw.q_step;
    system.law.episode_at_touch(system, before.t, tw.q, tw.qd, minus, tw.tip);
    tw.q[j] = before.q[j];
    column(j, tw.q_step);
  }
  for (int j = 0; j < n; ++j) {
    tw.qd[j] = before.qd[j] + tw.qd_step;
    system.law.episode_at_touch(system, before.t, tw.q, tw.qd, plus, tw.tip);
    tw.qd[j] = before.qd[j] - tw.qd_step;
    system.law.episode_at_touch(system, before.t, tw.q, tw.qd, minus, tw.tip);
    tw.qd[j] = before.qd[j];
    column(n + j, tw.qd_step);
  }
  // The rate of p along the flow before the touch (tw.f_minus = (q̇⁻, q̈⁻) from saltation_matrix).
  const double omega = std::abs(system.beam.hub_motion().omega);
  const double dt = kTimeStepPerRevolution * (omega > 0.0 ? 2.0 * M_PI / omega : 1e-2);
  tw.q = before.q + dt * tw.f_minus.head(n);
  tw.qd = before.qd + dt * tw.f_minus.tail(n);
  system.law.episode_at_touch(system, before.t + dt, tw.q, tw.qd, plus, tw.tip);
  tw.q = before.q - dt * tw.f_minus.head(n);
  tw.qd = before.qd - dt * tw.f_minus.tail(n);
  system.law.episode_at_touch(system, before.t - dt, tw.q, tw.qd, minus, tw.tip);
  for (int k = 0; k < kEpisodeParameters; ++k) {
    const double rate = (plus.parameter[k] - minus.parameter[k]) / (2.0 * dt);
    tw.episode_jacobian.row(k) -= (rate / tw.h_rate) * tw.grad_h.transpose();
  }
  return tw.episode_jacobian.allFinite();
}

void parameter_field(const System& system, Phase phase, const ContactEpisode& episode, double t,
                     const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                     unsigned which, TangentWorkspace& tw) {
  ContactEpisode e = episode;
  for (int k = 0; k < kEpisodeParameters; ++k) {
    if (!(which & (1u << k))) {
      tw.parameter_field.col(k).setZero();
      continue;
    }
    const double p = episode.parameter[k];
    const double h = kRelativeStep * std::max(std::abs(p), 1e-12);
    e.parameter[k] = p + h;
    phase_acceleration(system, phase, e, t, q, qd, tw, tw.a_plus);
    e.parameter[k] = p - h;
    phase_acceleration(system, phase, e, t, q, qd, tw, tw.a_minus);
    e.parameter[k] = p;
    tw.parameter_field.col(k) = (tw.a_plus - tw.a_minus) / (2.0 * h);
  }
}

}  // namespace rotbeam
