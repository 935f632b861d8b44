#include "rotbeam/process_memory.hpp"

#include <fstream>
#include <sstream>
#include <string>

namespace rotbeam {

double resident_memory_mib() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) {
      std::istringstream s(line.substr(6));
      double kib = 0;
      s >> kib;
      return kib / 1024.0;
    }
  }
  return 0.0;
}

double available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  for (std::string line; std::getline(meminfo, line);) {
    if (line.rfind("MemAvailable:", 0) == 0) {
      std::istringstream s(line.substr(13));
      double kib = 0;
      s >> kib;
      return kib * 1024.0;
    }
  }
  return 0.0;
}

}  // namespace rotbeam
