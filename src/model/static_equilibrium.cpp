#include "rotbeam/static_equilibrium.hpp"

#include <Eigen/LU>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace rotbeam {

namespace {

struct Residual {
  const BeamModel& beam;
  std::unique_ptr<BeamWorkspace> ws;
  HubFrameTip tip;
  Eigen::VectorXd zero;
  explicit Residual(const BeamModel& b) : beam(b), ws(b.make_workspace()), tip(b.modes()), zero(Eigen::VectorXd::Zero(b.modes())) {}
  // R(q) = Ψ(q, 0) − P ∂y_t/∂q [N].
  void operator()(const Eigen::VectorXd& q, double load, Eigen::VectorXd& r) {
    beam.evaluate_dynamics(q, zero, *ws);
    beam.tip(q, zero, tip);
    r = ws->psi - load * tip.dy_dq;
  }
};

// Newton from q at `load`; true when converged (q updated, iterations added).
bool newton(Residual& res, double load, Eigen::VectorXd& q, int& iterations) {
  const int n = static_cast<int>(q.size());
  const double L = res.beam.beam_length();
  Eigen::VectorXd r(n), rp(n), trial(n), r_trial(n);
  Eigen::MatrixXd jac(n, n);
  res(q, load, r);
  double previous_step = INFINITY;
  for (int it = 0; it < 60; ++it) {
    ++iterations;
    for (int j = 0; j < n; ++j) {  // forward differences, step 1e-7 L: Newton's rate stays ~1e-7 per iteration
      const double h = 1e-7 * std::max(L, std::abs(q[j]));
      trial = q;
      trial[j] += h;
      res(trial, load, rp);
      jac.col(j) = (rp - r) / h;
    }
    const Eigen::VectorXd step = jac.partialPivLu().solve(-r);
    if (!step.allFinite()) return false;
    double scale = 1.0;
    const double r0 = r.norm();
    for (int k = 0; k < 40; ++k) {  // backtrack until the residual does not grow
      trial = q + scale * step;
      res(trial, load, r_trial);
      if (r_trial.allFinite() && r_trial.norm() <= r0 * (1.0 + 1e-12) + 1e-300) break;
      scale *= 0.5;
    }
    if (!r_trial.allFinite()) return false;
    q = trial;
    r = r_trial;
    // Converged: a full step below 1e-13 L, or below 1e-9 L and no longer shrinking (the round-off
    // floor of the residual, reached at high mode counts).
    const double size = step.lpNorm<Eigen::Infinity>();
    if (scale == 1.0 && (size <= 1e-13 * L || (size <= 1e-9 * L && size > 0.25 * previous_step))) return true;
    previous_step = scale == 1.0 ? size : INFINITY;
    if (scale < 1e-6) return false;
  }
  return false;
}

}  // namespace

StaticEquilibrium static_equilibrium(const BeamModel& beam, double tip_load_n, const StopToken* stop) {
  if (!std::isfinite(tip_load_n)) throw std::invalid_argument("the tip load must be finite");
  Residual res(beam);
  StaticEquilibrium out;
  const int n = beam.modes();
  out.q = Eigen::VectorXd::Zero(n);
  // The load scale: the tip load that would deflect the straight filament by L in the linear
  // theory, L/(∂y/∂qᵀ K⁻¹ ∂y/∂q) (3EI/L² for a cantilever at rest).
  const Linearization lin = beam.linearization();
  beam.tip(out.q, out.q, res.tip);
  const Eigen::LLT<Eigen::MatrixXd> k_llt(lin.stiffness);
  const double compliance = k_llt.info() == Eigen::Success ? res.tip.dy_dq.dot(k_llt.solve(res.tip.dy_dq)) : 0.0;
  out.load_scale = compliance > 0.0 ? beam.beam_length() / compliance : std::abs(tip_load_n);
  // The load is followed from the straight filament in increments of at most the load scale at
  // first and then at most the load reached (so that Newton stays on the branch it started on: a
  // single jump to a load of 1e12 N landed on another equilibrium), grown by 1.5 after a success and
  // halved after a failure.
  const double sign = tip_load_n < 0 ? -1.0 : 1.0;
  double reached = 0.0, increment = sign * std::min(std::abs(tip_load_n), 0.5 * out.load_scale);
  int attempts = 0;
  while (reached != tip_load_n) {
    if (stop && stop->stop_requested()) throw std::runtime_error("static equilibrium interrupted");
    if (reached != 0.0 && std::abs(increment) > std::abs(reached)) increment = reached;
    const double target = std::abs(tip_load_n - reached) <= std::abs(increment) ? tip_load_n : reached + increment;
    Eigen::VectorXd q = out.q;
    if (newton(res, target, q, out.iterations)) {
      out.q = q;
      reached = target;
      ++out.load_steps;
      increment *= 1.5;
    } else {
      increment *= 0.5;
      if (std::abs(increment) < 1e-9 * out.load_scale || ++attempts > 1000) {
        std::ostringstream m;
        m << "no static equilibrium found beyond a tip load of " << reached << " N (of " << tip_load_n
          << " N): Newton's method does not converge there";
        throw std::runtime_error(m.str());
      }
    }
  }
  Eigen::VectorXd r(beam.modes());
  res(out.q, tip_load_n, r);
  out.residual = r.lpNorm<Eigen::Infinity>();
  const Eigen::Vector2d tip = beam.tip_position(out.q);
  out.tip_x = tip.x();
  out.tip_y = tip.y();
  out.reach = tip_reach(beam, out.q);
  return out;
}

std::vector<std::string> static_warnings(const BeamModel& beam, const StaticEquilibrium& s, double tip_load_n,
                                         double deflection_warning_ratio, double load_parameter) {
  std::vector<std::string> w;
  const double ratio = std::abs(s.tip_y) / beam.beam_length();
  // PL²/EI ≈ 3P/(load scale): the elastica bends within √(EI/P) = L/√(PL²/EI) of its clamp, which
  // n modes resolve down to about L/n.
  // The caller's exact PL²/EI where given: one value in the output, not two that differ.
  const double k = std::isnan(load_parameter) ? 3.0 * std::abs(tip_load_n) / s.load_scale : std::abs(load_parameter);
  const int n = beam.modes();
  if (k > static_cast<double>(n) * n) {
    std::ostringstream b;
    b << "the load (PL²/EI " << (std::isnan(load_parameter) ? "≈ " : "= ") << k << ") bends the filament within about " << 1.0 / std::sqrt(k)
      << " L of its clamp, finer than " << n << " modes resolve (about " << 1.0 / n << " L): give more modes (beam.modes)";
    w.push_back(b.str());
  }
  std::ostringstream m;
  if (s.reach > kReachLimit) {
    m << "the tip lies " << s.reach << " L from its clamp, farther than a filament of length L can reach: the "
      << "quadratic foreshortening model has left its geometry (beam.theory = \"elastica\" is exact)";
    w.push_back(m.str());
  } else if (!beam.geometrically_exact() && ratio > deflection_warning_ratio) {
    m << "tip deflection |y_t|/L = " << ratio << " exceeds simulation.deflection_warning_ratio = " << deflection_warning_ratio
      << ": the quadratic foreshortening model is at the edge of its validity (beam.theory = \"elastica\" is exact)";
    w.push_back(m.str());
  }
  return w;
}

}  // namespace rotbeam
