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
  // A pass stopped on a diagnosed numerical failure; the partial results are written (docs/cli.md).
  kPainleve = 4,
  kStick = 5,
  kCorrectorNotConverged = 6,
  kStepUnderflow = 7,
  kNonFinite = 8,
  kValidity = 9,
  kImpactsAccumulate = 10,  // also `chatter`
  kInterrupted = 130,       // SIGINT/SIGTERM: stopped cleanly, partial results written
};

/// The exit code of a numerical failure kind (NumericalFailure::kind).
int exit_code_for_failure(const std::string& kind);

/// Installs SIGINT/SIGTERM handlers that ask the running pass to stop (a second signal kills).
void install_interrupt_handlers();

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
