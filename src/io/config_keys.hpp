// The configuration's key table (config_keys.cpp): every key declared once, with its type, unit,
// accepted values, one line of documentation, and where its value lives in Config. Parsing a TOML
// file (config.cpp), checking a Config changed in code (revalidate), Config::to_json, the list of
// keys and `rotbeam keys` all read this one table. The defaults are not in it: they are the
// structs' own (a default-constructed Config).
#pragma once

#include "rotbeam/config.hpp"

#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace rotbeam::config_detail {

/// A key's value as TOML gives it (integer, float, boolean, string, array) or as Config::to_json
/// writes it from the struct: the one form every check reads.
using Value = nlohmann::json;

/// One shape a key's value may take and the values accepted in it.
struct Form {
  enum class Kind { number, integer, boolean, word, numbers };
  Kind kind = Kind::number;
  // number: the range, each end open or closed (hi = inf for none); integer: [lo, hi]; numbers:
  // every element within [-hi, hi], then at least lo.
  double lo = 0, hi = 0;
  bool lo_open = false, hi_open = false;
  // number: values in (0, zero_or_at_least) are refused (0 itself is accepted).
  double zero_or_at_least = 0;
  std::vector<std::string> words;  // word: the accepted strings
};

/// What a key accepts: one or more forms, tried in order by the value's type.
struct Check {
  std::vector<Form> forms;
  std::string mismatch;      // the refusal of a value of none of the forms' types ("" : the form's own)
  std::string out_of_range;  // the refusal of a value outside its form's range ("" : "must be in …")
  std::string below_floor;   // the refusal of a number in (0, zero_or_at_least)
};

/// One configuration key.
struct Key {
  std::string name;  // "section.key"
  std::string unit;  // SI unit, "" for none
  Check check;
  std::string doc;    // one line
  std::string unset;  // what leaving the key out means, where the struct's default is a placeholder
  std::function<Value(const Config&)> get;            // the value as Config::to_json writes it
  std::function<void(Config&, const Value&)> set;     // stores an accepted value
  std::function<bool(const Config&)> written;         // whether Config::to_json writes the key
  // The values brushes, seals and rotating blades use (NaN: no such range): a value outside them is
  // accepted with a one-line warning (plausibility_warnings), e.g. a length in millimetres typed as metres.
  double plausible_lo = std::numeric_limits<double>::quiet_NaN();
  double plausible_hi = std::numeric_limits<double>::quiet_NaN();
};

/// Every key, in documentation order.
const std::vector<Key>& key_table();

/// The key named `name`, or nullptr.
const Key* find_key(const std::string& name);

/// Why `key` refuses `value` ("must be in (0, 100]"), or nullopt if it accepts it.
std::optional<std::string> refusal(const Key& key, const Value& value);

/// The key's type in words ("number", "integer or string", …).
std::string type_text(const Key& key);

/// The accepted values in words ("(0, 100]", "\"plane\", \"cylinder\"", "1..1000", …).
std::string allowed_text(const Key& key);

/// The configuration whose values are every key's default: Config{} with a default brush.
const Config& defaults();

/// The shortest text that reads back as v (1e-11, not 9.9999999999999994e-12).
std::string format_number(double v);

/// A short, single-line rendering of a value for messages, numbers in their shortest round-trip
/// form (what the user typed: -0.0635), a float always with a '.' or an exponent, a long array by
/// its first values and its length, a long string cut.
std::string render(const Value& value);

/// An array's rendering from its size and its elements' (render's rule for arrays).
std::string render_list(std::size_t size, const std::function<std::string(std::size_t)>& item);

/// The keys a configuration gave, each with its value as a message shows it: the TOML node's
/// rendering for a file and its overrides, the struct's value for a Config checked in code.
using GivenValues = std::map<std::string, std::string>;

/// Throws ConfigError "<key> = <shown>: <why>".
[[noreturn]] void refuse(const std::string& key, const std::string& shown, const std::string& why);

}  // namespace rotbeam::config_detail
