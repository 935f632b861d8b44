#include "rotbeam/sweep.hpp"

#include "rotbeam/brush.hpp"
#include "rotbeam/brush_output.hpp"

#include "rotbeam/atomic_file.hpp"
#include "rotbeam/folder_lock.hpp"
#include "rotbeam/case.hpp"
#include "rotbeam/detail/csv.hpp"
#include "rotbeam/detail/parse.hpp"
#include "rotbeam/pass_output.hpp"
#include "rotbeam/version.hpp"

#include <optional>
#include <span>
#include <charconv>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <map>
#include <numeric>
#include <mutex>
#include <set>
#include <unistd.h>

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

// sweep.csv's metric columns: where each sits in summary.json, its units, what it is.
const SweepMetric kMetrics[] = {
    {"impacts", "/impacts", "1", "momentum-balance impacts"},
    {"contact_episodes", "/contact_episodes", "1", "episodes of sustained contact"},
    {"first_impact_deg", "/first_impact_deg", "degree", "hub angle of the first impact"},
    {"last_separation_deg", "/last_separation_deg", "degree", "hub angle of the last separation"},
    {"contact_time_s", "/contact_time_s", "s", "total time in sustained contact"},
    {"peak_normal_force_n", "/peak_normal_force_n", "N", "largest normal force in sustained contact"},
    {"mean_normal_force_n", "/mean_normal_force_n", "N", "mean normal force in sustained contact"},
    {"normal_impulse_n_s", "/normal_impulse_n_s", "N s", "normal impulse of contact and impacts"},
    {"binned_peak_normal_force_n", "/binned_force/peak_normal_force_n", "N",
     "peak of the normal force over hub-angle bins, impacts counted as momentum"},
    {"friction_work_j", "/friction_work_j", "J", "work of friction on the tip"},
    {"max_tip_deflection_ratio", "/max_tip_deflection_ratio", "1", "largest tip deflection over the length"},
    {"energy_audit_residual", "/energy_audit_residual", "1", "relative residual of the energy audit"},
    // The last complete revolution of a run over revolutions (the steady one): what a rub map reads
    // (docs/surfaces.md).
    {"last_revolution_impacts", "/last_revolution/impacts", "1", "impacts in the last complete revolution"},
    {"last_revolution_peak_normal_force_n", "/last_revolution/peak_normal_force_n", "N",
     "largest normal force in the last complete revolution"},
    {"last_revolution_normal_impulse_n_s", "/last_revolution/normal_impulse_n_s", "N s",
     "normal impulse in the last complete revolution"},
    {"last_revolution_friction_work_j", "/last_revolution/friction_work_j", "J",
     "work of friction in the last complete revolution"},
    {"last_revolution_max_tip_deflection_ratio", "/last_revolution/max_tip_deflection_ratio", "1",
     "largest tip deflection over the length in the last complete revolution"},
    {"steady_after_revolutions", "/steady_state/after_revolutions", "1",
     "revolutions run until the steady state was reached (runs with until_steady; 0: not reached)"},
    {"f1_hz", "/natural_frequencies_hz/0", "Hz", "first natural frequency at the hub speed"},
    {"f2_hz", "/natural_frequencies_hz/1", "Hz", "second natural frequency at the hub speed"},
    {"f3_hz", "/natural_frequencies_hz/2", "Hz", "third natural frequency at the hub speed"},
    {"steps", "/steps", "1", "integration steps"},
    {"rhs_evaluations", "/rhs_evaluations", "1", "evaluations of the equations of motion"},
    {"wall_time_s", "/wall_time_s", "s", "wall time of the case (the machine's, not a result)"}};
