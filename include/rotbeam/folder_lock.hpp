// One writer at a time in an output folder: an advisory lock (flock) on DIR/.rotbeam.lock, which
// the kernel releases if the process dies. Runs, sweeps and reproductions hold it while they write.
#pragma once

#include <filesystem>

namespace rotbeam {

class FolderLock {
public:
  /// Takes the lock of `dir` (which must exist). Throws std::runtime_error naming the folder when
  /// another process holds it ("another rotbeam run is writing into this folder") or the lock file
  /// cannot be created.
  explicit FolderLock(const std::filesystem::path& dir);
  /// Removes the lock file while still holding it (so no other writer locks a removed file), then
  /// releases the lock.
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  static constexpr const char* kFileName = ".rotbeam.lock";

private:
  int fd_ = -1;
  std::filesystem::path path_;
};

}  // namespace rotbeam
