// CSV quoting (RFC 4180) for the output files (internal).
#pragma once

#include <string>

namespace rotbeam::detail {

/// The field as is, or quoted with doubled quotes when it holds a comma, a quote or a newline.
inline std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace rotbeam::detail
