#include "rotbeam/continuation.hpp"

#include "rotbeam/job_runner.hpp"
#include "rotbeam/steady_state.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <complex>
#include <deque>
#include <sstream>
#include <stdexcept>

namespace rotbeam {

const char* special_kind_name(SpecialKind kind) {
  switch (kind) {
    case SpecialKind::fold: return "fold";
    case SpecialKind::branch_point: return "branch_point";
    case SpecialKind::period_doubling: return "period_doubling";
    case SpecialKind::neimark_sacker: return "neimark_sacker";
    case SpecialKind::grazing: return "grazing";
  }
  return "?";
}

namespace {

std::string num(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

// The sign of Π (μ_i − shift) over the multipliers: complex pairs give |μ − shift|² > 0, so it changes
// only where a real multiplier passes `shift` (det(J − shift·I) without forming it).
int product_sign(const std::vector<Multiplier>& mu, double shift) {
  std::complex<double> p(1.0, 0.0);
  for (const Multiplier& m : mu) {
    const std::complex<double> f(m.re - shift, m.im);
    p *= f / std::max(std::abs(f), 1e-300);  // unit factors: no overflow, only the phase counts
  }
  return p.real() >= 0 ? 1 : -1;
}

bool is_real(const Multiplier& m) { return std::abs(m.im) <= 1e-9 * std::max(m.magnitude(), 1e-300); }

// The real multiplier nearest `target` (NaN when none is real).
double nearest_real(const std::vector<Multiplier>& mu, double target) {
  double best = NAN;
  for (const Multiplier& m : mu)
    if (is_real(m) && (std::isnan(best) || std::abs(m.re - target) < std::abs(best - target))) best = m.re;
  return best;
}

// Complex pairs outside the unit circle (each pair counted once).
int complex_pairs_outside(const std::vector<Multiplier>& mu) {
  int n = 0;
  for (const Multiplier& m : mu)
    if (!is_real(m) && m.im > 0 && m.magnitude() > 1.0) ++n;
  return n;
}

// The complex multiplier (upper half-plane) whose magnitude is nearest 1.
std::optional<Multiplier> pair_nearest_circle(const std::vector<Multiplier>& mu) {
  std::optional<Multiplier> best;
  for (const Multiplier& m : mu)
    if (!is_real(m) && m.im > 0 && (!best || std::abs(m.magnitude() - 1.0) < std::abs(best->magnitude() - 1.0))) best = m;
  return best;
}

class Engine {
public:
  Engine(const ParametrisedMap& map, const ParametrisedJacobian& with_jacobian, double from, double to,
         const ContinuationSettings& s, const std::function<void(const ContinuationProgress&)>& on_point,
         ContinuationResult& out)
      : map_(map), with_jacobian_(with_jacobian), from_(from), span_(to - from), s_(s), on_point_(on_point), out_(out) {}

  double parameter(double u) const { return from_ + u * span_; }
  double scaled(double p) const { return (p - from_) / span_; }
  bool stop_requested() const { return s_.stop && s_.stop->stop_requested(); }

  void set_scale(const Eigen::VectorXd& z) { zs_ = std::max(z.norm(), 1e-6); }

  MapValue evaluate(const Eigen::VectorXd& z, double p, int period) {
    ++out_.map_evaluations;
    out_.revolutions += period;
    return map_(z, p, period);
  }

  // The relative residual of a fixed point, with a floor for states near zero.
  double residual(const Eigen::VectorXd& z, const Eigen::VectorXd& pz) const {
    return (pz - z).norm() / std::max({pz.norm(), z.norm(), 1e-6 * zs_});
  }

  // ∂P/∂z and ∂P/∂p at (z, p): ∂P/∂z from the map's own Jacobian where it gives one (with_jacobian_),
  // else by central differences; ∂P/∂p by central differences. The evaluations run in parallel. False
  // when one did not complete (its failure kept in *failure).
  bool jacobian(BranchPoint& pt, std::optional<NumericalFailure>* failure) {
    if (with_jacobian_) {
      if (!jacobian_variational(pt, failure)) return false;
      if (pt.jacobian.size() > 0) return true;
    }
    return jacobian_by_differences(pt, failure);
  }

  // ∂P/∂z from one evaluation of with_jacobian_ (left empty where it gives none) beside the
  // parameter's stencil (∂P/∂p).
  bool jacobian_variational(BranchPoint& pt, std::optional<NumericalFailure>* failure) {
    const Eigen::Index d = pt.z.size();
    const double dp = s_.jacobian_step * std::abs(span_);
    const double u = scaled(pt.parameter), du = s_.jacobian_step;
    const bool one_sided = pt.image.size() == pt.z.size() && (u + du > 1.0 || u - du < 0.0);
    const double toward = span_ > 0 ? (u + du > 1.0 ? -1.0 : 1.0) : (u + du > 1.0 ? 1.0 : -1.0);
    std::vector<MapValue> v(one_sided ? 2 : 3);
    JobRunnerOptions jo;
    jo.threads = std::max(1, s_.threads);
    jo.stop = s_.stop;
    const std::vector<std::size_t> ran = run_jobs(v.size(), [&](std::size_t j) {
      if (j == 0) {
        v[0] = with_jacobian_(pt.z, pt.parameter, pt.period);
        return;
      }
      const double p = pt.parameter + (one_sided ? toward * dp : (j == 1 ? dp : -dp));
      v[j] = map_(pt.z, p, pt.period);
    }, jo);
    out_.map_evaluations += static_cast<int>(ran.size());
    out_.revolutions += static_cast<int>(ran.size()) * pt.period;
    if (ran.size() != v.size()) return false;
    for (const MapValue& e : v)
      if (!e.complete()) {
        if (failure && !*failure) *failure = e.failure;
        return false;
      }
    pt.jacobian_event_changes = 0;
    for (std::size_t j = 0; j < v.size(); ++j)
      if (v[j].metrics.impacts != pt.metrics.impacts || v[j].metrics.contact_episodes != pt.metrics.contact_episodes)
        ++pt.jacobian_event_changes;
    if (v[0].jacobian.rows() != d || v[0].jacobian.cols() != d) {
      out_.jacobian_fallback = v[0].jacobian_fallback;
      pt.jacobian.resize(0, 0);
      return true;
    }
    ++out_.variational_jacobians;
    pt.jacobian = v[0].jacobian;
    pt.parameter_derivative = one_sided ? Eigen::VectorXd((v[1].z - pt.image) / (toward * dp))
                                        : Eigen::VectorXd((v[1].z - v[2].z) / (2.0 * dp));
    pt.multipliers = floquet_multipliers(pt.jacobian);
    pt.stable = !pt.multipliers.empty() && pt.multipliers.front().magnitude() < 1.0;
    return true;
  }

  bool jacobian_by_differences(BranchPoint& pt, std::optional<NumericalFailure>* failure) {
    ++out_.difference_jacobians;
    const Eigen::Index d = pt.z.size();
    const double dz = s_.jacobian_step * std::max(pt.z.norm(), 1e-6);
    const double dp = s_.jacobian_step * std::abs(span_);
    // The parameter's stencil stays within [from, to] (a key's values may end there: a friction from
    // 0): one-sided with the point's own image at the ends.
    const double u = scaled(pt.parameter), du = s_.jacobian_step;
    const bool one_sided = pt.image.size() == pt.z.size() && (u + du > 1.0 || u - du < 0.0);
    const double toward = span_ > 0 ? (u + du > 1.0 ? -1.0 : 1.0) : (u + du > 1.0 ? 1.0 : -1.0);
    std::vector<MapValue> v(static_cast<std::size_t>(2 * d + (one_sided ? 1 : 2)));
    JobRunnerOptions jo;
    jo.threads = std::max(1, s_.threads);
    jo.stop = s_.stop;
    const std::vector<std::size_t> ran = run_jobs(v.size(), [&](std::size_t j) {
      Eigen::VectorXd z = pt.z;
      double p = pt.parameter;
      const Eigen::Index c = static_cast<Eigen::Index>(j / 2);
      const double sign = j % 2 == 0 ? 1.0 : -1.0;
      if (c < d) z[c] += sign * dz;
      else p += one_sided ? toward * dp : sign * dp;
      v[j] = map_(z, p, pt.period);
    }, jo);
    out_.map_evaluations += static_cast<int>(ran.size());
    out_.revolutions += static_cast<int>(ran.size()) * pt.period;
    if (ran.size() != v.size()) return false;
    pt.jacobian.resize(d, d);
    pt.jacobian_event_changes = 0;
    for (std::size_t j = 0; j < v.size(); ++j) {
      if (!v[j].complete()) {
        if (failure && !*failure) *failure = v[j].failure;
        return false;
      }
      if (v[j].metrics.impacts != pt.metrics.impacts || v[j].metrics.contact_episodes != pt.metrics.contact_episodes)
        ++pt.jacobian_event_changes;
    }
    for (Eigen::Index c = 0; c < d; ++c) pt.jacobian.col(c) = (v[2 * c].z - v[2 * c + 1].z) / (2.0 * dz);
    pt.parameter_derivative = one_sided ? Eigen::VectorXd((v[2 * d].z - pt.image) / (toward * dp))
                                        : Eigen::VectorXd((v[2 * d].z - v[2 * d + 1].z) / (2.0 * dp));
    pt.multipliers = floquet_multipliers(pt.jacobian);
    pt.stable = !pt.multipliers.empty() && pt.multipliers.front().magnitude() < 1.0;
    return true;
  }

  // [P_z − I, P_u] in the scaled unknowns (d × (d + 1)).
  Eigen::MatrixXd augmented(const Eigen::MatrixXd& J, const Eigen::VectorXd& Pp) const {
    const Eigen::Index d = J.rows();
    Eigen::MatrixXd A(d, d + 1);
    A.leftCols(d) = J - Eigen::MatrixXd::Identity(d, d);
    A.col(d) = Pp * span_ / zs_;
    return A;
  }
  Eigen::MatrixXd augmented(const BranchPoint& pt) const { return augmented(pt.jacobian, pt.parameter_derivative); }

  // The unit tangent of the branch: A t = 0, on the side of `hint`.
  static Eigen::VectorXd tangent(const Eigen::MatrixXd& A, const Eigen::VectorXd& hint) {
    const Eigen::Index d = A.rows();
    Eigen::MatrixXd B(d + 1, d + 1);
    B.topRows(d) = A;
    B.row(d) = hint.transpose();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(d + 1);
    rhs[d] = 1.0;
    Eigen::VectorXd t = B.fullPivLu().solve(rhs);
    if (!t.allFinite() || t.norm() == 0) return hint.normalized();
    t.normalize();
    if (t.dot(hint) < 0) t = -t;
    return t;
  }

  Eigen::VectorXd unknowns(const BranchPoint& pt) const {
    Eigen::VectorXd y(pt.z.size() + 1);
    y.head(pt.z.size()) = pt.z / zs_;
    y[pt.z.size()] = scaled(pt.parameter);
    return y;
  }

  struct Corrected {
    bool converged = false;
    BranchPoint point;
    std::optional<NumericalFailure> failure;
  };

  // The corrector: P(z) − z = 0 with tᵀ(y − y_pred) = 0 (or u fixed when t is empty), Newton's chord
  // from B0 with Broyden's update.
  Corrected correct(const Eigen::VectorXd& y_pred, const Eigen::VectorXd& t, Eigen::MatrixXd B, int period) {
    Corrected c;
    const Eigen::Index d = y_pred.size() - 1;
    Eigen::VectorXd y = y_pred, y_prev, H_prev;
    for (int it = 0; it <= s_.max_corrector_iterations; ++it) {
      if (stop_requested()) return c;
      const Eigen::VectorXd z = y.head(d) * zs_;
      const double p = parameter(y[d]);
      MapValue v = evaluate(z, p, period);
      if (!v.complete()) {
        c.failure = v.failure;
        return c;
      }
      Eigen::VectorXd H(d + 1);
      H.head(d) = v.z / zs_ - y.head(d);
      H[d] = t.size() ? t.dot(y - y_pred) : y[d] - y_pred[d];
      if (residual(z, v.z) < s_.tolerance) {
        c.converged = true;
        c.point.period = period;
        c.point.parameter = p;
        c.point.z = z;
        c.point.image = v.z;
        c.point.metrics = v.metrics;
        c.point.corrector_iterations = it;
        return c;
      }
      if (it > 0) {
        if (!(H.norm() < 2.0 * H_prev.norm())) return c;  // diverging
        const Eigen::VectorXd s = y - y_prev;
        B += ((H - H_prev) - B * s) * s.transpose() / s.squaredNorm();
      }
      const Eigen::VectorXd dy = B.partialPivLu().solve(-H);
      if (!dy.allFinite()) return c;
      y_prev = y;
      H_prev = H;
      y += dy;
    }
    return c;
  }

  Eigen::MatrixXd bordered(const Eigen::MatrixXd& A, const Eigen::VectorXd& t) const {
    Eigen::MatrixXd B(A.rows() + 1, A.cols());
    B.topRows(A.rows()) = A;
    B.row(A.rows()) = t.transpose();
    return B;
  }

  // The special points between a and b (consecutive points of one branch, b the later one).
  void detect(const BranchPoint& a, const BranchPoint& b, int before, double h) {
    auto add = [&](SpecialKind kind, double theta, Multiplier mu, std::string note) {
      SpecialPoint sp;
      sp.kind = kind;
      sp.branch = b.branch;
      sp.before = before;
      theta = std::clamp(theta, 0.0, 1.0);
      sp.parameter = a.parameter + theta * (b.parameter - a.parameter);
      sp.z = a.z + theta * (b.z - a.z);
      sp.multiplier = mu;
      sp.note = std::move(note);
      out_.special.push_back(std::move(sp));
    };
    const bool fold = a.tangent_parameter * b.tangent_parameter < 0;
    if (fold) {
      // The cubic Hermite interpolant of u(s) over the step, from u and du/ds at both ends: where its
      // derivative vanishes.
      const double u0 = scaled(a.parameter), u1 = scaled(b.parameter);
      const double m0 = h * a.tangent_parameter, m1 = h * b.tangent_parameter;
      // u'(τ) = (6τ² − 6τ)u0 + (3τ² − 4τ + 1)m0 + (−6τ² + 6τ)u1 + (3τ² − 2τ)m1
      const double qa = 6 * u0 + 3 * m0 - 6 * u1 + 3 * m1, qb = -6 * u0 - 4 * m0 + 6 * u1 - 2 * m1, qc = m0;
      double tau = m0 / (m0 - m1);  // linear in the derivative when the quadratic is degenerate
      if (std::abs(qa) > 1e-14 * (std::abs(qb) + std::abs(qc))) {
        const double disc = std::sqrt(std::max(0.0, qb * qb - 4 * qa * qc));
        for (double r : {(-qb + disc) / (2 * qa), (-qb - disc) / (2 * qa)})
          if (r >= 0 && r <= 1) tau = r;
      }
      const double h00 = 2 * tau * tau * tau - 3 * tau * tau + 1, h10 = tau * tau * tau - 2 * tau * tau + tau;
      const double h01 = -2 * tau * tau * tau + 3 * tau * tau, h11 = tau * tau * tau - tau * tau;
      const double u = h00 * u0 + h10 * m0 + h01 * u1 + h11 * m1;
      // The state is taken along the chord at the same fraction of the step; the parameter from the cubic.
      add(SpecialKind::fold, tau, {1.0, 0.0},
          "the branch turns back at p = " + num(parameter(u)) + " (a multiplier through +1)");
      out_.special.back().parameter = parameter(u);
    }
    if (product_sign(a.multipliers, 1.0) != product_sign(b.multipliers, 1.0) && !fold) {
      const double r0 = nearest_real(a.multipliers, 1.0), r1 = nearest_real(b.multipliers, 1.0);
      const double theta = std::isfinite(r0 - r1) && r0 != r1 ? (r0 - 1.0) / (r0 - r1) : 0.5;
      add(SpecialKind::branch_point, theta, {1.0, 0.0}, "a real multiplier passes +1 while the branch goes on");
    }
    if (product_sign(a.multipliers, -1.0) != product_sign(b.multipliers, -1.0)) {
      const double r0 = nearest_real(a.multipliers, -1.0), r1 = nearest_real(b.multipliers, -1.0);
      const double theta = std::isfinite(r0 - r1) && r0 != r1 ? (r0 + 1.0) / (r0 - r1) : 0.5;
      add(SpecialKind::period_doubling, theta, {-1.0, 0.0},
          "a real multiplier passes −1: a period-" + std::to_string(2 * b.period) + " orbit branches off here");
    }
    const auto m0 = pair_nearest_circle(a.multipliers), m1 = pair_nearest_circle(b.multipliers);
    // A pair that crosses the circle (not one that meets the real axis outside it and splits there).
    if (complex_pairs_outside(a.multipliers) != complex_pairs_outside(b.multipliers) && m0 && m1 &&
        (m0->magnitude() - 1.0) * (m1->magnitude() - 1.0) < 0) {
      double theta = 0.5;
      Multiplier mu{NAN, NAN};
      if (m0->magnitude() != m1->magnitude()) {
        theta = (m0->magnitude() - 1.0) / (m0->magnitude() - m1->magnitude());
        const double th = std::clamp(theta, 0.0, 1.0);
        mu = {m0->re + th * (m1->re - m0->re), m0->im + th * (m1->im - m0->im)};
      }
      const double angle = std::isfinite(mu.re) ? std::atan2(mu.im, mu.re) * 180.0 / M_PI : NAN;
      add(SpecialKind::neimark_sacker, theta, mu,
          "a complex pair passes the unit circle at " + num(angle) + "° (a quasi-periodic, torus, orbit appears)");
    }
    if (a.metrics.impacts != b.metrics.impacts || a.metrics.contact_episodes != b.metrics.contact_episodes) {
      add(SpecialKind::grazing, 0.5, {NAN, NAN},
          "impacts per period " + std::to_string(a.metrics.impacts) + " → " + std::to_string(b.metrics.impacts) +
              ", contact episodes " + std::to_string(a.metrics.contact_episodes) + " → " +
              std::to_string(b.metrics.contact_episodes) +
              " (the map is not smooth here; the continuation steps over it on the pieces either side)");
    }
  }

  // Follows one branch from its first (converged, with Jacobian) point in the direction of `hint`.
  // Returns how it ended.
  std::string follow(BranchPoint start, Eigen::VectorXd hint) {
    stalled_ = false;
    Eigen::VectorXd t = tangent(augmented(start), hint);
    start.tangent_parameter = t[t.size() - 1];
    int index = static_cast<int>(out_.points.size());
    out_.points.push_back(start);
    report(out_.points.back());
    int count = 1;
    double h = s_.initial_step;
    for (;;) {
      if (stop_requested()) {
        out_.stopped = true;
        return "stopped on request";
      }
      if (count >= s_.max_points) return "reached the limit of " + std::to_string(s_.max_points) + " points";
      const BranchPoint& last = out_.points[static_cast<std::size_t>(index)];
      const Eigen::VectorXd y = unknowns(last);
      const Eigen::Index d = last.z.size();
      const double u = y[d], tu = t[d];
      bool final_step = false;
      double step = h, u_end = 1.0;
      if (tu > 0 && u + step * tu > 1.0) {
        step = (1.0 - u) / tu;
        final_step = true;
      } else if (backward_ && tu < 0 && u + step * tu < 0.0) {
        step = -u / tu;
        final_step = true;
        u_end = 0.0;
      }
      if (final_step && step < 1e-9) return "reached the end of the range";
      Eigen::VectorXd y_pred = y + step * t;
      // The last step lands on the range's end itself: its corrector holds u there instead of the arclength.
      if (final_step) y_pred[d] = u_end;
      const Eigen::VectorXd e_u = Eigen::VectorXd::Unit(d + 1, d);
      Corrected c = final_step ? correct(y_pred, Eigen::VectorXd(), bordered(augmented(last), e_u), last.period)
                               : correct(y_pred, t, bordered(augmented(last), t), last.period);
      std::optional<NumericalFailure> failure = c.failure;
      if (c.converged) {
        c.point.branch = last.branch;
        if (!jacobian(c.point, &failure)) c.converged = false;
      }
      if (!c.converged) {
        if (stop_requested()) {
          out_.stopped = true;
          return "stopped on request";
        }
        h = step / 2.0;
        if (h < s_.min_step) {
          last_failure_ = failure;
          stalled_ = true;
          return "stalled at p = " + num(last.parameter) + ": no step down to " + num(s_.min_step) + " converged" +
                 (failure ? " (an evaluation of the map failed: " + failure->message + ")" : "");
        }
        continue;
      }
      const Eigen::VectorXd t_new = tangent(augmented(c.point), t);
      c.point.tangent_parameter = t_new[d];
      c.point.arclength = last.arclength + step;
      const BranchPoint before = last;
      out_.points.push_back(std::move(c.point));
      ++count;
      detect(before, out_.points.back(), index, step);
      index = static_cast<int>(out_.points.size()) - 1;
      t = t_new;
      report(out_.points.back());
      const int its = out_.points.back().corrector_iterations;
      if (its <= 3) h = std::min(step * 1.5, s_.max_step);
      else if (its >= 5) h = std::max(step / 1.5, s_.min_step);
      else h = step;
      const double u_new = scaled(out_.points.back().parameter);
      if (final_step) return "reached p = " + num(parameter(u_end));
      if (u_new >= 1.0 - 1e-9) return "reached p = " + num(parameter(1.0));
      if (u_new < -1e-9) return (backward_ ? "reached p = " : "turned back and left the range at p = ") + num(parameter(0.0));
    }
  }

  void report(const BranchPoint& pt) {
    if (!on_point_) return;
    ContinuationProgress pr;
    pr.branch = pt.branch;
    pr.points = static_cast<int>(out_.points.size());
    pr.map_evaluations = out_.map_evaluations;
    pr.parameter = pt.parameter;
    pr.u = scaled(pt.parameter);
    pr.stable = pt.stable;
    on_point_(pr);
  }

  // A first point: Newton on P(z) − z at p fixed, from z0.
  std::optional<BranchPoint> first_point(const Eigen::VectorXd& z0, double p0, int period, std::string& why) {
    BranchPoint pt;
    pt.period = period;
    pt.parameter = p0;
    pt.z = z0;
    std::optional<NumericalFailure> failure;
    MapValue v0 = evaluate(z0, p0, period);
    if (!v0.complete()) {
      why = "the map could not be evaluated at p = " + num(p0) + (v0.failure ? ": " + v0.failure->message : "");
      last_failure_ = v0.failure;
      return std::nullopt;
    }
    pt.metrics = v0.metrics;
    pt.image = v0.z;
    if (!jacobian(pt, &failure)) {
      why = "the Jacobian at p = " + num(p0) + " could not be evaluated" + (failure ? ": " + failure->message : "");
      last_failure_ = failure;
      return std::nullopt;
    }
    const Eigen::Index d = z0.size();
    Eigen::VectorXd y = unknowns(pt);
    Eigen::MatrixXd B = bordered(augmented(pt), Eigen::VectorXd::Unit(d + 1, d));
    Corrected c = correct(y, Eigen::VectorXd(), B, period);
    if (!c.converged) {
      why = "no fixed point of period " + std::to_string(period) + " was found near the state given at p = " + num(p0) +
            (c.failure ? " (an evaluation failed: " + c.failure->message + ")" : "");
      last_failure_ = c.failure;
      return std::nullopt;
    }
    if (!jacobian(c.point, &failure)) {
      why = "the Jacobian at the fixed point at p = " + num(p0) + " could not be evaluated";
      last_failure_ = failure;
      return std::nullopt;
    }
    return c.point;
  }
  std::optional<NumericalFailure> last_failure_;  // the last evaluation that ended a branch or a start
  bool stalled_ = false;                          // the last branch or start tried ended in a stall
  bool backward_ = false;                         // the branch under way is followed toward `from`

  // The doubled branch from a period doubling: the period-2M map has a pitchfork there, its new branch
  // leaving along the eigenvector of μ = −1 at constant parameter.
  std::optional<BranchPoint> doubled_start(const SpecialPoint& pd, std::string& why) {
    const BranchPoint& a = out_.points[static_cast<std::size_t>(pd.before)];
    const BranchPoint& b = out_.points[static_cast<std::size_t>(pd.before) + 1];
    const double theta = b.parameter != a.parameter ? (pd.parameter - a.parameter) / (b.parameter - a.parameter) : 0.5;
    const Eigen::MatrixXd J = a.jacobian + theta * (b.jacobian - a.jacobian);
    const Eigen::VectorXd Pp = a.parameter_derivative + theta * (b.parameter_derivative - a.parameter_derivative);
    const Eigen::EigenSolver<Eigen::MatrixXd> es(J, true);
    if (es.info() != Eigen::Success) {
      why = "the eigenvectors at the period doubling could not be computed";
      return std::nullopt;
    }
    Eigen::Index k = 0;
    for (Eigen::Index i = 1; i < es.eigenvalues().size(); ++i)
      if (std::abs(es.eigenvalues()[i] + 1.0) < std::abs(es.eigenvalues()[k] + 1.0)) k = i;
    Eigen::VectorXd v = es.eigenvectors().col(k).real();
    if (v.norm() == 0) {
      why = "the eigenvector of μ = −1 is not real";
      return std::nullopt;
    }
    v.normalize();
    const Eigen::Index d = J.rows();
    BranchPoint pd_point;
    pd_point.period = 2 * a.period;
    pd_point.parameter = pd.parameter;
    pd_point.z = pd.z;
    const Eigen::VectorXd y0 = unknowns(pd_point);
    // At the doubling itself the period-2M map's [P_z − I, P_u] vanishes along v (a pitchfork): the
    // corrector starts from the Jacobian at the predicted point, a step along v, where it does not.
    for (double h : {s_.initial_step, s_.initial_step / 4, s_.initial_step / 16}) {
      for (double sign : {1.0, -1.0}) {
        if (stop_requested()) {
          why = "stopped on request before the doubled branch was found";
          return std::nullopt;
        }
        Eigen::VectorXd t = Eigen::VectorXd::Zero(d + 1);
        t.head(d) = sign * v;
        const Eigen::VectorXd y_pred = y0 + h * t;
        BranchPoint guess = pd_point;
        guess.z = y_pred.head(d) * zs_;
        const MapValue at_guess = evaluate(guess.z, guess.parameter, guess.period);
        if (!at_guess.complete()) continue;
        guess.metrics = at_guess.metrics;
        guess.image = at_guess.z;
        std::optional<NumericalFailure> failure;
        if (!jacobian(guess, &failure)) continue;
        Corrected c = correct(y_pred, t, bordered(augmented(guess), t), pd_point.period);
        if (!c.converged) continue;
        // Not the period-M orbit the corrector may have fallen back to.
        const MapValue once = evaluate(c.point.z, c.point.parameter, a.period);
        if (!once.complete() || residual(c.point.z, once.z) < 100.0 * s_.tolerance) continue;
        if (!jacobian(c.point, &failure)) continue;
        return c.point;
      }
    }
    why = "no period-" + std::to_string(2 * a.period) + " orbit was found beside the period doubling at p = " +
          num(pd.parameter);
    return std::nullopt;
  }

private:
  const ParametrisedMap& map_;
  const ParametrisedJacobian& with_jacobian_;
  double from_, span_;
  ContinuationSettings s_;
  const std::function<void(const ContinuationProgress&)>& on_point_;
  ContinuationResult& out_;
  double zs_ = 1.0;
};

}  // namespace

ContinuationResult continue_fixed_points(const ParametrisedMap& map, const Eigen::VectorXd& z0, double from, double to,
                                         int period, const ContinuationSettings& settings,
                                         const std::function<void(const ContinuationProgress&)>& on_point,
                                         const ReseedFunction& reseed, const ParametrisedJacobian& with_jacobian) {
  if (!std::isfinite(from) || !std::isfinite(to) || from == to)
    throw std::invalid_argument("the parameter's range must be two different finite numbers");
  if (z0.size() == 0) throw std::invalid_argument("an empty start state");
  if (period < 1) throw std::invalid_argument("a period below 1");
  ContinuationResult out;
  Engine e(map, with_jacobian, from, to, settings, on_point, out);
  e.set_scale(z0);
  std::string why;
  std::optional<BranchPoint> first = e.first_point(z0, from, period, why);
  std::string start_words = "the start";
  double start_u = 0.0;
  // No orbit at `from`: sought further on (reseed) in restart_jump steps; the branch found is then
  // followed back toward `from` as well.
  const int jumps = static_cast<int>(std::ceil(1.0 / settings.restart_jump));
  for (int tries = 0; !first && reseed && tries < std::min(settings.max_restarts, jumps) && !e.stop_requested(); ++tries) {
    start_u += settings.restart_jump;
    if (start_u >= 1.0) break;
    const double p = e.parameter(start_u);
    std::optional<Reseed> r = reseed(p, z0);
    if (!r) continue;
    first = e.first_point(r->z, p, r->period, why);
    if (first) start_words = "found at p = " + num(p) + " (none at " + num(from) + "): " + r->note;
  }
  if (!first) {
    out.branches.push_back({0, period, 0, "the start", why});
    out.failure = e.last_failure_;
    out.stopped = e.stop_requested();
    return out;
  }
  e.set_scale(first->z);
  const Eigen::Index d = z0.size();
  std::deque<std::size_t> doublings;  // indices into out.special still to be followed
  auto run_branch = [&](BranchPoint start, const Eigen::VectorXd& hint, const std::string& how) {
    const std::size_t special_before = out.special.size(), points_before = out.points.size();
    const int branch = start.branch, per = start.period;
    const std::string end = e.follow(std::move(start), hint);
    out.branches.push_back({branch, per, static_cast<int>(out.points.size() - points_before), how, end});
    for (std::size_t k = special_before; k < out.special.size(); ++k)
      if (out.special[k].kind == SpecialKind::period_doubling) doublings.push_back(k);
  };
  const Eigen::VectorXd forward = Eigen::VectorXd::Unit(d + 1, d);
  int next_branch = 1;
  if (start_u > 0.0) {
    e.backward_ = true;
    run_branch(*first, -forward, start_words + "; followed back toward p = " + num(from));
    e.backward_ = false;
    first->branch = next_branch++;
  }
  run_branch(*first, forward, start_words);
  // After a stall, the orbit is sought again a little further on (reseed), and followed from there.
  double reached = start_u;  // the furthest u the branches got to
  Eigen::VectorXd near = first->z;  // the state there
  for (int restarts = 0; reseed && e.stalled_ && restarts < std::min(settings.max_restarts, jumps) && !e.stop_requested();
       ++restarts) {
    for (const BranchPoint& p : out.points)
      if (e.scaled(p.parameter) > reached) reached = e.scaled(p.parameter), near = p.z;
    reached += settings.restart_jump;
    if (reached >= 1.0) break;
    const double p_next = e.parameter(reached);
    std::optional<Reseed> r = reseed(p_next, near);
    if (!r) continue;
    std::optional<BranchPoint> start = e.first_point(r->z, p_next, r->period, why);
    if (!start) {
      e.stalled_ = true;
      continue;
    }
    start->branch = next_branch++;
    run_branch(*start, forward, "restarted at p = " + num(p_next) + " after a stall: " + r->note);
  }
  if (e.stalled_ && e.last_failure_) out.failure = e.last_failure_;
  int doubled = 0;
  while (settings.switch_period_doubling && !doublings.empty() && !out.stopped && !e.stop_requested()) {
    if (doubled == settings.max_branches) {
      for (std::size_t k : doublings)
        out.special[k].note += "; not followed: " + std::to_string(settings.max_branches) + " doubled branches were";
      break;
    }
    SpecialPoint& pd = out.special[doublings.front()];
    doublings.pop_front();
    std::string why_not;
    std::optional<BranchPoint> start = e.doubled_start(pd, why_not);
    if (!start) {
      pd.note += "; " + why_not;
      continue;
    }
    start->branch = next_branch;
    pd.doubled_branch = next_branch;
    ++next_branch;
    ++doubled;
    // Away from the doubling along the new branch: the direction the corrector moved in.
    BranchPoint at_doubling;
    at_doubling.z = pd.z;
    at_doubling.parameter = pd.parameter;
    const Eigen::VectorXd hint = e.unknowns(*start) - e.unknowns(at_doubling);
    run_branch(*start, hint, "from the period doubling at p = " + num(pd.parameter));
  }
  if (e.stop_requested()) out.stopped = true;
  return out;
}

}  // namespace rotbeam
