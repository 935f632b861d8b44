// The key table (src/io/config_keys.cpp): each key reads back its own default, docs/configuration.md
// documents every key with the table's unit and default, and revalidate refuses a value set in code
// as --set refuses the same value.
#include "../src/io/config_keys.hpp"

#include "rotbeam/config.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <regex>
#include <string>

using namespace rotbeam;
using namespace rotbeam::config_detail;

namespace {

// The message `f` throws as ConfigError ("" if none).
template <class F>
std::string refusal_of(F&& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

// The cells of a Markdown table row, trimmed, split at the bars that are not escaped (\|).
std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::string cell;
  for (std::size_t i = 1; i < row.size(); ++i) {
    if (row[i] == '|' && row[i - 1] != '\\') {
      const auto b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
      out.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
      cell.clear();
    } else {
      cell += row[i];
    }
  }
  return out;
}

// A documented default as the value it names: backticks dropped, a number read as a number.
Value documented(std::string text) {
  text.erase(std::remove(text.begin(), text.end(), '`'), text.end());
  if (text == "true" || text == "false") return text == "true";
  if (text.size() >= 2 && text.front() == '"' && text.back() == '"') return text.substr(1, text.size() - 2);
  std::size_t used = 0;
  try {
    const double v = std::stod(text, &used);
    if (used == text.size()) return v;
  } catch (const std::exception&) {
  }
  return text;
}

// Two defaults alike: numbers by value (7800 is 7800.0), everything else as JSON.
bool same_value(const Value& a, const Value& b) {
  if (a.is_number() && b.is_number()) return a.get<double>() == b.get<double>();
  return a == b;
}

}  // namespace

TEST(ConfigKeys, EveryKeyAcceptsItsDefaultAndReadsItBack) {
  ASSERT_EQ(key_table().size(), config_keys().size());
  for (const Key& k : key_table()) {
    const Value d = k.get(defaults());
    Config c = defaults();
    if (k.unset.empty()) {
      // A default that is a value (not a placeholder for "not given") passes its key's own check.
      EXPECT_FALSE(refusal(k, d).has_value()) << k.name << " = " << render(d) << ": " << *refusal(k, d);
    }
    if (refusal(k, d)) continue;
    k.set(c, d);
    EXPECT_EQ(k.get(c), d) << k.name;
    EXPECT_FALSE(type_text(k).empty()) << k.name;
    EXPECT_FALSE(allowed_text(k).empty()) << k.name;
    EXPECT_FALSE(k.doc.empty()) << k.name;
  }
}

TEST(ConfigKeys, EveryKeyParsesItsDefaultFromText) {
  // Given as --set gives it, each default reads back as itself; a key of another surface shape or
  // contact law is refused only by the checks across keys, never by its own check.
  for (const Key& k : key_table()) {
    const Value d = k.get(defaults());
    if (!k.unset.empty()) continue;
    const std::string text = render(d);
    try {
      const Config c = load_config_values(std::nullopt, {{k.name, text}});
      EXPECT_TRUE(same_value(k.get(c), d)) << k.name << ": " << render(k.get(c)) << " != " << text;
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).find(k.name + " = " + text + ": must"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("applies to"), std::string::npos) << e.what();
    }
  }
}

TEST(ConfigKeys, TheDocsListEveryKeyWithItsUnitAndDefault) {
  std::ifstream in(std::string(ROTBEAM_SOURCE_DIR) + "/docs/configuration.md");
  ASSERT_TRUE(in) << "docs/configuration.md";
  std::map<std::string, std::vector<std::string>> rows;
  std::size_t unit_col = 0, default_col = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("| key |", 0) == 0) {
      const std::vector<std::string> head = cells(line);
      unit_col = std::find(head.begin(), head.end(), "unit") - head.begin();
      default_col = std::find(head.begin(), head.end(), "default") - head.begin();
      ASSERT_LT(unit_col, head.size()) << line;
      ASSERT_LT(default_col, head.size()) << line;
      continue;
    }
    std::smatch m;
    if (!std::regex_search(line, m, std::regex("^\\| `([a-z_]+\\.[a-z_0-9]+)` \\|"))) continue;
    EXPECT_TRUE(rows.emplace(m[1], cells(line)).second) << m[1] << " is documented twice";
    EXPECT_TRUE(find_key(m[1])) << m[1] << " is documented but is no key";
  }
  for (const Key& k : key_table()) {
    const auto row = rows.find(k.name);
    if (row == rows.end()) {
      ADD_FAILURE() << k.name << " is not in docs/configuration.md's table";
      continue;
    }
    EXPECT_EQ(row->second.at(unit_col), k.unit) << k.name << "'s unit";
    const std::string& cell = row->second.at(default_col);
    if (!k.unset.empty())
      EXPECT_EQ(cell, k.unset) << k.name << "'s default";
    else
      EXPECT_TRUE(same_value(documented(cell), k.get(defaults())))
          << k.name << "'s default: documented " << cell << ", the struct's " << render(k.get(defaults()));
  }
}

TEST(ConfigKeys, RevalidateRefusesAValueSetInCodeAsSetDoes) {
  const Config base = load_config_string("", {});
  const auto both = [&](const std::string& assignment, auto change) {
    Config c = base;
    change(c);
    const std::string by_set = refusal_of([&] { load_config_string("", {assignment}); });
    const std::string in_code = refusal_of([&] { revalidate(c); });
    EXPECT_FALSE(by_set.empty()) << assignment;
    EXPECT_EQ(in_code, by_set) << assignment;
  };
  both("beam.length_m=-0.01", [](Config& c) { c.beam.length_m = -0.01; });
  both("beam.diameter_m=nan", [](Config& c) { c.beam.diameter_m = std::nan(""); });
  both("beam.diameter_m=0.1", [](Config& c) { c.beam.diameter_m = 0.1; });
  both("surface.depth_fraction=1.5", [](Config& c) { c.surface.depth_fraction = 1.5; });
  both("beam.modes=45", [](Config& c) {
    c.beam.modes = 45;
    c.initial.modal_velocity.assign(45, 0.0);
    c.initial.modal_displacement.assign(45, 0.0);
  });
  both("initial.modal_velocity=[0.0,0.0]", [](Config& c) { c.initial.modal_velocity = {0, 0}; });
  both("surface.depth_fraction=1e-18", [](Config& c) { c.surface.depth_fraction = 1e-18; });
  // Accepted in code as with --set: the same configuration.
  Config c = base;
  c.beam.length_m = 0.05;
  EXPECT_EQ(revalidate(c).to_json(), load_config_string("", {"beam.length_m=0.05"}).to_json());
}
