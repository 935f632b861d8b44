#include "rotbeam/orbit_continuation.hpp"

#include "rotbeam/beam_model.hpp"
#include "rotbeam/case.hpp"
#include "rotbeam/modal_analysis.hpp"
#include "rotbeam/steady_state.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>

namespace rotbeam {

std::string parameter_literal(double v) {
  char buf[40];
  std::string s(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
  // A TOML float needs a '.' or an exponent; a whole number stays an integer literal, which the
  // float keys accept.
  return s;
}

std::vector<EngineOrderCrossing> engine_order_crossings(const BeamParameters& base, double lo_rpm, double hi_rpm,
                                                        int max_order) {
  std::vector<EngineOrderCrossing> out;
  if (!(hi_rpm > lo_rpm)) std::swap(lo_rpm, hi_rpm);
  if (!(hi_rpm > lo_rpm)) return out;
  constexpr int kNodes = 241;
  std::vector<double> speeds(kNodes);
  for (int i = 0; i < kNodes; ++i) speeds[static_cast<std::size_t>(i)] = lo_rpm + (hi_rpm - lo_rpm) * i / (kNodes - 1);
  const Eigen::MatrixXd f = frequencies_versus_speed(base, speeds);
  for (int k = 1; k <= max_order; ++k)
    for (Eigen::Index m = 0; m < f.cols(); ++m)
      for (int i = 0; i + 1 < kNodes; ++i) {
        const double s0 = speeds[static_cast<std::size_t>(i)], s1 = speeds[static_cast<std::size_t>(i) + 1];
        const double g0 = f(i, m) - k * s0 / 60.0, g1 = f(i + 1, m) - k * s1 / 60.0;
        if (!std::isfinite(g0) || !std::isfinite(g1) || (g0 > 0) == (g1 > 0) || g0 == g1) continue;
        const double th = g0 / (g0 - g1);
        const double s = s0 + th * (s1 - s0);
        out.push_back({k, static_cast<int>(m) + 1, s, k * s / 60.0});
      }
  return out;
}

namespace {

// The cases of the parameter's values, built once each and shared by the threads of a Jacobian (the
// last few kept: a point's stencil needs three values of the parameter).
class CaseCache {
public:
  explicit CaseCache(const ConfigAtValue& config_at) : config_at_(config_at) {}

  std::shared_ptr<const Case> at(double p) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (auto it = cases_.find(p); it != cases_.end()) return it->second;
    auto c = std::make_shared<const Case>(build_case(config_at_(parameter_literal(p))));
    cases_[p] = c;
    order_.push_back(p);
    if (order_.size() > kKept) {
      cases_.erase(order_.front());
      order_.pop_front();
    }
    return c;
  }

private:
  static constexpr std::size_t kKept = 8;
  const ConfigAtValue& config_at_;
  std::mutex mutex_;
  std::map<double, std::shared_ptr<const Case>> cases_;
  std::deque<double> order_;
};

constexpr int kReseedRevolutions = 60;
constexpr int kStartRevolutions = 100;  // the search at `from`; past it, the orbit is sought further on

// The options of a steady-state search by shooting of at most `revolutions` revolutions, its rows
// discarded (the start, and the reseeds past a stall).
PassOptions orbit_search(const Case& c, int revolutions) {
  PassOptions o = c.options;
  o.until_steady = true;
  o.steady_method = SteadyMethod::shooting;
  o.multipliers = false;
  o.revolutions = revolutions;
  o.end_angle_deg = c.beam->theta(0.0) * 180.0 / M_PI + 360.0 * revolutions;
  o.output_interval_s = 1e9;
  o.near_surface_gap_m = 0.0;
  return o;
}

OrbitMetrics metrics_of(const MapEvaluation& e, double omega, int period) {
  OrbitMetrics m;
  m.impacts = e.impacts;
  m.contact_episodes = e.contact_episodes;
  const PassSummary& s = e.summary;
  m.normal_impulse_n_s = s.ledger[LedgerTerm::normal_impulse];
  m.peak_normal_force_n = s.peak_normal_force_n;
  const double duration = period * 2.0 * M_PI / omega;
  m.mean_hub_power_w = s.ledger[LedgerTerm::hub_work] / duration;
  m.mean_hub_torque_n_m = m.mean_hub_power_w / omega;
  m.max_tip_deflection_ratio = s.max_tip_deflection_ratio;
  return m;
}

}  // namespace

void check_orbit_continuation(const ConfigAtValue& config_at, const OrbitContinuationOptions& options) {
  require_known_key(options.parameter, "--parameter");
  const std::string& key = options.parameter;
  for (const auto& k : describe_config_keys())
    if (k["name"] == key && k["type"].get<std::string>().find("number") == std::string::npos)
      throw ConfigError("--parameter " + key + ": a key of " + k["type"].get<std::string>() +
                        " values; continuation needs a number that varies continuously");
  if (!std::isfinite(options.from) || !std::isfinite(options.to))
    throw ConfigError("--from/--to: must be finite numbers");
  if (options.from == options.to)
    throw ConfigError("--from " + parameter_literal(options.from) + " --to " + parameter_literal(options.to) +
                      ": the range of " + key + " is empty");
  if (options.period < 0 || options.period > 64)
    throw ConfigError("--period " + std::to_string(options.period) + ": must be 1 … 64 revolutions (0: the steady state's)");
  const Config from = config_at(parameter_literal(options.from));
  const Config to = config_at(parameter_literal(options.to));
  if (from.brush)
    throw ConfigError("brush.*: continuation follows one filament's orbits; give a configuration without [brush]");
  const int n_from = build_case(from).beam->modes(), n_to = build_case(to).beam->modes();
  if (n_from != n_to)
    throw ConfigError(key + ": changes the number of coordinates (" + std::to_string(n_from) + " at " +
                      parameter_literal(options.from) + ", " + std::to_string(n_to) + " at " +
                      parameter_literal(options.to) + "): an orbit cannot be continued across it");
}

OrbitContinuation continue_orbits(const ConfigAtValue& config_at, const OrbitContinuationOptions& options,
                                  const std::function<void(const ContinuationProgress&)>& on_point) {
  const auto wall0 = std::chrono::steady_clock::now();
  check_orbit_continuation(config_at, options);
  const std::string& key = options.parameter;
  OrbitContinuation out;
  out.options = options;
  out.config_from = config_at(parameter_literal(options.from));
  const Case start_case = build_case(out.config_from);
  out.modes = start_case.beam->modes();
  const StopToken* stop = options.settings.stop;

  // 1. The start: the steady state at `from` by shooting from the configuration's start.
  const int cap = start_case.options.revolutions;
  const PassOptions search = orbit_search(start_case, cap > 0 ? std::min(cap, kStartRevolutions) : kStartRevolutions);
  DiscardSink discard;
  const PassResult found = run_to_steady_state(start_case.system(), start_case.initial, search, {&discard, stop, {}});
  const SteadyState& st = found.summary.steady_state;
  out.period = options.period > 0 ? options.period : (st.reached ? st.period_revolutions : 1);
  std::ostringstream note;
  if (found.failure && found.failure->kind == FailureKind::interrupted) {
    out.result.stopped = true;
    out.result.branches.push_back({0, out.period, 0, "the start", "stopped on request while the start was sought"});
    out.start_note = "stopped on request";
    return out;
  }
  if (found.final_q.size() == 0) {
    out.result.failure = found.failure;
    out.result.branches.push_back( {0, out.period, 0, "the start", "the start's run failed: " + (found.failure ? found.failure->message : std::string("no state"))});
    out.start_note = out.result.branches.back().end;
    return out;
  }
  note << "steady state at " << key << " = " << parameter_literal(options.from) << ": " << st.note;
  out.start_note = note.str();
  const Eigen::VectorXd z0 = section_state(*start_case.beam, found.final_q, found.final_qd);

  // 2. The map at any value of the parameter, and the continuation.
  CaseCache cases(config_at);
  const auto evaluate = [&cases, stop](const Eigen::VectorXd& z, double p, int period, bool tangent) {
    MapValue v;
    std::shared_ptr<const Case> c;
    try {
      c = cases.at(p);
    } catch (const std::exception& e) {  // a value the key refuses, or the model cannot be built there
      v.failure = NumericalFailure{FailureKind::initial_state, 0.0, 0.0, e.what()};
      return v;
    }
    const System system = c->system();  // SectionMap keeps a reference to it
    const SectionMap section(system, c->options, stop);
    MapEvaluation e;
    try {
      e = section(z, period, tangent);
    } catch (const std::exception& x) {
      v.failure = NumericalFailure{FailureKind::non_finite, 0.0, 0.0, x.what()};
      return v;
    }
    v.failure = e.failure;
    if (!e.complete) return v;
    v.z = e.z;
    v.metrics = metrics_of(e, c->beam->hub_motion().omega, period);
    v.jacobian = e.jacobian;
    v.jacobian_fallback = e.tangent_lost;
    return v;
  };
  const ParametrisedMap map = [&evaluate](const Eigen::VectorXd& z, double p, int period) {
    return evaluate(z, p, period, false);
  };
  // simulation.jacobian: ∂P/∂z from the variational equations (one run), or central differences.
  ParametrisedJacobian with_jacobian;
  if (start_case.options.jacobian == JacobianMethod::variational)
    with_jacobian = [&evaluate](const Eigen::VectorXd& z, double p, int period) { return evaluate(z, p, period, true); };
  // After a stall: the steady state a little further on, by shooting from the last state the branch
  // reached (at most kReseedRevolutions revolutions: where no orbit settles, the range is crossed in
  // restart_jump steps).
  const ReseedFunction reseed = [&cases, stop](double p, const Eigen::VectorXd& z_near) -> std::optional<Reseed> {
    std::shared_ptr<const Case> c;
    try {
      c = cases.at(p);
    } catch (const std::exception&) {
      return std::nullopt;
    }
    const InitialConditions ic = section_start(*c->beam, z_near, c->initial);
    const PassOptions o = orbit_search(*c, kReseedRevolutions);
    DiscardSink sink;
    PassResult r;
    try {
      r = run_to_steady_state(c->system(), ic, o, {&sink, stop, {}});
    } catch (const std::exception&) {
      return std::nullopt;
    }
    const SteadyState& st = r.summary.steady_state;
    if (r.failure || !st.reached) return std::nullopt;
    return Reseed{section_state(*c->beam, r.final_q, r.final_qd), st.period_revolutions, st.note};
  };
  ContinuationSettings settings = options.settings;
  settings.tolerance = options.tolerance > 0 ? options.tolerance : out.config_from.simulation.steady_tolerance;
  out.result = continue_fixed_points(map, z0, options.from, options.to, out.period, settings, on_point, reseed,
                                     with_jacobian);
  // The first branch's period: the start found further on may have another than the one sought.
  if (!out.result.points.empty()) out.period = out.result.points.front().period;
  if (key == "hub.speed_rpm")
    out.crossings = engine_order_crossings(out.config_from.beam, std::min(options.from, options.to),
                                           std::max(options.from, options.to));
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return out;
}

}  // namespace rotbeam
