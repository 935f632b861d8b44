// Parameter sweeps: the Cartesian grid of `--vary` axes over a base case, run in parallel, each
// case's files in its own folder, resumable, failures isolated (issue: studies); a deterministic
// shard i of N of the grid per process or machine, and the merge of the shards' folders into one
// sweep (issue 20: distributed sweeps, docs/distributed.md).
#pragma once

#include "rotbeam/config.hpp"
#include "rotbeam/job_runner.hpp"
#include "rotbeam/pass.hpp"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace rotbeam {

/// One axis: a configuration key and its values as TOML literals.
struct SweepAxis {
  std::string key;
  std::vector<std::string> values;
};

/// Parses "KEY=V1,V2,…" (values are TOML literals; commas inside [..] or quotes do not split) or
/// "KEY=A:B:N" (N evenly spaced numbers from A to B; whole numbers stay integers). Throws ConfigError.
SweepAxis parse_sweep_axis(const std::string& spec);

struct SweepCase {
  int index = 0;                        // 0-based, last axis fastest
  std::vector<std::string> values;      // one per axis
  std::vector<std::string> overrides;   // "key=value" for the axes
  std::string folder;                   // "case-0001", …
};

/// The largest grid a sweep accepts (each case is a folder of files).
inline constexpr std::size_t kMaxSweepCases = 100000;

/// The cases of the grid, the last axis fastest. Throws ConfigError for a key varied twice or a grid of
/// more than kMaxSweepCases cases.
std::vector<SweepCase> sweep_cases(const std::vector<SweepAxis>& axes);

/// The number of cases of the grid, checked as sweep_cases checks it (ConfigError).
std::size_t sweep_grid_size(const std::vector<SweepAxis>& axes);

/// Case `index` (0-based, < sweep_grid_size) of the grid: sweep_cases(axes)[index], without the others.
SweepCase sweep_case_at(const std::vector<SweepAxis>& axes, std::size_t index);

/// How a sweep gets one case's configuration: the base case (a file, overrides) with the case's
/// axis values applied last. Throws ConfigError.
using CaseLoader = std::function<Config(const SweepCase&)>;

/// The command line's loader: load_config(config_path, base_overrides + the case's "key=value").
CaseLoader case_loader(const std::optional<std::string>& config_path, const std::vector<std::string>& base_overrides);

/// A grid whose every case's configuration has been validated, and what the cases share.
struct SweepPlan {
  std::vector<SweepAxis> axes;
  std::vector<SweepCase> cases;
  std::vector<Config> configs;  // one per case
  bool brush = false;           // the cases are brushes (docs/brush.md)
  // The resolved configuration's keys that hold one value in every case ({section: {key: value}},
  // as summary.json's `config`), and the dotted keys of the others: the varied keys, and any key
  // whose resolved value follows from one of them.
  nlohmann::json common_config;
  std::vector<std::string> varying_keys;
};

/// sweep_cases(axes), then every case's configuration by `load` (a bad one: ConfigError naming the
/// case folder and its values, before anything runs), and what the cases share.
SweepPlan plan_sweep(const std::vector<SweepAxis>& axes, const CaseLoader& load);

/// sweep.json, the description of a sweep folder that `merge` reads: {"format": "rotbeam sweep",
/// "version", "axes": [{key, values}], "cases" (the grid's), "shard": {index, count}, "brush",
/// "config" (plan.common_config), "varying_keys"}.
nlohmann::json sweep_description(const SweepPlan& plan, Shard shard);

/// Parses `--shard I/N` (shard I of N, counted from 0; the cases whose 0-based index is I mod N).
/// Throws ConfigError naming the option and the value.
Shard parse_shard(const std::string& text);

/// One metric column of sweep.csv (and variable of sweep.nc): where it sits in a case's
/// summary.json (a JSON pointer), its units (UDUNITS text, "1" for a number without units) and
/// what it is.
struct SweepMetric {
  const char* column;
  const char* pointer;
  const char* units;
  const char* description;
};

/// The metric columns, in sweep.csv's order: those of a single filament's pass, or of a brush.
std::span<const SweepMetric> sweep_metrics(bool brush);

/// The metric's value in a case's summary, or nothing when the summary has none (null, missing).
std::optional<double> sweep_metric_value(const nlohmann::json& summary, const SweepMetric& metric);

enum class SweepStatus { done, resumed, failed, error, interrupted };
const char* sweep_status_name(SweepStatus s);

struct SweepCaseResult {
  SweepStatus status = SweepStatus::error;
  nlohmann::json summary;  // summary.json of the case (null for `error`)
  std::string message;     // failure or error message
  bool resumed = false;    // computed by an earlier run of the sweep (status done → `resumed`; a failed case stays `failed`)
};

