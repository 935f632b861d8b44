#include "rotbeam/sweep.hpp"

#include "rotbeam/brush.hpp"
#include "rotbeam/brush_output.hpp"

#include "rotbeam/atomic_file.hpp"
#include "rotbeam/folder_lock.hpp"
#include "rotbeam/case.hpp"
#include "rotbeam/detail/csv.hpp"
#include "rotbeam/detail/parse.hpp"
#include "rotbeam/pass_output.hpp"

#include <optional>
#include <span>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <set>

namespace rotbeam {

using detail::csv_field;

namespace {

std::vector<std::string> split_top_level(const std::string& text) {
  std::vector<std::string> out;
  std::string cur;
  int depth = 0;
  char quote = 0;  // the quote of the TOML string being read: '"' (basic, with \ escapes) or '\'' (literal)
  bool escaped = false;
  for (char c : text) {
    if (quote != 0) {
      if (escaped)
        escaped = false;
      else if (quote == '"' && c == '\\')
        escaped = true;
      else if (c == quote)
        quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    }
    const bool quoted = quote != 0;
    if (!quoted && c == '[') ++depth;
    if (!quoted && c == ']') --depth;
    if (c == ',' && depth == 0 && !quoted) {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

std::string number_literal(double v) {
  if (v == std::floor(v) && std::abs(v) < 1e15) return std::to_string(static_cast<long long>(v));
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  std::string s = buf;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

// sweep.csv's metric columns and where each sits in summary.json.
struct Metric {
  const char* column;
  const char* pointer;
};
const Metric kMetrics[] = {{"impacts", "/impacts"},
                           {"contact_episodes", "/contact_episodes"},
                           {"first_impact_deg", "/first_impact_deg"},
                           {"last_separation_deg", "/last_separation_deg"},
                           {"contact_time_s", "/contact_time_s"},
                           {"peak_normal_force_n", "/peak_normal_force_n"},
                           {"mean_normal_force_n", "/mean_normal_force_n"},
                           {"normal_impulse_n_s", "/normal_impulse_n_s"},
                           {"binned_peak_normal_force_n", "/binned_force/peak_normal_force_n"},
                           {"friction_work_j", "/friction_work_j"},
                           {"max_tip_deflection_ratio", "/max_tip_deflection_ratio"},
                           {"energy_audit_residual", "/energy_audit_residual"},
                           // The last complete revolution of a run over revolutions (the steady one):
                           // what a rub map reads (docs/surfaces.md).
                           {"last_revolution_impacts", "/last_revolution/impacts"},
                           {"last_revolution_peak_normal_force_n", "/last_revolution/peak_normal_force_n"},
                           {"last_revolution_normal_impulse_n_s", "/last_revolution/normal_impulse_n_s"},
                           {"last_revolution_friction_work_j", "/last_revolution/friction_work_j"},
                           {"last_revolution_max_tip_deflection_ratio", "/last_revolution/max_tip_deflection_ratio"},
                           {"steady_after_revolutions", "/steady_state/after_revolutions"},
                           {"f1_hz", "/natural_frequencies_hz/0"},
                           {"f2_hz", "/natural_frequencies_hz/1"},
                           {"f3_hz", "/natural_frequencies_hz/2"},
                           {"steps", "/steps"},
                           {"rhs_evaluations", "/rhs_evaluations"},
                           {"wall_time_s", "/wall_time_s"}};
// The columns of a sweep over brushes (docs/brush.md: the brush maps).
const Metric kBrushMetrics[] = {{"mean_normal_force_n", "/mean_normal_force_n"},
                                {"mean_tangential_force_n", "/mean_tangential_force_n"},
                                {"peak_normal_force_n", "/peak_normal_force_n"},
                                {"peak_tangential_force_n", "/peak_tangential_force_n"},
                                {"mean_hub_torque_n_m", "/mean_hub_torque_n_m"},
                                {"mean_hub_power_w", "/mean_hub_power_w"},
                                {"contact_zone_deg", "/contact_zone/angle_deg"},
                                {"contact_zone_width_m", "/contact_zone/width_m"},
                                {"depth_ratio", "/dimensionless/depth_ratio"},
                                {"speed_ratio", "/dimensionless/speed_ratio"},
                                {"force_ratio", "/dimensionless/force_ratio"},
                                {"steady_filaments", "/steady_filaments"},
                                {"failed_filaments", "/failed_filaments"},
                                {"wall_time_s", "/wall_time_s"}};

// True when a case's summary.json holds what resuming reads as summary_json wrote it: a config
// object, and a failure that is null or an object with the string kind and message. A damaged one
// (edited, or written by another program) makes the case incomplete: it is run again.
bool resumable_summary(const nlohmann::json& j) {
  if (!j.is_object() || !j.contains("config") || !j.contains("failure")) return false;
  const nlohmann::json& f = j["failure"];
  if (f.is_null()) return true;
  return f.is_object() && f.contains("kind") && f["kind"].is_string() && f.contains("message") &&
         f["message"].is_string();
}

}  // namespace

const char* sweep_status_name(SweepStatus s) {
  switch (s) {
    case SweepStatus::done: return "done";
    case SweepStatus::resumed: return "resumed";
    case SweepStatus::failed: return "failed";
    case SweepStatus::error: return "error";
    case SweepStatus::interrupted: return "interrupted";
  }
  return "?";
}

SweepAxis parse_sweep_axis(const std::string& spec) {
  const auto eq = spec.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == spec.size())
    throw ConfigError("--vary " + spec + ": expected KEY=V1,V2,… or KEY=A:B:N");
  SweepAxis axis;
  axis.key = spec.substr(0, eq);
  // Spaces around the key are not part of it, as for --set (" hub.speed_rpm" was an unknown key
  // whose suggestion read the same).
  axis.key.erase(0, axis.key.find_first_not_of(" \t"));
  axis.key.erase(axis.key.find_last_not_of(" \t") + 1);
  require_known_key(axis.key, "--vary");
  const std::string rest = spec.substr(eq + 1);
  if (rest.find_first_of("\n\r") != std::string::npos)
    throw ConfigError("--vary " + axis.key + ": a value holds a line break (give the values on one line)");
  const bool is_range = rest.find(':') != std::string::npos && rest.find_first_of("[\"'") == std::string::npos;
  if (is_range) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (std::size_t p; (p = rest.find(':', start)) != std::string::npos; start = p + 1) parts.push_back(rest.substr(start, p - start));
    parts.push_back(rest.substr(start));
    for (std::string& part : parts) {  // ' 3 : 5 :3' read "' 3 ' is not a number"; --set trims too
      const std::size_t from = part.find_first_not_of(" \t"), to = part.find_last_not_of(" \t");
      part = from == std::string::npos ? std::string() : part.substr(from, to - from + 1);
    }
    auto number = [&](const std::string& s) {
      double v = 0;
      if (!detail::parse_finite_number(s, v)) throw ConfigError("--vary " + spec + ": '" + s + "' is not a number");
      return v;
    };
    if (parts.size() != 3) throw ConfigError("--vary " + spec + ": a range is A:B:N");
    const double a = number(parts[0]), b = number(parts[1]), nd = number(parts[2]);
    if (nd < 1 || nd != std::floor(nd) || nd > 100000) throw ConfigError("--vary " + spec + ": N must be a whole number from 1 to 100000");
    const int n = static_cast<int>(nd);
    // B − A overflows for ends near the largest double (-1e308:1e308 gave nan): then each value is
    // weighed from both ends instead.
    const bool wide = !std::isfinite(b - a);
    // Integer ends are stepped exactly: through double, 1:9223372036854775807:2 gave
    // 9223372036854779904.0, "not an integer".
    long long ia = 0, ib = 0;
    const auto integer = [](const std::string& text, long long& v) {
      const std::size_t from = text.find_first_not_of(" \t"), to = text.find_last_not_of(" \t");
      const std::string t = from == std::string::npos ? std::string() : text.substr(from, to - from + 1);
      const char* first = t.c_str() + (!t.empty() && t[0] == '+' ? 1 : 0);
      const auto res = std::from_chars(first, t.c_str() + t.size(), v);
      return !t.empty() && res.ec == std::errc() && res.ptr == t.c_str() + t.size();
    };
    const bool integers = integer(parts[0], ia) && integer(parts[1], ib);
    for (int i = 0; i < n; ++i) {
      if (integers) {
        __extension__ using wide = __int128;  // (B − A)·i of two 64-bit ends fits in 128 bits
        const wide span = static_cast<wide>(ib) - ia, step = span * i;
        if (n == 1 || step % (n - 1) == 0) {
          const long long v = n == 1 ? ia : static_cast<long long>(ia + step / (n - 1));
          axis.values.push_back(std::to_string(v));
          continue;
        }
      }
      const double f = n == 1 ? 0.0 : static_cast<double>(i) / (n - 1);
      axis.values.push_back(number_literal(n == 1 ? a : wide ? a * (1.0 - f) + b * f : a + (b - a) * i / (n - 1)));
    }
  } else {
    for (const std::string& v : split_top_level(rest)) {
      if (v.empty()) throw ConfigError("--vary " + spec + ": an empty value");
      axis.values.push_back(v);
    }
  }
  return axis;
}

std::vector<SweepCase> sweep_cases(const std::vector<SweepAxis>& axes) {
  std::size_t total = 1;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j)
      if (axes[j].key == axes[i].key)
        throw ConfigError("--vary " + axes[i].key + ": the key is varied twice (give all its values in one --vary)");
    total *= axes[i].values.size();
    if (total > kMaxSweepCases)
      throw ConfigError("--vary: the grid has more than " + std::to_string(kMaxSweepCases) +
                        " cases; split the study into several sweeps");
  }
  std::vector<SweepCase> cases;
  for (std::size_t i = 0; i < total; ++i) {
    SweepCase c;
    c.index = static_cast<int>(i);
    std::size_t rem = i;
    c.values.resize(axes.size());
    for (std::size_t k = axes.size(); k-- > 0;) {
      c.values[k] = axes[k].values[rem % axes[k].values.size()];
      rem /= axes[k].values.size();
    }
    for (std::size_t k = 0; k < axes.size(); ++k) c.overrides.push_back(axes[k].key + "=" + c.values[k]);
    char name[32];
    std::snprintf(name, sizeof name, "case-%04zu", i + 1);
    c.folder = name;
    cases.push_back(c);
  }
  return cases;
}

SweepReport run_sweep(const std::vector<SweepAxis>& axes, const SweepOptions& options) {
  SweepReport report;
  report.axes = axes;
  report.cases = sweep_cases(axes);
  report.results.resize(report.cases.size());
  // Validate every case before running any.
  std::vector<Config> configs;
  for (const SweepCase& c : report.cases) {
    std::vector<std::string> overrides = options.base_overrides;
    overrides.insert(overrides.end(), c.overrides.begin(), c.overrides.end());
    try {
      configs.push_back(load_config(options.config_path, overrides));
    } catch (const ConfigError& e) {
      throw ConfigError(c.folder + " (" + [&] {
        std::string s;
        for (const std::string& o : c.overrides) s += (s.empty() ? "" : ", ") + o;
        return s;
      }() + "): " + e.what());
    }
  }
  // The cases' histories must fit on the disk, as for one run (check_history_fits, on the same
  // central estimate): checked before the folder is made (cases an earlier run finished are counted
  // too).
  {
    double need = 0.0;
    for (const Config& config : configs) {
      if (config.brush) continue;  // a brush keeps no history
      const HistoryEstimate e = estimate_history(build_case(config));
      if (e.known && !e.upper_bound) need += e.csv_bytes;
    }
    const double available = available_disk_bytes(options.dir);
    if (available > 0 && need > available)
      throw ConfigError("output.interval_s: the histories of the " + std::to_string(configs.size()) +
                        " cases would take about " + size_text(need) + ", more than the " + size_text(available) +
                        " free where " + options.dir.string() + " goes (sample less often)");
  }
  // A sweep is over brushes or over single filaments (a --vary of a brush key sets it in every case).
  report.brush = !configs.empty() && configs.front().brush.has_value();
  // A run's folder (its summary.json) is not made a sweep's as well: `plot` would draw one of the two.
  if (std::filesystem::exists(options.dir / "summary.json"))
    throw ConfigError("-o " + options.dir.string() + ": holds a run (summary.json), not a sweep; give another folder");
  if (std::filesystem::exists(options.dir / "manifest.json") && std::filesystem::exists(options.dir / "report.md"))
    throw ConfigError("-o " + options.dir.string() +
                      ": holds a reproduction (manifest.json, report.md), not a sweep; give another folder");
  std::optional<FolderLock> lock;  // one sweep at a time in a folder (each case folder has its own)
  try {
    prepare_output_folder(options.dir);
    lock.emplace(options.dir);
  } catch (const std::runtime_error& e) {
    throw ConfigError(std::string("-o ") + e.what());
  }

  // Finished earlier? A complete folder (summary.json and the files it lists, at their sizes) of
  // the same configuration, not interrupted.
  std::vector<std::size_t> todo;
  for (std::size_t i = 0; i < report.cases.size(); ++i) {
    nlohmann::json j;
    bool finished = false;
    // A case folder that is a link (to another case's folder, say) is not this case's: a resume
    // wrote through it into the other case's folder, and sweep.csv no longer described the files.
    // The link is removed and the case run into a folder of its own.
    const std::filesystem::path folder = options.dir / report.cases[i].folder;
    std::error_code link_ec;
    if (std::filesystem::is_symlink(std::filesystem::symlink_status(folder, link_ec))) {
      std::filesystem::remove(folder, link_ec);
      if (link_ec)
        throw ConfigError(folder.string() + ": a link where the case's folder goes, and it cannot be removed (" +
                          link_ec.message() + ")");
    } else if (complete_run_folder(folder, &j) && resumable_summary(j)) {
      const bool interrupted = j["failure"].is_object() && j["failure"]["kind"] == "interrupted";
      if (!interrupted && j["config"] == configs[i].to_json()) {
        report.results[i].summary = j;
        report.results[i].resumed = true;
        // A case that stopped on a diagnosed failure stays `failed`: resuming does not hide it.
        if (j["failure"].is_object()) {
          report.results[i].status = SweepStatus::failed;
          report.results[i].message = j["failure"]["kind"].get<std::string>() + ": " +
                                      j["failure"]["message"].get<std::string>() + " (computed by an earlier run)";
        } else {
          report.results[i].status = SweepStatus::resumed;
        }
        finished = true;
      }
    }
    if (finished)
      ++report.resumed;
    else
      todo.push_back(i);
  }

  // An older sweep.csv describes other cases (or an older state of these): until this sweep writes
  // its own at the end, the folder has no index, so that nothing reads a mix of two sweeps.
  if (!todo.empty()) {
    std::error_code ec;
    std::filesystem::remove(options.dir / "sweep.csv", ec);
    if (ec)
      throw std::runtime_error((options.dir / "sweep.csv").string() + ": cannot remove the older index (" +
                               ec.message() + ")");
  }

  std::mutex mutex;
  SweepProgress progress;
  progress.total = static_cast<int>(report.cases.size());
  progress.resumed = report.resumed;
  progress.finished = report.resumed;
  for (const SweepCaseResult& r : report.results) progress.failed += r.resumed && r.status == SweepStatus::failed;
  JobRunnerOptions runner;
  runner.threads = options.jobs;
  runner.stop = options.stop;
  runner.on_job_finished = [&](const JobProgress& p) {
    const std::size_t i = todo[p.job];
    ++progress.finished;
    const SweepStatus status = report.results[i].status;
    if (status == SweepStatus::failed || status == SweepStatus::error) ++progress.failed;
    progress.elapsed_s = p.elapsed_s;
    progress.eta_s = p.eta_s;
    progress.last = &report.cases[i];
    progress.last_result = &report.results[i];
    if (options.on_case_finished) options.on_case_finished(progress);
  };
  run_jobs(
      todo.size(),
      [&](std::size_t n) {
        const std::size_t i = todo[n];
        SweepCaseResult res;
        try {
          if (configs[i].brush) {
            // One brush per case, its filaments on this case's thread (the cases fill the cores).
            BrushFiles files(options.dir / report.cases[i].folder);
            BrushOptions brush_options;
            brush_options.threads = 1;
            brush_options.stop = options.stop;
            const BrushResult brush = run_brush(configs[i], brush_options);
            files.commit(brush, configs[i]);
            res.summary = brush_summary_json(brush, configs[i]);
            const std::optional<NumericalFailure>& f = brush.summary.failure;
            res.status = !f ? SweepStatus::done
                         : f->kind == FailureKind::interrupted ? SweepStatus::interrupted
                                                               : SweepStatus::failed;
            if (f)
              res.message = std::string(failure_name(f->kind)) + " (filament " +
                            std::to_string(brush.summary.failed_filament + 1) + "): " + f->message;
            std::lock_guard<std::mutex> lock(mutex);
            report.results[i] = res;
            return;
          }
          const Case c = build_case(configs[i]);
          PassFiles files(options.dir / report.cases[i].folder, configs[i].beam.modes, configs[i].simulation.history_revolutions);
          const PassResult pass = run_case(c, {&files, options.stop, {}});
          files.commit(pass, configs[i], *c.surface);
          res.summary = summary_json(pass, configs[i], *c.surface);
          if (!pass.failure)
            res.status = SweepStatus::done;
          else if (pass.failure->kind == FailureKind::interrupted)
            res.status = SweepStatus::interrupted;
          else
            res.status = SweepStatus::failed;
          if (pass.failure) res.message = std::string(failure_name(pass.failure->kind)) + ": " + pass.failure->message;
        } catch (const std::exception& e) {
          res.status = SweepStatus::error;
          res.message = e.what();
        }
        std::lock_guard<std::mutex> lock(mutex);
        report.results[i] = res;
      },
      runner);
  // Cases never started (an interrupted sweep) are reported as interrupted.
  for (std::size_t n = 0; n < todo.size(); ++n) {
    SweepCaseResult& r = report.results[todo[n]];
    if (r.summary.is_null() && r.status == SweepStatus::error && r.message.empty()) {
      r.status = SweepStatus::interrupted;
      r.message = "not run (interrupted)";
    }
  }
  for (const SweepCaseResult& r : report.results) {
    switch (r.status) {
      case SweepStatus::done: ++report.ran; break;
      case SweepStatus::failed: report.ran += r.resumed ? 0 : 1, ++report.failed; break;
      case SweepStatus::error: ++report.errors; break;
      case SweepStatus::interrupted: ++report.interrupted; break;
      case SweepStatus::resumed: break;
    }
  }
  write_file_atomically(options.dir / "sweep.csv", sweep_csv(report));
  std::set<std::string> ours;
  for (const SweepCase& c : report.cases) ours.insert(c.folder);
  std::error_code ec;
  for (const std::filesystem::directory_entry& e : std::filesystem::directory_iterator(options.dir, ec)) {
    const std::string name = e.path().filename().string();
    const bool case_name = name.size() > 5 && name.rfind("case-", 0) == 0 &&
                           name.find_first_not_of("0123456789", 5) == std::string::npos;
    std::error_code kind_ec;
    if (case_name && !ours.count(name) && e.is_directory(kind_ec)) ++report.other_case_folders;
  }
  return report;
}

std::string sweep_csv(const SweepReport& report) {
  std::string out = "case,folder";
  for (const SweepAxis& a : report.axes) {
    out += ',';
    out += csv_field(a.key);
  }
  out += ",status";
  const std::span<const Metric> metrics = report.brush ? std::span<const Metric>(kBrushMetrics) : std::span<const Metric>(kMetrics);
  for (const Metric& m : metrics) out += std::string(",") + m.column;
  out += ",message\n";
  for (std::size_t i = 0; i < report.cases.size(); ++i) {
    const SweepCase& c = report.cases[i];
    const SweepCaseResult& r = report.results[i];
    out += std::to_string(c.index + 1);
    out += ',';
    out += c.folder;
    for (const std::string& v : c.values) {
      out += ',';
      out += csv_field(v);
    }
    out += std::string(",") + sweep_status_name(r.status);
    for (const Metric& m : metrics) {
      out += ",";
      const nlohmann::json::json_pointer at(m.pointer);
      if (r.summary.is_object() && r.summary.contains(at) && r.summary[at].is_number()) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.17g", r.summary[at].get<double>());
        out += buf;
      }
    }
    out += ',';
    out += csv_field(r.message);
    out += '\n';
  }
  return out;
}

}  // namespace rotbeam