// The columns of a sweep over brushes (docs/brush.md: the brush maps).
const SweepMetric kBrushMetrics[] = {
    {"mean_normal_force_n", "/mean_normal_force_n", "N", "mean normal force on the workpiece over a revolution"},
    {"mean_tangential_force_n", "/mean_tangential_force_n", "N", "mean tangential force on the workpiece"},
    {"peak_normal_force_n", "/peak_normal_force_n", "N", "peak of the binned normal force"},
    {"peak_tangential_force_n", "/peak_tangential_force_n", "N", "peak of the binned tangential force"},
    {"mean_hub_torque_n_m", "/mean_hub_torque_n_m", "N m", "mean torque the hub supplies"},
    {"mean_hub_power_w", "/mean_hub_power_w", "W", "mean power the hub supplies"},
    {"contact_zone_deg", "/contact_zone/angle_deg", "degree", "span of a filament's angle that delivers momentum"},
    {"contact_zone_width_m", "/contact_zone/width_m", "m", "extent along the surface that tips touch"},
    {"depth_ratio", "/dimensionless/depth_ratio", "1", "depth over length, d/L"},
    {"speed_ratio", "/dimensionless/speed_ratio", "1", "hub speed over the first bending frequency"},
    {"force_ratio", "/dimensionless/force_ratio", "1", "mean normal force per filament over 3EI d/L^3"},
    {"steady_filaments", "/steady_filaments", "1", "filaments that reached their steady state"},
    {"failed_filaments", "/failed_filaments", "1", "filaments stopped on a numerical failure"},
    {"wall_time_s", "/wall_time_s", "s", "wall time of the case (the machine's, not a result)"}};

// " at t = … s, θ = … deg" of a failure, for the case's message (the console line and sweep.csv).
std::string where_in_pass(double t_s, double theta_deg) {
  std::ostringstream s;
  s.precision(6);
  s << " at t = " << t_s << " s, θ = " << std::fixed << std::setprecision(4) << theta_deg << " deg";
  return s.str();
}

// The message of a case that finished beyond the model's validity (summary.json `validity` "edge" or
// "outside"), with the warning that says how far; "" within it: a sweep's reader sees it in sweep.csv.
std::string validity_message(const nlohmann::json& summary) {
  if (!summary.is_object() || !summary.contains("validity")) return {};
  const nlohmann::json& validity = summary["validity"];
  if (!validity.is_string() || validity == "within") return {};
  std::string message = "validity " + validity.get<std::string>();
  if (summary.contains("warnings"))
    for (const nlohmann::json& w : summary["warnings"]) {
      if (!w.is_string()) continue;
      const std::string text = w.get<std::string>();
      if (text.find("|y_t|/L") != std::string::npos || text.find("tip deflection") != std::string::npos ||
          text.find("geometry") != std::string::npos)
        return message + ": " + text;
    }
  return message;
}

// Status and message of a case from how its pass or brush ended.
void set_outcome(SweepCaseResult& res, const std::optional<NumericalFailure>& failure, const std::string& where) {
  if (!failure)
    res.status = SweepStatus::done;
  else if (failure->kind == FailureKind::interrupted)
    res.status = SweepStatus::interrupted;
  else
    res.status = SweepStatus::failed;
  if (failure) {
    res.message = std::string(failure_name(failure->kind)) + where +
                  where_in_pass(failure->t, failure->theta * 180.0 / M_PI) + ": " + failure->message;
    return;
  }
  res.message = validity_message(res.summary);
}

// Writes `text` to the temporary file `path` (not atomically: nothing reads it under that name but
// the caller). Throws std::runtime_error naming it.
void write_temporary(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  out.flush();
  if (!out) {
    const int err = errno;
    std::error_code ec;
    std::filesystem::remove(path, ec);
    throw std::runtime_error(path.string() + ": cannot write (" + std::strerror(err) + ")");
  }
}

// Removes what a killed sweep or merge left in the sweep folder `dir` (held under its lock, so no
// live writer's): "sweep.csv.tmp.<pid>[.<n>]", likewise for sweep.json and sweep.nc (written by
// rotbeam.netcdf). Any other name is not ours.
void remove_killed_temporaries(const std::filesystem::path& dir) {
  std::error_code ec;
  for (const std::filesystem::directory_entry& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    for (const std::string stem : {"sweep.csv.tmp.", "sweep.json.tmp.", "sweep.nc.tmp."}) {
      if (name.rfind(stem, 0) != 0) continue;
      const std::string rest = name.substr(stem.size());
      const std::size_t dot = rest.find('.');
      const auto digits = [](const std::string& t) {
        return !t.empty() && t.find_first_not_of("0123456789") == std::string::npos;
      };
      if (dot == std::string::npos ? digits(rest) : digits(rest.substr(0, dot)) && digits(rest.substr(dot + 1)))
        std::filesystem::remove(e.path(), ec);
    }
  }
}

