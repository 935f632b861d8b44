#include "common.hpp"

#include <csignal>
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

namespace {
StopToken g_interrupt;

extern "C" void on_interrupt(int signal) {
  g_interrupt.request_stop();
  std::signal(signal, SIG_DFL);  // a second signal ends the process at once
}
}  // namespace

const StopToken& interrupt_token() { return g_interrupt; }

void install_interrupt_handlers() {
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
}

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

}  // namespace rotbeam::cli
