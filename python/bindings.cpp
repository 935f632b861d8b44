// rotbeam._core: the C++ library's jobs for Python, with the GIL released while they compute.
// Configuration errors raise rotbeam._core.ConfigError (a ValueError) with the CLI's message.
#include "rotbeam/continuation_output.hpp"
#include "rotbeam/job_runner.hpp"
#include "rotbeam/orbit_continuation.hpp"
#include "rotbeam/wear_output.hpp"
#include "rotbeam/wear_run.hpp"
#include "rotbeam/brush.hpp"
#include "rotbeam/units.hpp"
#include "rotbeam/brush_output.hpp"
#include "rotbeam/case.hpp"
#include "rotbeam/process_memory.hpp"
#include "rotbeam/impact_output.hpp"
#include "rotbeam/beam_factory.hpp"
#include "rotbeam/modal_analysis.hpp"
#include "rotbeam/output_columns.hpp"
#include "rotbeam/static_equilibrium.hpp"
#include "rotbeam/pass_output.hpp"
#include "rotbeam/sweep.hpp"
#include "rotbeam/version.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <future>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace py = pybind11;
using namespace rotbeam;

namespace {

// A number in a message as the caller wrote it: the shortest text that reads back as v (-1, not
// -1.000000; 1e-05, not 0.000010).
std::string shortest(double v) {
  char buf[40];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

// A computed time in a message, with six significant digits as the command line gives it (a
// failure before 1 µs read t = 0.000000 s with six fixed decimals).
std::string significant(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

py::object from_json(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

using Values = std::vector<std::pair<std::string, std::string>>;  // (dotted key, TOML value), never pasted

Config load(const std::optional<std::string>& path, const Values& values) { return load_config_values(path, values); }

// Runs `work(stop)` on a worker thread while the calling (Python) thread waits with the GIL released,
// checking for signals every 50 ms: Ctrl-C requests a stop on the token, the pass ends at its next
// step, and the KeyboardInterrupt is raised at once (the partial result is dropped).
template <class Work>
auto interruptible(Work&& work) -> decltype(work(std::declval<const StopToken&>())) {
  using Result = decltype(work(std::declval<const StopToken&>()));
  StopToken stop;
  std::promise<Result> promise;
  std::future<Result> future = promise.get_future();
  std::thread worker([&] {
    try {
      promise.set_value(work(stop));
    } catch (...) {
      promise.set_exception(std::current_exception());
    }
  });
  bool interrupted = false;
  {
    py::gil_scoped_release release;
    while (future.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) {
        stop.request_stop();
        interrupted = true;
        break;
      }
    }
    future.wait();
  }
  worker.join();
  if (interrupted) throw py::error_already_set();
  return future.get();
}

py::dict history_arrays(const PassResult& r, int n) {
  const std::size_t rows = r.history.size();
  auto column = [&](auto get) {
    py::array_t<double> a(static_cast<py::ssize_t>(rows));
    auto m = a.mutable_unchecked<1>();
    for (std::size_t i = 0; i < rows; ++i) m(static_cast<py::ssize_t>(i)) = get(r.history[i]);
    return a;
  };
  py::dict h;
  h["t_s"] = column([](const HistoryRow& x) { return x.t; });
  h["theta_deg"] = column([](const HistoryRow& x) { return x.theta * 180.0 / M_PI; });
  py::list phase;
  for (const HistoryRow& x : r.history) phase.append(phase_name(x.phase));
  h["phase"] = py::module_::import("numpy").attr("array")(phase);
  h["x_tip_m"] = column([](const HistoryRow& x) { return x.x_tip; });
  h["y_tip_m"] = column([](const HistoryRow& x) { return x.y_tip; });
  h["gap_m"] = column([](const HistoryRow& x) { return x.gap; });
  h["vx_m_s"] = column([](const HistoryRow& x) { return x.vx; });
  h["vy_m_s"] = column([](const HistoryRow& x) { return x.vy; });
  h["normal_force_n"] = column([](const HistoryRow& x) { return x.normal_force; });
  h["friction_force_n"] = column([](const HistoryRow& x) { return x.friction_force; });
  h["lambda_n"] = column([](const HistoryRow& x) { return x.lambda; });
  for (int i = 0; i < n; ++i)
    h[py::str("q" + std::to_string(i + 1) + "_m")] = column([i](const HistoryRow& x) { return x.q[i]; });
  for (int i = 0; i < n; ++i)
    h[py::str("qd" + std::to_string(i + 1) + "_m_s")] = column([i](const HistoryRow& x) { return x.qd[i]; });
  h["jacobi_j"] = column([](const HistoryRow& x) { return x.jacobi; });
  h["hub_torque_n_m"] = column([](const HistoryRow& x) { return x.hub_torque; });
  return h;
}

py::list event_dicts(const PassResult& r) {
  py::list events;
  const py::object nan = py::float_(NAN);
  for (const PassEvent& e : r.events) {
    py::dict d;
    d["t_s"] = e.t;
    d["theta_deg"] = e.theta * 180.0 / M_PI;
    d["kind"] = event_name(e.kind);
    d["y_tip_m"] = e.y_tip;
    d["vx_before_m_s"] = e.vx_before;
    d["vx_after_m_s"] = e.vx_after;
    d["restitution"] = e.restitution;
    d["impulse_n_s"] = e.impulse;
    d["tangential_impulse_n_s"] = e.tangential_impulse;
    d["hub_work_j"] = e.hub_work;
    d["impact_loss_j"] = e.impact_loss;
    d["surface_work_j"] = e.surface_work;
    d["detail"] = e.detail;
    events.append(d);
  }
  return events;
}

py::tuple run(const std::optional<std::string>& path, const Values& overrides) {
  const Config config = load(path, overrides);
  const Case c = build_case(config);
  check_history_fits(c, available_memory_bytes(), true);  // the whole history is kept in memory
  const PassResult result = interruptible([&](const StopToken& stop) { return run_case(c, {nullptr, &stop}); });
  const nlohmann::json summary = summary_json(result, config, *c.surface);
  const std::string wear = wear_profile_csv(
      wear_report(result, config.wear, *c.surface, config.beam.diameter_m, config.simulation.wear_profile_bins), config.wear);
  return py::make_tuple(from_json(summary), history_arrays(result, coordinate_count(config.beam)), event_dicts(result),
                        py::bytes(revolutions_csv(result, coordinate_count(config.beam))), py::bytes(force_bins_csv(result)),
                        py::bytes(wear));
}

py::tuple brush(const std::optional<std::string>& path, const Values& overrides, int threads) {
  const Config config = load(path, overrides);
  if (!config.brush)
    throw ConfigError("brush: the configuration has no [brush] section (give brush.filaments, e.g. {\"brush.filaments\": 24})");
  if (threads < 0) throw ConfigError("jobs = " + std::to_string(threads) + ": must be >= 0 (0: all cores)");
  const BrushResult result = interruptible([&](const StopToken& stop) {
    BrushOptions options;
    options.threads = threads;
    options.stop = &stop;
    return run_brush(config, options);
  });
  const double omega = rad_per_s_from_rpm(config.beam.speed_rpm);
  return py::make_tuple(from_json(brush_summary_json(result, config)), py::bytes(workpiece_csv(result, omega)),
                        py::bytes(profile_csv(result, omega)), py::bytes(filaments_csv(result)),
                        py::bytes(wear_profile_csv(brush_wear_report(result, config), config.wear)),
                        py::bytes(representatives_csv(result)),
                        py::bytes(spectrum_csv(result, omega, config.brush->filaments)));
}

py::tuple wear(const std::optional<std::string>& path, const Values& overrides, double hours, int steps) {
  const Config config = load(path, overrides);
  if (config.brush) throw ConfigError("brush: wear() runs one filament; leave out the [brush] keys");
  WearRunOptions options;
  options.hours = hours;
  options.steps = steps;
  const WearRun result = interruptible([&](const StopToken& stop) {
    WearRunOptions o = options;
    o.stop = &stop;
    return run_wear(config, o);
  });
  return py::make_tuple(from_json(wear_run_json(result, config, options)), py::bytes(wear_history_csv(result)),
                        py::bytes(wear_depth_csv(result, config.wear)));
}

py::tuple continue_orbits_py(const std::optional<std::string>& path, const Values& overrides, const std::string& parameter,
                          double from, double to, int period, double tolerance, double step, double max_step,
                          int max_points, bool doubling, int threads) {
  const Config base = load(path, overrides);
  if (base.brush) throw ConfigError("brush: continue_orbits() follows one filament; leave out the [brush] keys");
  require_known_key(parameter, "parameter");
  if (!(step >= ContinuationSettings{}.min_step) || !(max_step >= step) || !std::isfinite(max_step))
    throw ConfigError("step = " + shortest(step) + ", max_step = " + shortest(max_step) + ": must be at least " +
                      shortest(ContinuationSettings{}.min_step) + " with max_step >= step");
  if (max_points < 2 || max_points > 100000)
    throw ConfigError("max_points = " + std::to_string(max_points) + ": must be 2 … 100000");
  if (tolerance < 0 || !std::isfinite(tolerance))
    throw ConfigError("tolerance = " + shortest(tolerance) + ": must be a positive number (0: simulation.steady_tolerance)");
  OrbitContinuationOptions options;
  options.parameter = parameter;
  options.from = from;
  options.to = to;
  options.period = period;
  options.tolerance = tolerance;
  options.settings.initial_step = step;
  options.settings.max_step = max_step;
  options.settings.max_points = max_points;
  options.settings.switch_period_doubling = doubling;
  options.settings.threads = default_threads(threads);
  const ConfigAtValue config_at = [&](const std::string& literal) {
    Values v = overrides;
    v.emplace_back(parameter, literal);
    return load(path, v);
  };
  const OrbitContinuation run = interruptible([&](const StopToken& stop) {
    OrbitContinuationOptions o = options;
    o.settings.stop = &stop;
    return continue_orbits(config_at, o);
  });
  return py::make_tuple(from_json(continuation_json(run)), py::bytes(branch_csv(run)));
}

py::object impact(const std::optional<std::string>& path, const Values& overrides) {
  const Config config = load(path, overrides);
  const Case c = build_case(config);
  const FirstImpactResult r = interruptible([&](const StopToken& stop) { return run_first_impact(c, {nullptr, &stop}); });
  if (r.failure)
    throw std::runtime_error(std::string("numerical failure (") + failure_name(r.failure->kind) + ") at t = " +
                             significant(r.failure->t) + " s before the first impact: " + r.failure->message);
  if (!r.found) return py::none();
  return from_json(impact_json(r, config));
}

py::tuple modes(const std::optional<std::string>& path, const Values& overrides,
                const std::optional<std::vector<double>>& requested) {
  const Config config = load(path, overrides);
  if (requested && requested->empty()) throw ConfigError("speeds_rpm: empty (give speeds, or None for the defaults)");
  const std::vector<double> speeds_rpm = requested ? *requested : default_mode_speeds_rpm(config.beam.speed_rpm);
  if (speeds_rpm.size() > 100000)  // as `rotbeam modes --speeds-rpm A:B:N`
    throw ConfigError("speeds_rpm: " + std::to_string(speeds_rpm.size()) + " speeds, more than 100000");
  for (double s : speeds_rpm)
    if (!(s >= 0.0 && s <= 1e6))
      throw ConfigError("speeds_rpm: " + shortest(s) + " must be in [0, 1000000] rpm");
  const Eigen::MatrixXd f = interruptible(
      [&](const StopToken& stop) { return frequencies_versus_speed(config.beam, speeds_rpm, &stop); });
  py::array_t<double> freq({static_cast<py::ssize_t>(f.rows()), static_cast<py::ssize_t>(f.cols())});
  auto m = freq.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < f.rows(); ++i)
    for (Eigen::Index k = 0; k < f.cols(); ++k) m(i, k) = f(i, k);
  py::array_t<double> speeds(static_cast<py::ssize_t>(speeds_rpm.size()), speeds_rpm.data());
  return py::make_tuple(speeds, freq);
}

// The static equilibrium under a tip load (`rotbeam static --json`): tip_x_m, tip_y_m, q, ….
py::dict static_load(const std::optional<std::string>& path, const Values& overrides, double tip_load_n) {
  if (!std::isfinite(tip_load_n)) throw ConfigError("tip_load_n = " + shortest(tip_load_n) + ": must be a finite number of newtons");
  const Config config = load(path, overrides);
  if (config.brush) throw ConfigError("brush: static takes one filament's configuration, not a brush's");
  const auto beam = make_beam_model(config.beam);
  const StaticEquilibrium s =
      interruptible([&](const StopToken& stop) { return static_equilibrium(*beam, tip_load_n, &stop); });
  py::dict d;
  d["theory"] = beam_theory_name(config.beam.theory);
  d["modes"] = config.beam.modes;
  d["speed_rpm"] = config.beam.speed_rpm;
  d["tip_load_n"] = tip_load_n;
  d["tip_x_m"] = s.tip_x;
  d["tip_y_m"] = s.tip_y;
  d["q"] = py::array_t<double>(static_cast<py::ssize_t>(s.q.size()), s.q.data());
  d["residual_n"] = s.residual;
  d["iterations"] = s.iterations;
  d["load_steps"] = s.load_steps;
  d["warnings"] = static_warnings(*beam, s, tip_load_n, config.simulation.deflection_warning_ratio);
  return d;
}

// The filament's centreline in the hub frame for each row of q (frames × n) at the points xi
// (ascending in [0, 1]): an array frames × points × 2 [m] (BeamModel::shape).
py::array_t<double> filament_shape(const std::optional<std::string>& path, const Values& overrides,
                                   const py::array_t<double, py::array::c_style | py::array::forcecast>& q,
                                   const py::array_t<double, py::array::c_style | py::array::forcecast>& xi) {
  const Config config = load(path, overrides);
  const Case c = build_case(config);
  const int n = c.beam->modes();
  if (q.ndim() != 2 || q.shape(1) != n)
    throw ConfigError("q: must be an array of frames x " + std::to_string(n) + " modal coordinates");
  if (xi.ndim() != 1 || xi.shape(0) < 1) throw ConfigError("xi: must be a non-empty 1-D array of points in [0, 1]");
  const py::ssize_t frames = q.shape(0), points = xi.shape(0);
  py::array_t<double> out({frames, points, static_cast<py::ssize_t>(2)});
  const Eigen::Map<const Eigen::VectorXd> x(xi.data(), points);
  auto o = out.mutable_unchecked<3>();
  Eigen::MatrixXd r(points, 2);
  for (py::ssize_t f = 0; f < frames; ++f) {
    const Eigen::Map<const Eigen::VectorXd> qf(q.data(f, 0), n);
    c.beam->shape(qf, x, r);
    for (py::ssize_t k = 0; k < points; ++k) {
      o(f, k, 0) = r(k, 0);
      o(f, k, 1) = r(k, 1);
    }
  }
  return out;
}

using Axes = std::vector<std::pair<std::string, std::vector<std::string>>>;  // (key, TOML literals)

// The axes of a Python sweep: known keys (as --vary's, named `vary`), each with values.
std::vector<SweepAxis> sweep_axes(const Axes& given) {
  std::vector<SweepAxis> axes;
  for (const auto& [key, values] : given) {
    require_known_key(key, "vary");
    if (values.empty()) throw ConfigError("vary " + printable(key) + ": no values (give at least one)");
    axes.push_back({key, values});
  }
  if (axes.empty()) throw ConfigError("vary: give at least one key and its values, e.g. {\"hub.speed_rpm\": [550, 3000]}");
  return axes;
}

// A case's configuration: the base (a file's path, or its text named `name`, with (key, value)
// overrides) and the case's values applied last, keys taken whole.
CaseLoader python_loader(const std::optional<std::string>& path, const std::optional<std::string>& text,
                         const std::string& name, const Values& base, const std::vector<SweepAxis>& axes) {
  return [path, text, name, base, axes](const SweepCase& c) {
    Values values = base;
    for (std::size_t k = 0; k < axes.size(); ++k) values.emplace_back(axes[k].key, c.values[k]);
    return text ? load_config_text_values(*text, name, values) : load_config_values(path, values);
  };
}

// The columns of every CSV file of a run or a brush (output_columns.hpp): [{name, columns: [{name,
// unit, kind, description, words}]}], for the Python module's reader.
py::list output_column_table() {
  static const char* const kKinds[] = {"number", "optional_number", "integer", "boolean", "word", "text"};
  py::list files;
  for (const OutputFile& f : output_files()) {
    py::list columns;
    for (const OutputColumn& c : f.columns) {
      py::dict d;
      d["name"] = c.name;
      d["unit"] = c.unit;
      d["kind"] = kKinds[static_cast<int>(c.kind)];
      d["description"] = c.description;
      d["words"] = py::cast(c.words);
      columns.append(d);
    }
    py::dict file;
    file["name"] = f.name;
    file["columns"] = columns;
    files.append(file);
  }
  return files;
}

py::list metric_table(bool brush) {
  py::list out;
  for (const SweepMetric& m : sweep_metrics(brush)) out.append(py::make_tuple(m.column, m.units, m.description));
  return out;
}

// A sweep's grid with every case validated: ([values of each case], sweep.json's description of the
// whole grid, [(column, units, description)] of its metrics).
py::tuple sweep_plan(const std::optional<std::string>& path, const Values& base, const Axes& given) {
  const std::vector<SweepAxis> axes = sweep_axes(given);
  const SweepPlan plan = plan_sweep(axes, python_loader(path, std::nullopt, "", base, axes));
  py::list cases;
  for (const SweepCase& c : plan.cases) cases.append(py::cast(c.values));
  return py::make_tuple(cases, from_json(sweep_description(plan, Shard{})), metric_table(plan.brush));
}

// Runs the cases `indices` (0-based, of the grid of `given`) in memory on `threads` threads (0: all
// cores) with the GIL released: [(status, [metric values, NaN where none], message, seconds the
// case took)] in the order of `indices`. `progress(finished)` is called from this (Python) thread as cases finish; Ctrl-C
// stops the running cases and raises KeyboardInterrupt.
py::list sweep_run(const std::optional<std::string>& path, const std::optional<std::string>& text,
                   const std::string& name, const Values& base, const Axes& given, const std::vector<std::size_t>& indices,
                   int threads, const py::object& progress) {
  if (threads < 0) throw ConfigError("jobs = " + std::to_string(threads) + ": must be >= 0 (0: all cores)");
  const std::vector<SweepAxis> axes = sweep_axes(given);
  const std::size_t total = sweep_grid_size(axes);  // a task loads its own cases only, not the grid's
  const CaseLoader load = python_loader(path, text, name, base, axes);
  std::vector<Config> configs;
  for (std::size_t i : indices) {
    if (i >= total)
      throw ConfigError("case index " + std::to_string(i) + ": the grid has " + std::to_string(total) + " cases");
    configs.push_back(load(sweep_case_at(axes, i)));
  }
  std::vector<SweepCaseResult> results(configs.size());
  std::vector<double> seconds(configs.size(), 0.0);
  StopToken stop;
  std::atomic<std::size_t> finished{0};
  std::exception_ptr failure;
  std::promise<void> done;
  std::future<void> finished_all = done.get_future();
  std::thread worker([&] {
    try {
      JobRunnerOptions runner;
      runner.threads = threads;
      runner.stop = &stop;
      run_jobs(configs.size(), [&](std::size_t k) {
        const auto start = std::chrono::steady_clock::now();
        results[k] = run_sweep_case(configs[k], &stop);
        seconds[k] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        ++finished;
      }, runner);
    } catch (...) {
      failure = std::current_exception();
    }
    done.set_value();
  });
  bool interrupted = false;
  std::size_t reported = 0;
  std::optional<py::error_already_set> progress_error;
  {
    py::gil_scoped_release release;
    while (finished_all.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) {
        stop.request_stop();
        interrupted = true;
        break;
      }
      const std::size_t now = finished;
      if (!progress.is_none() && now != reported) {
        reported = now;
        try {
          progress(now);
        } catch (py::error_already_set& e) {
          stop.request_stop();
          progress_error = std::move(e);
          break;
        }
      }
    }
  }
  worker.join();
  if (interrupted) throw py::error_already_set();
  if (progress_error) throw *progress_error;
  if (failure) std::rethrow_exception(failure);
  if (!progress.is_none() && finished != reported) progress(static_cast<std::size_t>(finished));
  py::list out;
  for (std::size_t k = 0; k < results.size(); ++k) {
    SweepCaseResult& r = results[k];
    if (r.summary.is_null() && r.status == SweepStatus::error && r.message.empty()) {
      r.status = SweepStatus::interrupted;
      r.message = "not run (interrupted)";
    }
    py::list metrics;
    for (const SweepMetric& m : sweep_metrics(configs[k].brush.has_value())) {
      const std::optional<double> v = sweep_metric_value(r.summary, m);
      metrics.append(v ? *v : NAN);
    }
    out.append(py::make_tuple(sweep_status_name(r.status), metrics, r.message, seconds[k]));
  }
  return out;
}

py::tuple parse_axis(const std::string& spec) {
  const SweepAxis a = parse_sweep_axis(spec);
  return py::make_tuple(a.key, a.values);
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "rotbeam's C++ core: whole passes, first impacts and modal analysis of a spinning filament";
  static py::exception<ConfigError> config_error(m, "ConfigError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ConfigError& e) {
      PyErr_SetString(config_error.ptr(), e.what());
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(config_error.ptr(), e.what());
    }
  });
  m.def("run", &run, py::arg("path"), py::arg("overrides"),
        "A whole pass: (summary dict, history dict of arrays, list of event dicts, revolutions.csv's text, "
        "force_bins.csv's text, wear_profile.csv's text).");
  m.def("brush", &brush, py::arg("path"), py::arg("overrides"), py::arg("threads"),
        "A brush at its steady state: (summary dict, workpiece.csv's, profile.csv's, filaments.csv's, "
        "wear_profile.csv's, representatives.csv's and spectrum.csv's text).");
  m.def("wear", &wear, py::arg("path"), py::arg("overrides"), py::arg("hours"), py::arg("steps"),
        "Wear over hours of operation: (summary dict, wear_history.csv's and wear_depth.csv's text).");
  m.def("continue_orbits", &continue_orbits_py, py::arg("path"), py::arg("overrides"), py::arg("parameter"),
        py::arg("start"), py::arg("stop"), py::arg("period"), py::arg("tolerance"), py::arg("step"),
        py::arg("max_step"), py::arg("max_points"), py::arg("doubling"), py::arg("threads"),
        "Continuation of the periodic orbit in one key: (summary dict, branch.csv's text).");
  m.def("impact", &impact, py::arg("path"), py::arg("overrides"),
        "The first impact as a dict (the fields of `rotbeam impact --json`), or None without impact.");
  m.def("modes", &modes, py::arg("path"), py::arg("overrides"), py::arg("speeds_rpm"),
        "Natural frequencies: (speeds_rpm array, frequencies_hz 2-D array); None means the default speeds.");
  m.def("static", &static_load, py::arg("path"), py::arg("overrides"), py::arg("tip_load_n"),
        "The static equilibrium under a tip load normal to the undeformed filament (rotbeam static --json).");
  m.def("filament_shape", &filament_shape, py::arg("path"), py::arg("overrides"), py::arg("q"), py::arg("xi"),
        "The centreline in the hub frame [m] for each row of q (frames x n) at the points xi: frames x points x 2.");
  m.def("config_keys", &config_keys, "Every configuration key, 'section.key'.");
  m.def("sweep_plan", &sweep_plan, py::arg("path"), py::arg("overrides"), py::arg("axes"),
        "A sweep's grid, every case validated: ([values of each case], sweep.json's description, "
        "[(column, units, description)] of the metrics).");
  m.def("sweep_run", &sweep_run, py::arg("path"), py::arg("text"), py::arg("name"), py::arg("overrides"), py::arg("axes"),
        py::arg("indices"), py::arg("threads"), py::arg("progress") = py::none(),
        "Runs the cases `indices` of a sweep's grid in memory: [(status, [metric values], message, seconds)].");
  m.def("output_columns", &output_column_table,
        "The columns of every CSV file of a run or a brush: [{name, columns: [{name, unit, kind, description, "
        "words}]}] ('q{i}_m': one column per mode).");
  m.def("sweep_metrics", &metric_table, py::arg("brush"),
        "The metric columns of sweep.csv: [(column, units, description)], a filament's or a brush's.");
  m.def("parse_sweep_axis", &parse_axis, py::arg("spec"),
        "`--vary` text (KEY=V1,V2,… or KEY=A:B:N) as (key, [TOML literals]).");
  m.attr("__version__") = kVersion;

  // The key table (rotbeam keys --json): a list of dicts, one per key, in the table's order.
  m.def(
      "keys", [] { return py::module_::import("json").attr("loads")(describe_config_keys().dump()); },
      "Every configuration key as `rotbeam keys --json` lists it: name, type, unit, default, unset, allowed, doc.");
}
