#include "rotbeam/atomic_file.hpp"

#include <cstdio>
#include <fstream>
#include <system_error>
#include <unistd.h>

namespace rotbeam {

void write_file_atomically(const std::filesystem::path& path, const std::string& contents) {
  const std::filesystem::path tmp = path.string() + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(path.string() + ": cannot write (" + std::generic_category().message(errno) + ")");
    out << contents;
    out.flush();
    if (!out) {
      std::remove(tmp.c_str());
      throw std::runtime_error(path.string() + ": write failed");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw std::runtime_error(path.string() + ": cannot rename into place (" + ec.message() + ")");
  }
}

}  // namespace rotbeam
