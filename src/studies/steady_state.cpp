#include "rotbeam/steady_state.hpp"

#include "rotbeam/beam_model.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace rotbeam {

namespace {

std::string period_words(int m) {
  return m == 1 ? std::string("periodic every revolution") : "periodic every " + std::to_string(m) + " revolutions";
}

// The multipliers in words: stable or not, and how an instability would show.
std::string stability_words(const std::vector<Multiplier>& mu) {
  if (mu.empty()) return "";
  std::ostringstream s;
  s.precision(3);
  const Multiplier& top = mu.front();
  if (top.magnitude() < 1.0) {
    s << "stable (largest multiplier |μ| = " << top.magnitude() << ")";
  } else {
    s << "unstable (|μ| = " << top.magnitude() << ", ";
    if (std::abs(top.im) > 1e-9 * top.magnitude())
      s << "a complex pair: a quasi-periodic (torus) instability)";
    else if (top.re < 0)
      s << "real and negative: a period doubling)";
    else
      s << "real and positive: a fold or a symmetry breaking)";
  }
  return s.str();
}

}  // namespace

InitialConditions section_start(const BeamModel& beam, const Eigen::VectorXd& z, InitialConditions base) {
  const int n = beam.modes();
  const double L = beam.beam_length(), omega = beam.hub_motion().omega;
  base.rigid_start = false;
  base.q0 = z.head(n) * L;
  base.qd0 = z.tail(n) * (omega * L);
  return base;
}

SectionMap::SectionMap(const System& system, const PassOptions& options, const StopToken* stop)
    : system_(system), options_(options), stop_(stop) {
  options_.until_steady = false;
  options_.history_revolutions = 1;
  options_.output_interval_s = 1e9;  // rows only at events: the samples do not change the integration
  options_.near_surface_gap_m = 0.0;
}

MapEvaluation SectionMap::operator()(const Eigen::VectorXd& z, int m, bool tangent) const {
  const InitialConditions ic = section_start(system_.beam, z);
  PassOptions o = options_;
  o.tangent = tangent;
  o.revolutions = m;
  o.end_angle_deg = system_.beam.theta(0.0) * 180.0 / M_PI + 360.0 * m;
  DiscardSink sink;
  const PassResult r = run_pass(system_, ic, o, {&sink, stop_, {}});
  ++evaluations_;
  revolutions_run_ += m;
  MapEvaluation e;
  e.impacts = r.summary.impacts;
  e.contact_episodes = r.summary.contact_episodes;
  e.failure = r.failure;
  e.complete = !r.failure && r.summary.revolutions == m;
  if (e.complete) e.z = section_state(system_.beam, r.final_q, r.final_qd);
  e.summary = r.summary;
  e.tangent_lost = r.tangent_lost;
  if (e.complete && r.final_tangent.size() > 0) {
    // z = D x with D = diag(1/L, 1/(ωL)): ∂P/∂z = D Φ D⁻¹.
    const int n = system_.beam.modes();
    const double L = system_.beam.beam_length(), omega = system_.beam.hub_motion().omega;
    Eigen::VectorXd d(2 * n);
    d.head(n).setConstant(1.0 / L);
    d.tail(n).setConstant(1.0 / (omega * L));
    e.jacobian = d.asDiagonal() * r.final_tangent * d.cwiseInverse().asDiagonal();
  }
  return e;
}

Eigen::MatrixXd SectionMap::jacobian(const Eigen::VectorXd& z, int m, const MapEvaluation& base,
                                     int* sequence_changes) const {
  if (options_.jacobian == JacobianMethod::variational) {
    const MapEvaluation e = (*this)(z, m, true);
    if (e.complete && e.jacobian.size() > 0) {
      if (sequence_changes && (e.impacts != base.impacts || e.contact_episodes != base.contact_episodes))
        ++*sequence_changes;
      last_method_ = "variational";
      fallback_.clear();
      return e.jacobian;
    }
    if (!e.complete) return {};
    fallback_ = e.tangent_lost;
  }
  return jacobian_by_differences(z, m, base, sequence_changes);
}

