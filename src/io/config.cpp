// Reading a configuration: a TOML file or text, its `section.key=value` overrides, and a Config
// changed in code, each checked against the key table (config_keys.cpp) and then across keys
// (config_checks.cpp).
#include "rotbeam/config.hpp"

#include "config_checks.hpp"
#include "config_keys.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <system_error>

namespace rotbeam {

using namespace config_detail;

namespace {

// A TOML value as the key table's checks read it: integers, floats, booleans, strings and arrays
// as they are; a table, a date or a time as an object, which no key takes.
Value value_of(const toml::node& node) {
  if (const auto* v = node.as_integer()) return Value(v->get());
  if (const auto* v = node.as_floating_point()) return Value(v->get());
  if (const auto* v = node.as_boolean()) return Value(v->get());
  if (const auto* v = node.as_string()) return Value(v->get());
  if (const toml::array* arr = node.as_array()) {
    Value out = Value::array();
    for (const toml::node& el : *arr) out.push_back(value_of(el));
    return out;
  }
  return Value::object();
}

// A TOML node as a message shows it (render), a date or a time as TOML writes it.
std::string render(const toml::node& node) {
  if (const toml::array* arr = node.as_array())
    return render_list(arr->size(), [&](std::size_t i) { return render((*arr)[i]); });
  if (node.is_date() || node.is_time() || node.is_date_time()) {
    std::ostringstream s;
    node.visit([&](auto&& v) { s << v; });
    return s.str();
  }
  return config_detail::render(value_of(node));
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

// " (did you mean KEY?)" for the key nearest to `key`, or "".
// The words of a key's name ("speed_rpm" → speed, rpm).
std::vector<std::string> name_words(const std::string& name) {
  std::vector<std::string> words;
  std::stringstream in(name);
  for (std::string w; std::getline(in, w, '_');)
    if (!w.empty()) words.push_back(w);
  return words;
}

// A key whose name holds every word of `key`'s name, in the same section ("hub.rpm" → hub.speed_rpm;
// the shortest such), or a key of the same name in another section ("surface.damping_ratio" →
// beam.damping_ratio); "" for none.
std::string word_suggestion(const std::string& key) {
  const auto dot = key.find('.');
  if (dot == std::string::npos || dot + 1 >= key.size()) return {};
  const std::string section = key.substr(0, dot), name = key.substr(dot + 1);
  const std::vector<std::string> words = name_words(name);
  std::string best;
  for (const std::string& k : config_keys()) {
    const auto kd = k.find('.');
    if (kd == std::string::npos) continue;
    const std::string ks = k.substr(0, kd), kn = k.substr(kd + 1);
    if (kn == name) return k;
    if (ks != section || words.empty()) continue;
    const std::vector<std::string> kw = name_words(kn);
    const bool all = std::all_of(words.begin(), words.end(),
                                 [&](const std::string& w) { return std::find(kw.begin(), kw.end(), w) != kw.end(); });
    if (all && (best.empty() || k.size() < best.size())) best = k;
  }
  return best;
}

std::string suggestion(const std::string& key) {
  std::string best;
  std::size_t best_d = 4;
  for (const std::string& k : config_keys()) {
    const std::size_t d = edit_distance(key, k);
    if (d < best_d) best_d = d, best = k;
  }
  if (best.empty())  // a truncated name: "hub.speed" for "hub.speed_rpm"
    for (const std::string& k : config_keys())
      if (key.size() >= 3 && k.rfind(key, 0) == 0) return " (did you mean " + k + "?)";
  if (best.empty()) best = word_suggestion(key);
  return best.empty() ? std::string() : " (did you mean " + best + "?)";
}

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// Whether `text` is a TOML decimal integer (sign, digits, single underscores between digits) that
// is beyond the 64-bit range TOML reads.
bool wide_integer(const std::string& text) {
  std::string digits;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if ((c == '+' || c == '-') && i == 0) {
      if (c == '-') digits += c;
    } else if (c >= '0' && c <= '9') {
      digits += c;
    } else if (!(c == '_' && i > 0 && i + 1 < text.size() && std::isdigit(static_cast<unsigned char>(text[i - 1])) &&
                 std::isdigit(static_cast<unsigned char>(text[i + 1])))) {
      return false;
    }
  }
  if (digits.empty() || digits == "-") return false;
  int64_t v = 0;
  return std::from_chars(digits.data(), digits.data() + digits.size(), v).ec == std::errc::result_out_of_range;
}

// Values given as integers beyond TOML's 64-bit signed range that a key takes exactly (brush.seed
// takes every unsigned 64-bit seed): TOML cannot hold them, so they are kept here by key, beside the
// table (which holds a placeholder under the key).
using WideIntegers = std::map<std::string, std::uint64_t>;

// Sets `key` to the TOML value `text` (a bare word is a string). `what` names the override in errors.
void apply_value(toml::table& root, const std::string& key, const std::string& text, const std::string& what,
                 WideIntegers& wide) {
  const auto dot = key.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == key.size() || key.find('.', dot + 1) != std::string::npos)
    throw ConfigError(what + ": the key must be section.key");
  const std::string section = key.substr(0, dot), name = key.substr(dot + 1);
  const Key* known = find_key(key);
  if (!known)
    throw ConfigError((what.rfind("--set ", 0) == 0 ? "--set " : "") + printable(key) + ": unknown key" + suggestion(key));
  // One value on one line: a line break would let the text hold further assignments.
  if (text.find_first_of("\n\r") != std::string::npos)
    throw ConfigError(what + ": the value holds a line break (give one value on one line)");
  toml::table value_table;
  bool parsed_ok = false;
  if (!text.empty()) {
    try {
      value_table = toml::parse("value = " + text);
      parsed_ok = value_table.size() == 1 && value_table.contains("value");
    } catch (const toml::parse_error&) {
      parsed_ok = false;
    }
  }
  if (!root.contains(section)) root.insert(section, toml::table{});
  toml::table* sec = root[section].as_table();
  if (!sec) refuse(section, render(*root.get(section)), "unknown top-level key; expected a [section]" + suggestion(section));
  wide.erase(key);  // a later value of the key replaces an earlier one
  if (!parsed_ok && wide_integer(text)) {
    // An integer beyond the 64 bits TOML reads ("2**80" from Python) is a number, not a word: the
    // key's own check is asked with the nearest 64-bit integer (unsigned, where it fits: every
    // seed of mt19937_64) and its answer given with the value as written (it was
    // "beam.modes = \"1208925819614629174706176\": must be an integer"). A key that takes that
    // integer gets it exactly; one that takes a number that large, as a float.
    std::string digits;
    std::copy_if(text.begin(), text.end(), std::back_inserter(digits), [](char c) { return c != '_' && c != '+'; });
    std::uint64_t u = 0;
    const bool fits = digits[0] != '-' &&
                      std::from_chars(digits.data(), digits.data() + digits.size(), u).ec == std::errc();
    const Value nearest = digits[0] == '-' ? Value(std::numeric_limits<int64_t>::min())
                                           : Value(fits ? u : std::numeric_limits<std::uint64_t>::max());
    if (const auto why = refusal(*known, nearest)) throw ConfigError(printable(key) + " = " + text + ": " + *why);
    const bool takes_number = std::any_of(known->check.forms.begin(), known->check.forms.end(),
                                          [](const Form& f) { return f.kind == Form::Kind::number; });
    if (!takes_number) {
      if (!fits)  // beyond every unsigned 64-bit integer
        throw ConfigError(printable(key) + " = " + text + ": " +
                          (known->check.out_of_range.empty() ? std::string("must be a 64-bit integer")
                                                             : known->check.out_of_range));
      sec->insert_or_assign(name, int64_t{0});
      wide[key] = u;
      return;
    }
    sec->insert_or_assign(name, std::strtod(digits.c_str(), nullptr));
    return;
  }
  if (parsed_ok)
    value_table["value"].node()->visit([&](auto&& v) { sec->insert_or_assign(name, v); });
  else
    sec->insert_or_assign(name, text);  // a bare word is a string
}

// Applies one `--set section.key=value`.
void apply_override(toml::table& root, const std::string& assignment, WideIntegers& wide) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || trimmed(assignment.substr(0, eq)).empty())
    throw ConfigError("--set " + printable(assignment) + ": expected section.key=value");
  apply_value(root, trimmed(assignment.substr(0, eq)), trimmed(assignment.substr(eq + 1)), "--set " + printable(assignment),
              wide);
}

