#include "common.hpp"

#include <cstdio>
#include <iostream>
#include <sstream>

namespace rotbeam::cli {

void CaseOptions::add_to(CLI::App& app) {
  app.add_option("config", config_path, "Case configuration (TOML); defaults reproduce the thesis base case");
  app.add_option("--set", overrides, "Override one key: section.key=value (value read as TOML; repeatable)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

Config CaseOptions::load() const { return load_config(config_path, overrides); }

void print_error(const std::string& message) {
  std::string one_line = message;
  for (char& c : one_line)
    if (c == '\n') c = ' ';
  std::cerr << "rotbeam: error: " << one_line << std::endl;
}

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

}  // namespace rotbeam::cli
