// CSV quoting (RFC 4180) for the output files (internal).
#pragma once

#include <charconv>
#include <cmath>
#include <string>
#include <vector>

namespace rotbeam::detail {

/// Appends the shortest decimal that reads back to the same double (std::to_chars; about 4× cheaper
/// than printf's %.17g and never longer), "nan" for NaN.
inline void append_number(std::string& out, double v) {
  if (std::isnan(v)) {
    out += "nan";
    return;
  }
  char buf[40];
  out.append(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

/// The field as is, or quoted with doubled quotes when it holds a comma, a quote or a newline.
inline std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

/// The records of CSV text as csv_field writes them (RFC 4180: quoted fields may hold commas,
/// doubled quotes and line breaks); a final line break ends the last record. Sets `ok` false for a
/// quote that never closes.
inline std::vector<std::vector<std::string>> parse_csv(const std::string& text, bool& ok) {
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record;
  std::string field;
  bool quoted = false, any = false;
  ok = true;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
      continue;
    }
    any = true;
    if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      record.push_back(field);
      field.clear();
    } else if (c == '\n') {
      record.push_back(field);
      records.push_back(record);
      record.clear();
      field.clear();
      any = false;
    } else {
      field += c;
    }
  }
  if (quoted) ok = false;
  if (any || !field.empty() || !record.empty()) {
    record.push_back(field);
    records.push_back(record);
  }
  return records;
}

}  // namespace rotbeam::detail