// A key's value as given and as a message shows it.
struct GivenValue {
  Value value;
  std::string shown;
};

// `start` with the value `given_value` gives for each key (in the table's order, so that the first
// refusal is the same whatever the file's order) checked by its key and stored; then the checks
// across keys and of the start.
Config check_config(Config start, const std::function<std::optional<GivenValue>(const Key&)>& given_value) {
  GivenValues given;
  for (const Key& k : key_table()) {
    const std::optional<GivenValue> g = given_value(k);
    if (!g) continue;
    if (const auto why = refusal(k, g->value)) refuse(k.name, g->shown, *why);
    k.set(start, g->value);
    given[k.name] = g->shown;
  }
  check_combinations(start, given);
  check_start(start, given);
  return start;
}

// The configuration `root` describes: its names known, its values checked (check_config).
Config validate(const toml::table& root, const WideIntegers& wide = {}) {
  // Unknown names first.
  for (auto&& [section_key, section_node] : root) {
    const std::string section(section_key.str());
    const toml::table* sec = section_node.as_table();
    if (!sec) refuse(section, render(section_node), "unknown top-level key; expected a [section]" + suggestion(section));
    for (auto&& [name_key, value] : *sec) {
      const std::string key = section + "." + std::string(name_key.str());
      // An empty key name is shown quoted (it read `hub. = 5`).
      if (!find_key(key)) refuse(name_key.str().empty() ? section + ".\"\"" : key, render(value), "unknown key" + suggestion(key));
    }
  }
  return check_config(Config{}, [&](const Key& k) -> std::optional<GivenValue> {
    const toml::node* node = root.at_path(k.name).node();
    if (!node) return std::nullopt;
    if (const auto w = wide.find(k.name); w != wide.end()) return GivenValue{Value(w->second), std::to_string(w->second)};
    return GivenValue{value_of(*node), render(*node)};
  });
}

