// The files of `rotbeam continue` (docs/continuation.md): branch.csv (one row per converged point of
// every branch) and summary.json (the range, the branches and how each ended, the special points,
// the engine-order crossings, the counts), written atomically with summary.json last, so that a
// folder without it is not a complete continuation.
#pragma once

#include "rotbeam/folder_lock.hpp"
#include "rotbeam/orbit_continuation.hpp"

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace rotbeam {

std::string branch_csv(const OrbitContinuation& run);
/// summary.json's content; `complete` is false when a stop request ended the continuation early.
nlohmann::json continuation_json(const OrbitContinuation& run);

/// A folder for a continuation: refused when it holds another kind of output, locked while it writes.
class ContinuationFiles {
public:
  explicit ContinuationFiles(const std::filesystem::path& dir);
  ~ContinuationFiles();
  ContinuationFiles(const ContinuationFiles&) = delete;
  ContinuationFiles& operator=(const ContinuationFiles&) = delete;
  void commit(const OrbitContinuation& run);

private:
  std::filesystem::path dir_;
  std::unique_ptr<FolderLock> lock_;
};

}  // namespace rotbeam
