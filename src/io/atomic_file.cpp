#include "rotbeam/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <system_error>
#include <unistd.h>

namespace rotbeam {

namespace {

// Writes `contents` straight into the existing node at `path` (a device, a pipe, a terminal: what
// /dev/stdout or /dev/null name), without a temporary file.
void write_in_place(const std::filesystem::path& path, const std::string& contents) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error(path.string() + ": cannot write (" + std::strerror(errno) + ")");
  out << contents;
  out.flush();
  if (!out) throw std::runtime_error(path.string() + ": cannot write (" + std::strerror(errno) + ")");
}

// True when following the links from `path` passes through /proc or /dev (/dev/stdout →
// /proc/self/fd/1 → the file the shell opened): such a name is the process's open file, which only
// writing in place reaches; renaming onto what it points to would detach the open file.
bool names_an_open_file(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  fs::path p = fs::absolute(path);
  for (int hop = 0; hop < 40; ++hop) {
    const std::string s = p.lexically_normal().string();
    if (s.rfind("/proc/", 0) == 0 || s.rfind("/dev/", 0) == 0) return true;
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(p, ec))) return false;
    const fs::path next = fs::read_symlink(p, ec);
    if (ec) return false;
    p = next.is_absolute() ? next : p.parent_path() / next;
  }
  return false;
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, const std::string& contents) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status link = fs::symlink_status(path, ec);
  const fs::file_status target = fs::status(path, ec);
  if (fs::is_directory(target)) throw std::runtime_error(path.string() + ": is a folder, not a file");
  // A node that is not a regular file is written into, never replaced: replacing /dev/stdout or a
  // device by a regular file would lose the output and damage the system.
  if ((fs::exists(target) && !fs::is_regular_file(target)) || names_an_open_file(path))
    return write_in_place(path, contents);
  fs::path real = path;
  if (fs::is_symlink(link)) {
    // The user named a link: the file it points to is written, and the link stays.
    real = fs::exists(target) ? fs::canonical(path, ec) : fs::path();
    if (real.empty() || ec) return write_in_place(path, contents);  // a dangling link: create its target
  }
  const fs::path tmp = real.string() + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(path.string() + ": cannot write (" + std::generic_category().message(errno) + ")");
    out << contents;
    out.flush();
    if (!out) {  // a full disk: the user's name and the cause, not "write failed"
      const int err = errno;
      std::remove(tmp.c_str());
      throw std::runtime_error(path.string() + ": cannot write (" + std::strerror(err) + ")");
    }
  }
  fs::rename(tmp, real, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw std::runtime_error(path.string() + ": cannot rename into place (" + ec.message() + ")");
  }
}

}  // namespace rotbeam
