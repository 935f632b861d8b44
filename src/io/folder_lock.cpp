#include "rotbeam/folder_lock.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <stdexcept>
#include <string>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace rotbeam {

FolderLock::FolderLock(const std::filesystem::path& dir, Use use) : path_(dir / kFileName) {
  // A lock taken on a file that another writer removed meanwhile is not the folder's lock: take it
  // again on the current file.
  for (;;) {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0 && use == Use::drawing && (errno == EACCES || errno == EROFS || errno == EPERM)) return;
    if (fd_ < 0)
      throw std::runtime_error(path_.string() + ": cannot create the folder's lock (" + std::strerror(errno) + ")");
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      fd_ = -1;
      throw std::runtime_error(dir.string() + (use == Use::drawing
                                                   ? ": a rotbeam run is writing into this folder, or it is being "
                                                     "drawn; draw it once that has finished"
                                                   : ": another rotbeam run is writing into this folder; choose another -o"));
    }
    struct stat held {}, current {};
    if (::fstat(fd_, &held) == 0 && ::stat(path_.c_str(), &current) == 0 && held.st_ino == current.st_ino &&
        held.st_dev == current.st_dev)
      return;
    ::close(fd_);
  }
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());
  ::close(fd_);
}

}  // namespace rotbeam
