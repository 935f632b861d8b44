// `rotbeam keys`: every configuration key with its type, unit, default, accepted values and a line
// of documentation, from the key table (describe_config_keys).
#include "commands.hpp"
#include "common.hpp"

#include <algorithm>
#include <array>
#include <iostream>
#include <nlohmann/json.hpp>

namespace rotbeam::cli {

namespace {

// A default as the table shows it: what leaving the key out means where the value is a
// placeholder, else the value (a number in its shortest form, a string quoted).
std::string default_text(const nlohmann::ordered_json& key) {
  if (key["unset"].is_string()) return key["unset"].get<std::string>();
  const nlohmann::ordered_json& v = key["default"];
  return v.is_number_float() ? given_text(v.get<double>()) : v.dump();
}

// The keys as a table: one line of key, type, unit, default and accepted values, and the
// documentation indented below it.
void print_table(const nlohmann::ordered_json& keys) {
  std::vector<std::array<std::string, 5>> rows = {{"KEY", "TYPE", "UNIT", "DEFAULT", "ACCEPTED"}};
  for (const nlohmann::ordered_json& k : keys) {
    const std::string unit = k["unit"].get<std::string>();
    rows.push_back({k["name"].get<std::string>(), k["type"].get<std::string>(), unit.empty() ? "-" : unit,
                    default_text(k), k["allowed"].get<std::string>()});
  }
  std::array<std::size_t, 4> width{};
  for (const auto& row : rows)
    for (std::size_t c = 0; c < width.size(); ++c) width[c] = std::max(width[c], row[c].size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    std::string line;
    for (std::size_t c = 0; c < width.size(); ++c) line += rows[r][c] + std::string(width[c] - rows[r][c].size() + 2, ' ');
    std::cout << line << rows[r][4] << "\n";
    if (r > 0) std::cout << "    " << keys[r - 1]["doc"].get<std::string>() << "\n";
  }
}

}  // namespace

Command add_keys_command(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand("keys", "List every configuration key: type, unit, default, accepted values");
  sub->add_flag("--json", *json, "Print a JSON array of {name, type, unit, default, unset, allowed, doc}");
  return [json] {
    const nlohmann::ordered_json keys = describe_config_keys();
    if (*json)
      std::cout << keys.dump(2) << "\n";
    else
      print_table(keys);
    return kSuccess;
  };
}

}  // namespace rotbeam::cli
