// Strict number parsing for command-line options (internal).
#pragma once

#include <cmath>
#include <string>

namespace rotbeam::detail {

/// True, with `out` set, when the whole of `text` is one finite number (no trailing characters).
inline bool parse_finite_number(const std::string& text, double& out) {
  std::size_t used = 0;
  try {
    out = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used != 0 && used == text.size() && std::isfinite(out);
}

}  // namespace rotbeam::detail
