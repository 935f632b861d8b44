// Strict number parsing for command-line options (internal).
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

namespace rotbeam::detail {

/// True, with `out` set, when the whole of `text` is one finite number (no trailing characters).
/// A number too small for a normal double (1e-320) is read as its nearest double, subnormal or
/// zero, as TOML reads it (std::stod called that out of range and "not a number"); one too large
/// for any double is not finite and so refused.
inline bool parse_finite_number(const std::string& text, double& out) {
  if (text.find_first_not_of(" \t") == std::string::npos) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtod(text.c_str(), &end);
  const bool overflow = errno == ERANGE && std::isinf(out);
  return end == text.c_str() + text.size() && !overflow && std::isfinite(out);  // leading blanks are skipped
}

}  // namespace rotbeam::detail