Config resolve(toml::table& root, const std::vector<std::string>& overrides) {
  WideIntegers wide;
  for (const std::string& o : overrides) apply_override(root, o, wide);
  return validate(root, wide);
}

Config resolve(toml::table& root, const std::vector<std::pair<std::string, std::string>>& values) {
  WideIntegers wide;
  for (const auto& [key, text] : values) apply_value(root, key, text, printable(key) + " = " + printable(text), wide);
  return validate(root, wide);
}

toml::table read_file(const std::optional<std::string>& path) {
  toml::table root;
  if (!path) return root;
  namespace fs = std::filesystem;
  // The path as given, with "" for the empty one and its control characters escaped.
  const std::string shown = path->empty() ? "\"\"" : printable(*path);
  std::error_code ec;
  const fs::file_status st = fs::status(*path, ec);
  // status() reports what is not there as not_found; anything else (a loop of symbolic links, a
  // component that is not a folder, no permission) in the system's words.
  if (st.type() == fs::file_type::none && ec)
    throw ConfigError(shown + ": cannot read the configuration file (" + ec.message() + ")");
  if (!fs::exists(st)) throw ConfigError(shown + ": no such configuration file");
  if (fs::is_directory(st)) throw ConfigError(shown + ": is a folder, not a configuration file");
  if (!fs::is_regular_file(st)) throw ConfigError(shown + ": is not a regular file (a device, a pipe or a socket)");
  std::ifstream probe(*path);
  if (!probe) throw ConfigError(shown + ": cannot read the configuration file (" + std::generic_category().message(errno) + ")");
  try {
    // Read whole here, not by toml++'s parse_file, which sizes the file first: a file under /proc
    // reports size 0 and read as "could not be opened for reading".
    const std::string text((std::istreambuf_iterator<char>(probe)), std::istreambuf_iterator<char>());
    if (probe.bad()) throw ConfigError(shown + ": cannot read the configuration file");
    root = toml::parse(text, *path);
  } catch (const toml::parse_error& e) {
    throw ConfigError(shown + ":" + std::to_string(e.source().begin.line) + ":" +
                      std::to_string(e.source().begin.column) + ": TOML syntax error: " + printable(std::string(e.description())));
  }
  return root;
}
}  // namespace

