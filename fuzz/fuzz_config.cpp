// libFuzzer target for the configuration parser and the --set parser.
// Input: text whose lines starting with "--set " are overrides (the rest of the line), every other
// line is part of the TOML document. Bad input must end in rotbeam::ConfigError; any other
// exception, crash or sanitizer report is a bug.
#include "rotbeam/case.hpp"

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string toml;
  std::vector<std::string> overrides;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("--set ", 0) == 0)
      overrides.push_back(line.substr(6));
    else
      toml += line + "\n";
  }
  try {
    const rotbeam::Config c = rotbeam::load_config_string(toml, overrides);
    (void)c.to_json().dump();
    (void)rotbeam::build_case(c);
  } catch (const rotbeam::ConfigError&) {
  }
  return 0;
}
