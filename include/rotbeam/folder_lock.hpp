// One writer at a time in an output folder: an advisory lock (flock) on DIR/.rotbeam.lock, which
// the kernel releases if the process dies. Runs, sweeps and reproductions hold it while they write;
// plot and animate while they read and draw the folder.
#pragma once

#include <filesystem>

namespace rotbeam {

class FolderLock {
public:
  /// What the lock is taken for: writing the folder (run, sweep, reproduce), or reading it whole to
  /// draw it (plot, animate), so that no run replaces the files while they are drawn.
  enum class Use { writing, drawing };
  /// Takes the lock of `dir` (which must exist). Throws std::runtime_error naming the folder when
  /// another process holds it ("another rotbeam run is writing into this folder") or the lock file
  /// cannot be created; for drawing, a folder where no lock file can be created (read-only) is
  /// drawn without one: no rotbeam run of this user can write there either.
  explicit FolderLock(const std::filesystem::path& dir, Use use = Use::writing);
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