// The leaves of a configuration's JSON by dotted key ("hub.speed_rpm").
void flatten(const nlohmann::json& j, const std::string& prefix, std::map<std::string, nlohmann::json>& out) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (it.value().is_object())
      flatten(it.value(), key, out);
    else
      out[key] = it.value();
  }
}

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

std::size_t sweep_grid_size(const std::vector<SweepAxis>& axes) {
  std::size_t total = 1;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j)
      if (axes[j].key == axes[i].key)
        throw ConfigError("--vary " + axes[i].key + ": the key is varied twice (give all its values in one --vary)");
    // A value given twice runs the same case twice under one coordinate (which is sweep.csv's row
    // of it?): refused as a key varied twice is. Values written alike here; values written apart
    // that read the same (0.1 and 0.10) once the cases are loaded (plan_sweep).
    std::set<std::string> values;
    for (const std::string& v : axes[i].values)
      if (!values.insert(v).second)
        throw ConfigError("--vary " + axes[i].key + ": the value " + printable(v) + " is given twice (give each value once)");
    total *= axes[i].values.size();
    if (total > kMaxSweepCases)
      throw ConfigError("--vary: the grid has more than " + std::to_string(kMaxSweepCases) +
                        " cases; split the study into several sweeps");
  }
  return total;
}

SweepCase sweep_case_at(const std::vector<SweepAxis>& axes, std::size_t index) {
  SweepCase c;
  c.index = static_cast<int>(index);
  std::size_t rem = index;
  c.values.resize(axes.size());
  for (std::size_t k = axes.size(); k-- > 0;) {
    c.values[k] = axes[k].values[rem % axes[k].values.size()];
    rem /= axes[k].values.size();
  }
  for (std::size_t k = 0; k < axes.size(); ++k) c.overrides.push_back(axes[k].key + "=" + c.values[k]);
  char name[32];
  std::snprintf(name, sizeof name, "case-%04zu", index + 1);
  c.folder = name;
  return c;
}

std::vector<SweepCase> sweep_cases(const std::vector<SweepAxis>& axes) {
  const std::size_t total = sweep_grid_size(axes);
  std::vector<SweepCase> cases;
  cases.reserve(total);
  for (std::size_t i = 0; i < total; ++i) cases.push_back(sweep_case_at(axes, i));
  return cases;
}

CaseLoader case_loader(const std::optional<std::string>& config_path, const std::vector<std::string>& base_overrides) {
  return [config_path, base_overrides](const SweepCase& c) {
    std::vector<std::string> overrides = base_overrides;
    overrides.insert(overrides.end(), c.overrides.begin(), c.overrides.end());
    return load_config(config_path, overrides);
  };
}

