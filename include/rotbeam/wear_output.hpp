// The files of `rotbeam wear` (docs/wear.md): wear_history.csv (one row per slow-time step),
// wear_depth.csv (the surface's removed depth along it over the run) and summary.json, written
// atomically with summary.json last, so that a folder without it is not a complete wear run.
#pragma once

#include "rotbeam/config.hpp"
#include "rotbeam/folder_lock.hpp"
#include "rotbeam/wear_run.hpp"

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace rotbeam {

std::string wear_history_csv(const WearRun& run);
std::string wear_depth_csv(const WearRun& run, const WearSettings& settings);
nlohmann::json wear_run_json(const WearRun& run, const Config& config, const WearRunOptions& options);

/// A folder for a wear run: refused when it holds another kind of output, locked while the run writes.
class WearFiles {
public:
  explicit WearFiles(const std::filesystem::path& dir);
  ~WearFiles();
  WearFiles(const WearFiles&) = delete;
  WearFiles& operator=(const WearFiles&) = delete;
  void commit(const WearRun& run, const Config& config, const WearRunOptions& options);

private:
  std::filesystem::path dir_;
  std::unique_ptr<FolderLock> lock_;
};

}  // namespace rotbeam