std::string printable(const std::string& s) {
  std::string out;
  const auto escape = [&out](const char* format, unsigned value) {
    char buf[12];
    std::snprintf(buf, sizeof buf, format, value);
    out += buf;
  };
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      if (c < 0x20 || c == 0x7f) escape("\\u%04x", c);
      else out += static_cast<char>(c);
      ++i;
      continue;
    }
    // A UTF-8 sequence: its length from the lead byte, its continuation bytes checked, the
    // shortest form and the Unicode range required; anything else is a byte shown as \xNN.
    const std::size_t len = (c & 0xe0) == 0xc0 ? 2 : (c & 0xf0) == 0xe0 ? 3 : (c & 0xf8) == 0xf0 ? 4 : 0;
    unsigned cp = len == 2 ? (c & 0x1fu) : len == 3 ? (c & 0x0fu) : (c & 0x07u);
    bool valid = len != 0 && i + len <= s.size();
    for (std::size_t k = 1; valid && k < len; ++k) {
      const auto b = static_cast<unsigned char>(s[i + k]);
      valid = (b & 0xc0) == 0x80;
      cp = (cp << 6) | (b & 0x3fu);
    }
    if (valid)
      valid = (len == 2 && cp >= 0x80) || (len == 3 && cp >= 0x800 && (cp < 0xd800 || cp > 0xdfff)) ||
              (len == 4 && cp >= 0x10000 && cp <= 0x10ffff);
    if (!valid) {
      escape("\\x%02x", c);
      ++i;
      continue;
    }
    // C1 controls, and the marks, embeddings, overrides and isolates that reorder a terminal's line.
    const bool hidden = cp <= 0x9f || cp == 0x061c || cp == 0x200e || cp == 0x200f || (cp >= 0x202a && cp <= 0x202e) ||
                        (cp >= 0x2066 && cp <= 0x2069);
    if (hidden) escape("\\u%04x", cp);
    else out.append(s, i, len);
    i += len;
  }
  return out;
}

Config load_config_string(const std::string& toml_text, const std::vector<std::string>& overrides) {
  toml::table root;
  try {
    root = toml::parse(toml_text);
  } catch (const toml::parse_error& e) {
    throw ConfigError("TOML syntax error at line " + std::to_string(e.source().begin.line) + ", column " +
                      std::to_string(e.source().begin.column) + ": " + std::string(e.description()));
  }
  return resolve(root, overrides);
}

Config load_config(const std::optional<std::string>& path, const std::vector<std::string>& overrides) {
  toml::table root = read_file(path);
  return resolve(root, overrides);
}

Config load_config_values(const std::optional<std::string>& path,
                          const std::vector<std::pair<std::string, std::string>>& values) {
  toml::table root = read_file(path);
  return resolve(root, values);
}

Config load_config_text_values(const std::string& toml_text, const std::string& name,
                               const std::vector<std::pair<std::string, std::string>>& values) {
  toml::table root;
  try {
    root = toml::parse(toml_text, name);
  } catch (const toml::parse_error& e) {
    throw ConfigError((name.empty() ? std::string("\"\"") : printable(name)) + ":" +
                      std::to_string(e.source().begin.line) + ":" + std::to_string(e.source().begin.column) +
                      ": TOML syntax error: " + printable(std::string(e.description())));
  }
  return resolve(root, values);
}

Config revalidate(const Config& config) {
  // The keys its resolved configuration writes, each checked and stored as a file's value would be
  // (Config::to_json's value through the key's setter), as if the file had given them: less the
  // end angle of a run over revolutions, derived from them, or the revolutions of one pass.
  const std::string derived = config.simulation.revolutions > 0 ? "simulation.end_angle_deg" : "simulation.revolutions";
  return check_config(config, [&](const Key& k) -> std::optional<GivenValue> {
    if (!k.written(config) || k.name == derived) return std::nullopt;
    const Value v = k.get(config);
    return GivenValue{v, config_detail::render(v)};
  });
}

std::vector<std::string> plausibility_warnings(const Config& config) {
  std::vector<std::string> out;
  const auto text = [](double v) {
    std::ostringstream s;
    s.precision(6);
    s << v;
    return s.str();
  };
  for (const Key& k : key_table()) {
    if (!(k.plausible_lo <= k.plausible_hi) || !k.written(config)) continue;
    const Value v = k.get(config);
    if (!v.is_number()) continue;
    const double x = v.get<double>();
    if (x >= k.plausible_lo && x <= k.plausible_hi) continue;
    const std::string unit = k.unit.empty() ? "" : " " + k.unit;
    out.push_back(k.name + " = " + text(x) + unit + " is outside the usual [" + text(k.plausible_lo) + ", " +
                  text(k.plausible_hi) + "]" + unit + " of brushes, seals and blades: the run goes on; check the unit");
  }
  return out;
}

void require_known_key(const std::string& key, const std::string& flag) {
  if (!find_key(key)) throw ConfigError(flag + " " + printable(key) + ": unknown key" + suggestion(key));
}

}  // namespace rotbeam