SweepPlan plan_sweep(const std::vector<SweepAxis>& axes, const CaseLoader& load) {
  SweepPlan plan;
  plan.axes = axes;
  plan.cases = sweep_cases(axes);
  plan.configs.reserve(plan.cases.size());
  for (const SweepCase& c : plan.cases) {
    try {
      plan.configs.push_back(load(c));
    } catch (const ConfigError& e) {
      std::string values;
      for (const std::string& o : c.overrides) values += (values.empty() ? "" : ", ") + o;
      throw ConfigError(c.folder + " (" + values + "): " + e.what());
    }
  }
  // Two values of one key that read the same (0.1 and 0.10, 3000 and 3000.0) make the same cases:
  // each value's case with the other keys at their first values is compared, whole.
  std::size_t stride = plan.cases.size();
  for (const SweepAxis& axis : axes) {
    stride /= axis.values.size();
    std::map<std::string, std::size_t> seen;  // a case's configuration → the value that made it
    for (std::size_t a = 0; a < axis.values.size(); ++a) {
      const auto [at, fresh] = seen.emplace(plan.configs[a * stride].to_json().dump(), a);
      if (!fresh)
        throw ConfigError("--vary " + axis.key + ": " + printable(axis.values[at->second]) + " and " +
                          printable(axis.values[a]) + " are the same value, given twice (give each value once)");
    }
  }
  // A sweep is over brushes or over single filaments (a --vary of a brush key sets it in every case).
  plan.brush = !plan.configs.empty() && plan.configs.front().brush.has_value();
  // What the cases share: the keys whose resolved value is the same in every case.
  std::map<std::string, nlohmann::json> common;
  std::set<std::string> varying;
  for (std::size_t i = 0; i < plan.configs.size(); ++i) {
    std::map<std::string, nlohmann::json> keys;
    flatten(plan.configs[i].to_json(), "", keys);
    if (i == 0) {
      common = std::move(keys);
      continue;
    }
    for (auto it = common.begin(); it != common.end();) {
      const auto found = keys.find(it->first);
      if (found == keys.end() || found->second != it->second) {
        varying.insert(it->first);
        it = common.erase(it);
      } else {
        ++it;
      }
    }
    for (const auto& [key, value] : keys)
      if (!common.count(key)) varying.insert(key);
  }
  plan.common_config = nlohmann::json::object();
  for (const auto& [key, value] : common) {
    std::string pointer = "/" + key;  // "section.key" → "/section/key"
    for (char& ch : pointer)
      if (ch == '.') ch = '/';
    plan.common_config[nlohmann::json::json_pointer(pointer)] = value;
  }
  for (const SweepAxis& a : axes) varying.insert(a.key);  // a key varied over one value is still varied
  plan.varying_keys.assign(varying.begin(), varying.end());
  return plan;
}

nlohmann::json sweep_description(const SweepPlan& plan, Shard shard) {
  nlohmann::json axes = nlohmann::json::array();
  for (const SweepAxis& a : plan.axes) axes.push_back({{"key", a.key}, {"values", a.values}});
  return {{"format", "rotbeam sweep"},
          {"version", kVersion},
          {"axes", axes},
          {"cases", plan.cases.size()},
          {"shard", {{"index", shard.index}, {"count", shard.count}}},
          {"brush", plan.brush},
          {"config", plan.common_config},
          {"varying_keys", plan.varying_keys}};
}

Shard parse_shard(const std::string& text) {
  const std::string shown = printable(text);
  const std::size_t slash = text.find('/');
  const auto whole = [](const std::string& t, long long& v) {
    const auto res = std::from_chars(t.data(), t.data() + t.size(), v);
    return !t.empty() && res.ec == std::errc() && res.ptr == t.data() + t.size();
  };
  long long i = 0, n = 0;
  if (slash == std::string::npos || !whole(text.substr(0, slash), i) || !whole(text.substr(slash + 1), n))
    throw ConfigError("--shard " + (text.empty() ? std::string("\"\"") : shown) +
                      ": expected I/N, shard I of N counted from 0 (e.g. --shard 0/4 … --shard 3/4)");
  if (n < 1 || n > static_cast<long long>(kMaxSweepCases))
    throw ConfigError("--shard " + shown + ": N must be from 1 to " + std::to_string(kMaxSweepCases));
  if (i < 0 || i >= n)
    throw ConfigError("--shard " + shown + ": I must be from 0 to " + std::to_string(n - 1) +
                      " (the shards of " + std::to_string(n) + " are counted from 0)");
  return Shard{static_cast<int>(i), static_cast<int>(n)};
}

std::span<const SweepMetric> sweep_metrics(bool brush) {
  return brush ? std::span<const SweepMetric>(kBrushMetrics) : std::span<const SweepMetric>(kMetrics);
}

std::optional<double> sweep_metric_value(const nlohmann::json& summary, const SweepMetric& metric) {
  const nlohmann::json::json_pointer at(metric.pointer);
  if (summary.is_object() && summary.contains(at) && summary[at].is_number()) return summary[at].get<double>();
  return std::nullopt;
}

