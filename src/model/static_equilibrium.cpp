#include "rotbeam/static_equilibrium.hpp"

#include <Eigen/LU>
#include <cmath>
#include <sstream>
#include <stdexcept>

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
  Eigen::VectorXd r(n), rp(n), rm(n), trial(n), r_trial(n);
  Eigen::MatrixXd jac(n, n);
  res(q, load, r);
  for (int it = 0; it < 60; ++it) {
    ++iterations;
    for (int j = 0; j < n; ++j) {  // central differences, step 1e-6 L
      const double h = 1e-6 * std::max(L, std::abs(q[j]));
      trial = q;
      trial[j] += h;
      res(trial, load, rp);
      trial[j] = q[j] - h;
      res(trial, load, rm);
      jac.col(j) = (rp - rm) / (2.0 * h);
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
    if (scale == 1.0 && step.lpNorm<Eigen::Infinity>() <= 1e-13 * L) return true;
    if (scale < 1e-6) return false;
  }
  return false;
}

}  // namespace

StaticEquilibrium static_equilibrium(const BeamModel& beam, double tip_load_n, const StopToken* stop) {
  if (!std::isfinite(tip_load_n)) throw std::invalid_argument("the tip load must be finite");
  Residual res(beam);
  StaticEquilibrium out;
  out.q = Eigen::VectorXd::Zero(beam.modes());
  double reached = 0.0, increment = tip_load_n;
  while (reached != tip_load_n) {
    if (stop && stop->stop_requested()) throw std::runtime_error("static equilibrium interrupted");
    const double target = std::abs(tip_load_n - reached) <= std::abs(increment) ? tip_load_n : reached + increment;
    Eigen::VectorXd q = out.q;
    if (newton(res, target, q, out.iterations)) {
      out.q = q;
      reached = target;
      ++out.load_steps;
      increment *= 1.5;
    } else {
      increment *= 0.5;
      if (std::abs(increment) < 1e-9 * std::abs(tip_load_n)) {
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
  return out;
}

}  // namespace rotbeam
