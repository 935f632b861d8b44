// Parameter sweeps: the Cartesian grid of `--vary` axes over a base case, run in parallel, each
// case's files in its own folder, resumable, failures isolated (issue: studies).
#pragma once

#include "rotbeam/config.hpp"
#include "rotbeam/job_runner.hpp"

#include <filesystem>
#include <functional>
#include <optional>
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

struct SweepOptions {
  std::optional<std::string> config_path;
  std::vector<std::string> base_overrides;
  std::filesystem::path dir;
  int jobs = 0;  // 0: all cores
  const StopToken* stop = nullptr;  // a requested stop ends every running case and starts no other
  std::function<void(const SweepProgress&)> on_case_finished;  // called under a lock
};

struct SweepReport {
  std::vector<SweepAxis> axes;
  std::vector<SweepCase> cases;
  std::vector<SweepCaseResult> results;
  int ran = 0, resumed = 0, failed = 0, errors = 0, interrupted = 0;
  bool brush = false;  // the cases are brushes (docs/brush.md): sweep.csv has the brush's columns
  // Folders named case-N in `dir` that are no case of this grid (an earlier, larger sweep's): left
  // as they are, and counted so that the sweep can say so.
  int other_case_folders = 0;
};

/// Validates every case's configuration first (a bad key or value stops before anything runs:
/// ConfigError), then runs the cases not already finished in `dir/<folder>` (a complete
/// summary.json of the same configuration and not interrupted), writes each case's files and, at
/// the end (or when interrupted), `dir/sweep.csv` atomically.
SweepReport run_sweep(const std::vector<SweepAxis>& axes, const SweepOptions& options);

/// sweep.csv: case, folder, the axes' keys, status, the summary metrics (a run's, or a brush's), message.
std::string sweep_csv(const SweepReport& report);

}  // namespace rotbeam