SweepCaseResult run_sweep_case(const Config& config, const StopToken* stop) {
  SweepCaseResult res;
  try {
    if (config.brush) {
      BrushOptions brush_options;
      brush_options.threads = 1;  // the cases fill the cores
      brush_options.stop = stop;
      const BrushResult brush = run_brush(config, brush_options);
      res.summary = brush_summary_json(brush, config);
      set_outcome(res, brush.summary.failure, " (filament " + std::to_string(brush.summary.failed_filament + 1) + ")");
      return res;
    }
    const Case c = build_case(config);
    DiscardSink sink;  // a sweep in memory keeps only the summary
    const PassResult pass = run_case(c, {&sink, stop, {}});
    res.summary = summary_json(pass, config, *c.surface);
    set_outcome(res, pass.failure, "");
  } catch (const std::exception& e) {
    res = SweepCaseResult{};
    res.status = SweepStatus::error;
    res.message = e.what();
  }
  return res;
}

SweepReport run_sweep(const std::vector<SweepAxis>& axes, const SweepOptions& options) {
  SweepReport report;
  report.axes = axes;
  report.shard = options.shard;
  if (options.shard.count < 1 || options.shard.index < 0 || options.shard.index >= options.shard.count)
    throw ConfigError("--shard " + std::to_string(options.shard.index) + "/" + std::to_string(options.shard.count) +
                      ": I must be from 0 to N-1");
  // Validate every case of the grid before running any (every shard refuses a bad grid alike).
  const SweepPlan plan = plan_sweep(axes, case_loader(options.config_path, options.base_overrides));
  report.grid_cases = plan.cases.size();
  std::vector<Config> configs;
  for (std::size_t i = 0; i < plan.cases.size(); ++i)
    if (options.shard.contains(i)) {
      report.cases.push_back(plan.cases[i]);
      configs.push_back(plan.configs[i]);
    }
  report.results.resize(report.cases.size());
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
  report.brush = plan.brush;
  // A run's or a brush's folder (its summary.json) is not made a sweep's as well: `plot` would draw
  // one of the two.
  if (std::filesystem::exists(options.dir / "summary.json")) {
    std::ifstream in(options.dir / "summary.json");
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    const bool brush = j.is_object() && j.contains("kind") && j["kind"] == "brush";
    throw ConfigError("-o " + options.dir.string() + (brush ? ": holds a brush" : ": holds a run") +
                      " (summary.json), not a sweep; give another folder");
  }
  if (std::filesystem::exists(options.dir / "manifest.json") && std::filesystem::exists(options.dir / "report.md"))
    throw ConfigError("-o " + options.dir.string() +
                      ": holds a reproduction (manifest.json, report.md), not a sweep; give another folder");
  std::optional<FolderLock> lock;  // one sweep at a time in a folder (each case folder has its own)
  try {
    refuse_folders_under_file_names(options.dir, {"sweep.csv", "sweep.json", "sweep.nc"}, "the sweep");
    prepare_output_folder(options.dir);
    lock.emplace(options.dir);
  } catch (const std::runtime_error& e) {
    throw ConfigError(std::string("-o ") + e.what());
  }

  remove_killed_temporaries(options.dir);

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
          const nlohmann::json& f = j["failure"];
          const std::string where = f.contains("t_s") && f["t_s"].is_number() && f["theta_deg"].is_number()
                                        ? where_in_pass(f["t_s"].get<double>(), f["theta_deg"].get<double>())
                                        : std::string();
          report.results[i].message = f["kind"].get<std::string>() + where + ": " + f["message"].get<std::string>() +
                                      " (computed by an earlier run)";
        } else {
          report.results[i].status = SweepStatus::resumed;
          report.results[i].message = validity_message(j);
        }
        finished = true;
      }
    }
    if (finished)
      ++report.resumed;
    else
      todo.push_back(i);
  }

  // An older sweep.csv (and sweep.nc) describes other cases (or an older state of these): until
  // this sweep writes its own at the end, the folder has no index, so that nothing reads a mix of
  // two sweeps. sweep.json, which says what the folder's sweep is, is written before any case runs.
  const std::string description = sweep_description(plan, options.shard).dump(2) + "\n";
  const std::string older_description = [&] {
    std::ifstream in(options.dir / "sweep.json", std::ios::binary);
    return in ? std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()) : std::string();
  }();
  if (!todo.empty() || older_description != description) {
    for (const char* name : {"sweep.csv", "sweep.nc"}) {
      std::error_code ec;
      std::filesystem::remove(options.dir / name, ec);
      if (ec)
        throw std::runtime_error((options.dir / name).string() + ": cannot remove the older index (" + ec.message() + ")");
    }
  }
  if (older_description != description) write_file_atomically(options.dir / "sweep.json", description);

  std::mutex mutex;
  SweepProgress progress;
  progress.total = static_cast<int>(report.cases.size());
  progress.resumed = report.resumed;
  progress.finished = report.resumed;
  for (const SweepCaseResult& r : report.results) progress.failed += r.resumed && r.status == SweepStatus::failed;
  // Each case's cost, for the ETA: its pass's estimated wall time (the steps its step bounds imply
  // times one evaluation of q̈, timed here: a few ms a case); a brush counts its filaments. The ETA
  // is then the cost left over the cost done per second so far, not the count of cases left.
  std::vector<double> cost(todo.size(), NAN);
  for (std::size_t n = 0; n < todo.size(); ++n) {
    const Config& c = configs[todo[n]];
    try {
      if (c.brush) {
        Config one = c;
        one.brush.reset();
        cost[n] = estimate_steps(build_case(one)).wall_s * std::max(1, c.brush->filaments * c.brush->rows);
      } else {
        cost[n] = estimate_steps(build_case(c)).wall_s;
      }
    } catch (const std::exception&) {
    }
  }
  {
    double known = 0;
    int count = 0;
    for (double v : cost)
      if (std::isfinite(v) && v > 0) known += v, ++count;
    const double typical = count ? known / count : 1.0;
    for (double& v : cost)
      if (!(std::isfinite(v) && v > 0)) v = typical;
  }
  const double total_cost = std::accumulate(cost.begin(), cost.end(), 0.0);
  double done_cost = 0;
  JobRunnerOptions runner;
  runner.threads = options.jobs;
  runner.stop = options.stop;
  runner.on_job_finished = [&](const JobProgress& p) {
    const std::size_t i = todo[p.job];
    ++progress.finished;
    const SweepStatus status = report.results[i].status;
    if (status == SweepStatus::failed || status == SweepStatus::error) ++progress.failed;
    progress.elapsed_s = p.elapsed_s;
    done_cost += cost[p.job];
    progress.eta_s = done_cost > 0 && p.elapsed_s > 0 ? (total_cost - done_cost) / (done_cost / p.elapsed_s) : p.eta_s;
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
            set_outcome(res, brush.summary.failure, " (filament " + std::to_string(brush.summary.failed_filament + 1) + ")");
          } else {
            const Case c = build_case(configs[i]);
            PassFiles files(options.dir / report.cases[i].folder, coordinate_count(configs[i].beam),
                            configs[i].simulation.history_revolutions);
            PassControl control{&files, options.stop, {}};
            if (options.on_case_progress)
              control.on_progress = [&, i](const PassProgress& p) {
                std::lock_guard<std::mutex> lock(mutex);
                options.on_case_progress(report.cases[i], p);
              };
            const PassResult pass = run_case(c, control);
            files.commit(pass, configs[i], *c.surface);
            res.summary = summary_json(pass, configs[i], *c.surface);
            set_outcome(res, pass.failure, "");
          }
        } catch (const std::exception& e) {
          res = SweepCaseResult{};
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
  const std::string index = sweep_csv(report);
  if (options.before_index && report.interrupted == 0) {
    // The index's text in a temporary file beside it for the hook (sweep.nc is made from it), then
    // sweep.csv itself, last.
    const std::filesystem::path tmp = options.dir / ("sweep.csv.tmp." + std::to_string(::getpid()) + ".1");
    try {
      write_temporary(tmp, index);
      options.before_index(tmp);
    } catch (const std::exception& e) {
      report.index_error = e.what();
    }
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
  }
  write_file_atomically(options.dir / "sweep.csv", index);
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
  const std::span<const SweepMetric> metrics = sweep_metrics(report.brush);
  for (const SweepMetric& m : metrics) out += std::string(",") + m.column;
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
    for (const SweepMetric& m : metrics) {
      out += ",";
      if (const std::optional<double> v = sweep_metric_value(r.summary, m)) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.17g", *v);
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