Eigen::MatrixXd SectionMap::jacobian_by_differences(const Eigen::VectorXd& z, int m, const MapEvaluation& base,
                                                    int* sequence_changes) const {
  last_method_ = "differences";
  const Eigen::Index dim = z.size();
  const double delta = kJacobianStep * std::max(z.norm(), 1e-6);
  Eigen::MatrixXd J(dim, dim);
  for (Eigen::Index j = 0; j < dim; ++j) {
    Eigen::VectorXd zp = z, zm = z;
    zp[j] += delta;
    zm[j] -= delta;
    const MapEvaluation ep = (*this)(zp, m);
    const MapEvaluation em = (*this)(zm, m);
    if (!ep.complete || !em.complete) return {};
    for (const MapEvaluation* e : {&ep, &em})
      if (sequence_changes && (e->impacts != base.impacts || e->contact_episodes != base.contact_episodes))
        ++*sequence_changes;
    J.col(j) = (ep.z - em.z) / (2.0 * delta);
  }
  return J;
}

std::vector<Multiplier> floquet_multipliers(const Eigen::MatrixXd& jacobian) {
  std::vector<Multiplier> mu;
  if (jacobian.size() == 0) return mu;
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(jacobian, false);
  if (solver.info() != Eigen::Success) return mu;
  for (Eigen::Index i = 0; i < solver.eigenvalues().size(); ++i)
    mu.push_back({solver.eigenvalues()[i].real(), solver.eigenvalues()[i].imag()});
  std::stable_sort(mu.begin(), mu.end(), [](const Multiplier& a, const Multiplier& b) {
    return a.magnitude() != b.magnitude() ? a.magnitude() > b.magnitude() : a.im > b.im;
  });
  return mu;
}

namespace {

// The multipliers of P^m at z into st (and the counts of the evaluations they took).
void add_multipliers(const SectionMap& map, const Eigen::VectorXd& z, int m, SteadyState& st) {
  const MapEvaluation base = map(z, m);
  if (!base.complete) return;
  st.multipliers = floquet_multipliers(map.jacobian(z, m, base, &st.event_sequence_changes));
  st.jacobian = map.last_method();
}

// The clause of a note on a variational Jacobian that fell back to differences ("" when none did).
std::string fallback_words(const std::string& why) {
  return why.empty() ? "" : "; the map's Jacobian by differences, not the variational equations: " + why;
}

void report(const PassControl& control, std::chrono::steady_clock::time_point wall0, int revolutions_run, int cap,
            double distance, const std::string& stage) {
  if (!control.on_progress) return;
  PassProgress p;
  p.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  p.revolution = revolutions_run;
  p.revolutions = cap;
  p.section_distance = distance;
  p.stage = stage;
  control.on_progress(p);
}

// The brute-force test for the steady state (docs/model.md §11): every complete revolution's section state
// against those of the last kMaxSteadyPeriod revolutions; the first within simulation.steady_tolerance
// ends the run, periodic every p revolutions.
class SteadyStateDetector final : public RevolutionWatcher {
public:
  SteadyStateDetector(const BeamModel& beam, const PassOptions& options) : beam_(beam), options_(options) {}