struct SweepProgress {
  int total = 0, finished = 0, resumed = 0, failed = 0;
  double elapsed_s = 0, eta_s = 0;
  const SweepCase* last = nullptr;
  const SweepCaseResult* last_result = nullptr;
};

/// Runs one case in memory, no files (rows and events are dropped as they come), and returns what a
/// sweep records of it: `done`, `failed` (a diagnosed numerical failure) or `interrupted` (`stop`),
/// summary.json's content (without `files`) and the message; `error` with the exception's message
/// for anything else. The metrics equal those of the case run into files to the last bit.
SweepCaseResult run_sweep_case(const Config& config, const StopToken* stop);

/// Called with the path of a temporary file holding the finished index's text (sweep.csv) before
/// it is renamed into place (the command line writes sweep.nc from it there, so that sweep.csv,
/// which says the folder is complete, comes last).
using BeforeIndex = std::function<void(const std::filesystem::path& index_csv)>;

struct SweepOptions {
  std::optional<std::string> config_path;
  std::vector<std::string> base_overrides;
  std::filesystem::path dir;
  int jobs = 0;  // 0: all cores
  Shard shard;   // run only the cases of this shard (every case is validated all the same)
  const StopToken* stop = nullptr;  // a requested stop ends every running case and starts no other
  std::function<void(const SweepProgress&)> on_case_finished;  // called under a lock
  // Progress inside a running case (a pass's, about every quarter second; not a brush's), under the
  // same lock: a long case shows how far it is.
  std::function<void(const SweepCase&, const PassProgress&)> on_case_progress;
  // Called when no case is left interrupted, under the folder's lock; what it throws is reported
  // in SweepReport::index_error, and sweep.csv is written all the same.
  BeforeIndex before_index;
};

struct SweepReport {
  std::vector<SweepAxis> axes;
  std::vector<SweepCase> cases;           // the shard's cases (the whole grid without --shard)
  std::vector<SweepCaseResult> results;   // one per case
  std::size_t grid_cases = 0;             // the cases of the whole grid
  Shard shard;
  int ran = 0, resumed = 0, failed = 0, errors = 0, interrupted = 0;
  bool brush = false;  // the cases are brushes (docs/brush.md): sweep.csv has the brush's columns
  // Folders named case-N in `dir` that are no case of this sweep.csv (an earlier, larger sweep's,
  // or another shard's): left as they are, and counted so that the sweep can say so.
  int other_case_folders = 0;
  std::string index_error;  // what before_index threw ("" when it did not, or was not called)
};

/// Validates every case's configuration first (a bad key or value stops before anything runs:
/// ConfigError), then runs the shard's cases not already finished in `dir/<folder>` (a complete
/// summary.json of the same configuration and not interrupted), writes each case's files,
/// `dir/sweep.json` (sweep_description) before the first case runs and, at the end (or when
/// interrupted), `dir/sweep.csv` atomically. An older sweep.csv and sweep.nc are removed before
/// cases run or when the folder described another sweep.
SweepReport run_sweep(const std::vector<SweepAxis>& axes, const SweepOptions& options);

/// sweep.csv: case, folder, the axes' keys, status, the summary metrics (a run's, or a brush's), message.
std::string sweep_csv(const SweepReport& report);

struct MergeOptions {
  std::vector<std::filesystem::path> dirs;  // the shards' sweep folders
  std::filesystem::path output;             // a folder that does not exist, or an empty one
  const StopToken* stop = nullptr;          // a requested stop removes what the merge wrote
  std::function<void(std::size_t done, std::size_t total)> on_case;  // after each case's files
  BeforeIndex before_index;  // as SweepOptions::before_index; what it throws is an error here
};

struct MergeReport {
  SweepReport sweep;  // the whole grid, in case order, with the statuses the shards recorded
  int shards = 0;       // the folders merged that hold cases of the grid
  int shard_count = 0;  // N of the shards I/N (shards beyond the grid's cases hold none)
  std::size_t linked_files = 0, copied_files = 0;  // hard links where the file system allows, else copies
  bool interrupted = false;  // stopped by `stop`: the output folder the merge made is removed
};

/// Combines the folders of shards 0…N−1 of one sweep (same grid, configuration, version and N,
/// each shard once, read from their sweep.json and sweep.csv) into `output`: a sweep folder like
/// an unsharded sweep's (a case-NNNN folder per case holding its run's files, hard-linked or
/// copied; sweep.json; sweep.csv last), which `plot` draws and `sweep` resumes. Refuses, before
/// writing anything (ConfigError naming the folders and what differs), folders of different
/// sweeps, a shard given twice, missing shards or cases (named), cases not finished (interrupted,
/// error: run their shard again) and an output folder that holds anything. Interrupted (`stop`), it
/// removes the output folder it made and returns with `interrupted`; failing, it removes it and throws.
MergeReport merge_sweeps(const MergeOptions& options);

}  // namespace rotbeam
