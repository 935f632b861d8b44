// Pieces shared by the rotbeam subcommands: case options, exit codes, error reporting.
#pragma once

#include "rotbeam/config.hpp"

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace rotbeam::cli {

/// Exit codes of the rotbeam binary (documented in docs/cli.md).
enum ExitCode : int {
  kSuccess = 0,
  kRuntimeFailure = 1,  // I/O failure or an unexpected internal error
  kBadInput = 2,        // command line or configuration rejected
  kNoImpact = 3,        // `rotbeam impact`: the tip never reached the surface before the end angle
  kNumericalFailure = 4,// a pass stopped on a diagnosed numerical failure (partial results written)
};

/// The CONFIG positional and the repeatable --set option of a case-based subcommand.
struct CaseOptions {
  std::optional<std::string> config_path;
  std::vector<std::string> overrides;
  void add_to(CLI::App& app);
  Config load() const;  // throws ConfigError
};

/// Prints "rotbeam: error: <message>" on one line to stderr.
void print_error(const std::string& message);

/// Formats a double with `digits` significant digits.
std::string fixed(double v, int decimals);

}  // namespace rotbeam::cli