  void start(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override {
    sections_.clear();
    sections_.push_back(section_state(beam_, q, qd));
  }

  bool revolution(const RevolutionRecord& r) override {
    const Eigen::VectorXd z = section_state(beam_, r.q, r.qd);
    const double tol = options_.steady_tolerance;
    int period = r.section_distance < tol ? 1 : 0;  // against the previous section
    const int held = static_cast<int>(sections_.size());
    for (int p = 2; period == 0 && p <= held; ++p)
      if (section_distance(z, sections_[held - p]) < tol) period = p;
    sections_.push_back(z);
    if (static_cast<int>(sections_.size()) > kMaxSteadyPeriod) sections_.erase(sections_.begin());
    last_distance_ = r.section_distance;
    if (period == 0 || reached_) return false;
    reached_ = true;
    after_ = r.revolution;
    period_ = period;
    return true;
  }

  std::string finish(PassSummary& summary, bool failed, int revolution) override {
    SteadyState& st = summary.steady_state;
    st.sought = true;
    st.tolerance = options_.steady_tolerance;
    st.method = SteadyMethod::brute_force;
    st.final_distance = last_distance_;
    st.reached = reached_;
    st.after_revolutions = after_;
    st.period_revolutions = period_;
    std::ostringstream m;
    if (reached_)
      m << "reached after " << after_ << (after_ == 1 ? " revolution, " : " revolutions, ")
        << (period_ == 1 ? std::string("periodic every revolution")
                         : "periodic every " + std::to_string(period_) + " revolutions")
        << " (section distance over the period < " << options_.steady_tolerance << ")";
    else if (failed)
      m << "not reached: the run stopped in revolution " << revolution;
    else if (options_.revolutions == 1)
      m << "not reached within 1 revolution (its section compared with the start only: distance " << last_distance_
        << ", tolerance " << options_.steady_tolerance << ")";
    else
      m << "not reached within " << options_.revolutions << " revolutions (section distance " << last_distance_
        << ", tolerance " << options_.steady_tolerance << ")";
    st.note = m.str();
    return !reached_ && !failed ? "no steady state: " + st.note : "";
  }

private:
  const BeamModel& beam_;
  const PassOptions& options_;
  std::vector<Eigen::VectorXd> sections_;  // the last kMaxSteadyPeriod sections, oldest first
  double last_distance_ = NAN;
  bool reached_ = false;
  int after_ = 0, period_ = 0;
};

// run_pass with the brute-force steady-state test watching its revolutions.
PassResult run_watched(const System& system, const InitialConditions& initial, const PassOptions& options,
                       const PassControl& control) {
  SteadyStateDetector detector(system.beam, options);
  PassControl watched = control;
  watched.watcher = &detector;
  return run_pass(system, initial, options, watched);
}

PassResult brute_force(const System& system, const InitialConditions& initial, const PassOptions& options,
                       const PassControl& control) {
  PassResult r = run_watched(system, initial, options, control);
  SteadyState& st = r.summary.steady_state;
  if (!st.reached || r.failure || !options.multipliers) return r;
  const auto wall0 = std::chrono::steady_clock::now();
  const SectionMap map(system, options, control.stop);
  const int runs = options.jacobian == JacobianMethod::variational ? 2 : 4 * system.beam.modes() + 1;
  report(control, wall0, st.after_revolutions, options.revolutions, st.final_distance,
         "multipliers: " + std::to_string(runs) + " map evaluations");
  add_multipliers(map, section_state(system.beam, r.final_q, r.final_qd), st.period_revolutions, st);
  st.map_evaluations = map.evaluations();
  if (st.multipliers.empty())
    st.note += "; multipliers not computed (the map's evaluations did not complete)";
  else
    st.note += "; " + stability_words(st.multipliers);
  if (st.event_sequence_changes > 0)
    st.note += "; " + std::to_string(st.event_sequence_changes) +
               " of the Jacobian's evaluations changed the impacts or episodes (a grazing orbit: the multipliers "
               "are those of a non-smooth map)";
  st.note += fallback_words(map.fallback());
  r.summary.wall_time_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return r;
}

struct NewtonOutcome {
  bool converged = false;
  Eigen::VectorXd z;        // the best section state found
  double distance = INFINITY;
  int iterations = 0;
  Eigen::MatrixXd jacobian;  // the last iteration's ∂P^m/∂z (empty when none was needed)
  std::string why;          // why it stopped without converging
};

// Newton on F(z) = P^m(z) − z from z0, with backtracking on ‖F‖.
NewtonOutcome newton(const SectionMap& map, Eigen::VectorXd z, int m, const PassOptions& options,
                     const ShootingSettings& settings, const PassControl& control,
                     std::chrono::steady_clock::time_point wall0, int revolutions_before, SteadyState& st) {
  NewtonOutcome out;
  MapEvaluation base = map(z, m);
  if (!base.complete) {
    out.why = "the map's evaluation did not complete";
    return out;
  }
  Eigen::VectorXd F = base.z - z;
  out.z = z;
  out.distance = section_distance(base.z, z);
  const auto identity = Eigen::MatrixXd::Identity(z.size(), z.size());
  for (int it = 0;; ++it) {
    out.iterations = it;
    if (out.distance < options.steady_tolerance) {
      out.converged = true;
      return out;
    }
    if (it == settings.max_newton_iterations) {
      out.why = "Newton did not converge in " + std::to_string(it) + (it == 1 ? " iteration" : " iterations");
      return out;
    }
    if (revolutions_before + map.revolutions_run() > options.revolutions) {
      out.why = "the search reached simulation.revolutions = " + std::to_string(options.revolutions);
      return out;
    }
    report(control, wall0, revolutions_before + map.revolutions_run(), options.revolutions, out.distance,
           "shooting, period " + std::to_string(m) + ", Newton iteration " + std::to_string(it + 1));
    const Eigen::MatrixXd J = map.jacobian(z, m, base, &st.event_sequence_changes);
    out.jacobian = J;
    st.jacobian = map.last_method();
    if (J.size() == 0) {
      out.why = "the map's evaluation did not complete";
      return out;
    }
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(J - identity);
    if (!lu.isInvertible()) {
      out.why = "P − I is singular (a multiplier at 1)";
      return out;
    }
    const Eigen::VectorXd dz = lu.solve(-F);
    bool accepted = false;
    double lambda = 1.0;
    for (int h = 0; h <= settings.max_step_halvings; ++h, lambda *= 0.5) {
      const Eigen::VectorXd zt = z + lambda * dz;
      const MapEvaluation et = map(zt, m);
      if (!et.complete) continue;
      const Eigen::VectorXd Ft = et.z - zt;
      if (Ft.norm() < F.norm()) {
        z = zt;
        base = et;
        F = Ft;
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      out.why = out.distance < 1e3 * options.rtol
                    ? "no Newton step reduced the residual: the integration's noise (about rtol·‖z‖) was reached; "
                      "a tighter simulation.rtol lets a smaller tolerance be met"
                    : "no Newton step reduced the residual: the start is outside Newton's reach, or the map is not "
                      "smooth here (the impacts change with the state)";
      return out;
    }
    out.z = z;
    out.distance = section_distance(base.z, z);
  }
}

PassResult shooting(const System& system, const InitialConditions& initial, const PassOptions& options,
                    const PassControl& control, const ShootingSettings& settings) {
  const auto wall0 = std::chrono::steady_clock::now();
  // 1. Warm-up by brute force, its rows discarded, to come near the orbit and learn its period.
  PassOptions warm = options;
  warm.steady_method = SteadyMethod::brute_force;
  warm.steady_tolerance = std::max(settings.warmup_tolerance, options.steady_tolerance);
  warm.revolutions = std::min(settings.warmup_revolutions, options.revolutions);
  warm.end_angle_deg = system.beam.theta(0.0) * 180.0 / M_PI + 360.0 * warm.revolutions;
  warm.output_interval_s = 1e9;
  warm.near_surface_gap_m = 0.0;
  DiscardSink discard;
  PassControl warm_control{&discard, control.stop, control.on_progress};
  PassResult w = run_watched(system, initial, warm, warm_control);
  const int warm_revolutions = w.summary.revolutions;
  if (w.failure || warm_revolutions == 0) {
    // Nothing to shoot from: the warm-up's result (its failure, or a stop) is the answer. Its rows
    // were not recorded: a failure is run again, recording into the caller's sink (the run is
    // deterministic: it ends the same way), so that the record holds what the summary describes.
    // A stop is not run again: the record then holds no rows, and the note says so.
    const bool stopped = w.failure && w.failure->kind == FailureKind::interrupted;
    if (!stopped) {
      PassOptions again = warm;
      again.output_interval_s = options.output_interval_s;
      again.near_surface_gap_m = options.near_surface_gap_m;
      w = run_watched(system, initial, again, control);
    }
    SteadyState& st = w.summary.steady_state;
    st.sought = true;
    st.method = SteadyMethod::shooting;
    st.tolerance = options.steady_tolerance;
    st.reached = false;
    st.after_revolutions = 0;
    st.period_revolutions = 0;
    st.note = "not reached: the warm-up stopped in revolution " + std::to_string(w.summary.revolutions + 1) +
              (stopped ? " (interrupted; the warm-up records no rows, so the history and events hold none)" : "");
    return w;
  }
  const Eigen::VectorXd z0 = section_state(system.beam, w.final_q, w.final_qd);

  // 2. Newton on P^m(z) − z: the warm-up's period first, then the others.
  SteadyState st;
  st.sought = true;
  st.method = SteadyMethod::shooting;
  st.tolerance = options.steady_tolerance;
  const SectionMap map(system, options, control.stop);
  std::vector<int> periods;
  if (w.summary.steady_state.reached) periods.push_back(w.summary.steady_state.period_revolutions);
  for (int m = 1; m <= kMaxSteadyPeriod; ++m)
    if (std::find(periods.begin(), periods.end(), m) == periods.end()) periods.push_back(m);
  NewtonOutcome best;
  int period = 0;
  std::ostringstream tried;
  for (int m : periods) {
    if (control.stop && control.stop->stop_requested()) break;
    NewtonOutcome o = newton(map, z0, m, options, settings, control, wall0, warm_revolutions, st);
    st.newton_iterations += o.iterations;
    if (o.converged || o.distance < best.distance || best.z.size() == 0) {
      best = o;
      period = m;
    }
    if (o.converged) break;
    tried << (tried.tellp() > 0 ? "; " : "") << "period " << m << ": " << o.why << " (distance " << o.distance << ")";
    if (warm_revolutions + map.revolutions_run() > options.revolutions) break;
  }

  // 3. The orbit: m revolutions from the best state found, into the user's sink.
  const int m = std::max(period, 1);
  const Eigen::VectorXd z_star = best.z.size() ? best.z : z0;
  if (options.multipliers && best.converged) {
    if (best.jacobian.size() > 0) {
      // The last Newton step's Jacobian, taken within a step of z* (≈ the distance it closed): its
      // multipliers differ from those at z* by that much, far below their finite-difference accuracy.
      st.multipliers = floquet_multipliers(best.jacobian);
    } else {
      report(control, wall0, warm_revolutions + map.revolutions_run(), options.revolutions, best.distance,
             "multipliers: " + std::to_string(4 * system.beam.modes() + 1) + " map evaluations");
      add_multipliers(map, z_star, m, st);
    }
  }
  const InitialConditions orbit_start = section_start(system.beam, z_star);
  PassOptions orbit = options;
  orbit.until_steady = false;
  orbit.revolutions = m;
  orbit.end_angle_deg = system.beam.theta(0.0) * 180.0 / M_PI + 360.0 * m;
  PassResult r = run_pass(system, orbit_start, orbit, control);
  st.map_evaluations = map.evaluations();
  const int total = warm_revolutions + map.revolutions_run() + r.summary.revolutions;
  if (r.failure && r.failure->kind != FailureKind::interrupted) {
    // The orbit's run starts at t = 0 from a state the search reached: its t and θ (those of the
    // files) are named as such, and the state as what it is.
    std::ostringstream where;
    where << "in the run of the orbit from ";
    if (best.converged)
      where << "the state the shooting converged to";
    else if (best.z.size() == 0)
      where << "the state the warm-up ended in after its " << warm_revolutions
            << " revolutions (no Newton step was taken: the shooting did not converge)";
    else
      where << "the best state Newton found (the shooting did not converge)";
    where << "; t and θ count from that run's start: ";
    r.failure->message = where.str() + r.failure->message;
  }
  st.final_distance = r.failure ? best.distance : section_distance(section_state(system.beam, r.final_q, r.final_qd), z_star);
  st.reached = best.converged && !r.failure;
  st.after_revolutions = st.reached ? total : 0;
  st.period_revolutions = st.reached ? m : 0;
  std::ostringstream note;
  if (st.reached) {
    note << "reached by shooting after " << total << " revolutions (warm-up " << warm_revolutions << ", "
         << st.newton_iterations << (st.newton_iterations == 1 ? " Newton iteration, " : " Newton iterations, ")
         << st.map_evaluations << " map evaluations), "
         << period_words(m) << " (section distance over the period " << st.final_distance << " < "
         << options.steady_tolerance << ")";
    if (options.multipliers)
      note << "; " << (st.multipliers.empty() ? "multipliers not computed" : stability_words(st.multipliers));
  } else if (r.failure) {
    if (!best.converged) note << "not reached by shooting: " << tried.str() << "; ";
    note << "not reached: the orbit's run stopped (" << r.failure->message << ")";
  } else {
    note << "not reached by shooting: " << tried.str();
  }
  if (st.event_sequence_changes > 0)
    note << "; " << st.event_sequence_changes
         << " evaluations of the map changed the impacts or episodes (the event sequence is not fixed near this "
            "orbit: the map is not smooth there)";
  note << fallback_words(map.fallback());
  st.note = note.str();
  r.summary.steady_state = st;
  if (!st.reached && !r.failure) r.summary.warnings.push_back("no steady state: " + st.note);
  r.summary.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return r;
}

}  // namespace

PassResult run_to_steady_state(const System& system, const InitialConditions& initial, const PassOptions& options,
                               const PassControl& control, const ShootingSettings& settings) {
  if (!options.until_steady || options.revolutions <= 0) return run_pass(system, initial, options, control);
  return options.steady_method == SteadyMethod::shooting ? shooting(system, initial, options, control, settings)
                                                         : brute_force(system, initial, options, control);
}

}  // namespace rotbeam
