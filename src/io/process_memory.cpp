#include "rotbeam/process_memory.hpp"

#include <fstream>
#include <sstream>
#include <string>

namespace rotbeam {

namespace {
// The value [kiB] of the line "key: <n> kB" of a /proc file; 0 if absent.
double proc_kib(const char* file, const std::string& key) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(key, 0) == 0) {
      std::istringstream s(line.substr(key.size()));
      double kib = 0;
      s >> kib;
      return kib;
    }
  }
  return 0.0;
}
}  // namespace

double resident_memory_mib() { return proc_kib("/proc/self/status", "VmRSS:") / 1024.0; }

double available_memory_bytes() { return proc_kib("/proc/meminfo", "MemAvailable:") * 1024.0; }

}  // namespace rotbeam
