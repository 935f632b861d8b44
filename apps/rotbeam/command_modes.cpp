// `rotbeam modes`: natural frequencies of the spinning filament versus hub speed (docs/model.md §3, §9).
#include "commands.hpp"
#include "common.hpp"

#include "rotbeam/atomic_file.hpp"
#include "rotbeam/detail/parse.hpp"
#include "python_bridge.hpp"
#include "rotbeam/modal_analysis.hpp"

#include <filesystem>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>

namespace rotbeam::cli {

namespace {

struct ModesOptions {
  CaseOptions case_options;
  std::string speeds;
  bool json = false;
  std::string csv_path;
  std::string plot_path;
};

// "A:B:N" (N evenly spaced speeds from A to B) or a single value "A".
std::vector<double> parse_speeds(const std::string& text) {
  const std::string what = "--speeds-rpm " + text + ": ";
  std::vector<std::string> parts;
  std::stringstream ss(text);
  for (std::string part; std::getline(ss, part, ':');) parts.push_back(part);
  auto number = [&](const std::string& s) {
    double v = 0;
    if (!detail::parse_finite_number(s, v)) {
      errno = 0;
      char* end = nullptr;
      std::strtod(s.c_str(), &end);
      const bool overflow = errno == ERANGE && end == s.c_str() + s.size();
      throw ConfigError(what + "'" + s + (overflow ? "' is beyond the largest number" : "' is not a number"));
    }
    if (v < 0 || v > 1e6) throw ConfigError(what + "speeds must be in [0, 1000000] rpm");
    return v;
  };
  if (parts.size() == 1) return {number(parts[0])};
  if (parts.size() != 3) throw ConfigError(what + "expected A:B:N (from A to B rpm in N points) or a single speed");
  const double a = number(parts[0]), b = number(parts[1]);
  std::size_t used = 0;
  long count = 0;
  try {
    count = std::stol(parts[2], &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != parts[2].size() || count < 1 || count > 100000)
    throw ConfigError(what + "N must be a whole number from 1 to 100000");
  if (b < a) throw ConfigError(what + "B must not be below A");
  std::vector<double> out;
  for (long i = 0; i < count; ++i) out.push_back(count == 1 ? a : a + (b - a) * static_cast<double>(i) / (count - 1));
  return out;
}

// The decimals of the speed column: one ("3000.0"), or as many more as it takes for every speed to
// read back within 1e-7 of itself and for neighbouring speeds that differ to print differently
// (0:1:100000 printed 100 000 rows reading 0.0 … 1.0 with one), at most 12.
int speed_decimals(const std::vector<double>& speeds) {
  const auto fits = [&](int d) {
    for (std::size_t i = 0; i < speeds.size(); ++i) {
      const std::string text = fixed(speeds[i], d);
      if (std::abs(std::strtod(text.c_str(), nullptr) - speeds[i]) > 1e-7 * std::abs(speeds[i])) return false;
      if (i > 0 && speeds[i] != speeds[i - 1] && text == fixed(speeds[i - 1], d)) return false;
    }
    return true;
  };
  int d = 1;
  while (d < 12 && !fits(d)) ++d;
  return d;
}

int run_modes(const ModesOptions& o) {
  const Config config = o.case_options.load();
  if (!o.plot_path.empty()) check_output_file("--plot", o.plot_path, {".png", ".pdf", ".svg"});
  if (!o.csv_path.empty()) check_output_file("--csv", o.csv_path, {});
  // One file for both: the picture overwrote the table asked for.
  std::error_code same_ec;
  if (!o.csv_path.empty() && !o.plot_path.empty() &&
      std::filesystem::weakly_canonical(std::filesystem::absolute(o.csv_path, same_ec), same_ec) ==
          std::filesystem::weakly_canonical(std::filesystem::absolute(o.plot_path, same_ec), same_ec))
    throw ConfigError("--plot " + path_text(o.plot_path) + ": the same file as --csv; give two names");
  std::vector<double> speeds;
  if (!o.speeds.empty()) {
    speeds = parse_speeds(o.speeds);
  } else {
    speeds = default_mode_speeds_rpm(config.beam.speed_rpm);
  }
  const Eigen::MatrixXd f = frequencies_versus_speed(config.beam, speeds);
  const int n = config.beam.modes;

  // The plot reads the table from a CSV file: the user's --csv, else a scratch file of our own in the
  // system's temporary folder (never a path beside the user's that might be theirs).
  std::string csv_path = o.csv_path;
  ScratchFile scratch;
  if (!o.plot_path.empty() && csv_path.empty()) csv_path = scratch.create("rotbeam-modes", ".csv");
  if (!csv_path.empty()) {
    std::ostringstream csv;
    csv.precision(12);
    csv << "speed_rpm";
    for (int k = 0; k < n; ++k) csv << ",f" << k + 1 << "_hz";
    csv << "\n";
    for (std::size_t s = 0; s < speeds.size(); ++s) {
      csv << speeds[s];
      for (int k = 0; k < n; ++k) csv << "," << f(static_cast<Eigen::Index>(s), k);
      csv << "\n";
    }
    write_file_atomically(csv_path, csv.str());
  }
  if (!o.plot_path.empty()) {
    const int code = run_python_plots({csv_path, "--campbell", o.plot_path});
    if (code != 0) return code;
  }
  if (o.json) {
    nlohmann::json j;
    j["speeds_rpm"] = speeds;
    j["frequencies_hz"] = nlohmann::json::array();
    for (std::size_t s = 0; s < speeds.size(); ++s) {
      std::vector<double> row(n);
      for (int k = 0; k < n; ++k) row[k] = f(static_cast<Eigen::Index>(s), k);
      j["frequencies_hz"].push_back(row);
    }
    std::cout << j.dump(2) << "\n";
    return kSuccess;
  }
  if (!o.csv_path.empty() || !o.plot_path.empty()) return kSuccess;
  std::cout << "In-plane natural frequencies of the spinning filament, linearised about the straight beam\n"
            << "(L = " << config.beam.length_m << " m, D = " << config.beam.diameter_m
            << " m, r_h = " << config.beam.hub_radius_m << " m, " << n << " assumed modes)\n\n";
  std::cout << "  speed_rpm";
  for (int k = 0; k < n; ++k) {
    std::string head = "f" + std::to_string(k + 1) + "_hz";
    std::cout << std::string(std::max<int>(1, 12 - static_cast<int>(head.size())), ' ') << head;
  }
  std::cout << "\n";
  const int decimals = speed_decimals(speeds);
  for (std::size_t s = 0; s < speeds.size(); ++s) {
    std::string sp = fixed(speeds[s], decimals);
    std::cout << std::string(std::max<int>(1, 11 - static_cast<int>(sp.size())), ' ') << sp;
    for (int k = 0; k < n; ++k) {
      const std::string v = fixed(f(static_cast<Eigen::Index>(s), k), 3);
      std::cout << std::string(std::max<int>(1, 12 - static_cast<int>(v.size())), ' ') << v;
    }
    std::cout << "\n";
  }
  return kSuccess;
}

}  // namespace

Command add_modes_command(CLI::App& app) {
  auto opts = std::make_shared<ModesOptions>();
  CLI::App* sub = app.add_subcommand("modes", "Natural frequencies of the spinning filament versus hub speed");
  opts->case_options.add_to(*sub);
  sub->add_option("--speeds-rpm", opts->speeds,
                  "Speeds A:B:N (N points from A to B rpm) or one speed; default: 0, the Table 5-2 speeds and the case's speed")
      ->check(non_empty_list("0:3000:7 or 550"));
  sub->add_flag("--json", opts->json, "Print {\"speeds_rpm\": [...], \"frequencies_hz\": [[...], ...]}");
  sub->add_option("--csv", opts->csv_path, "Write the table to this CSV file instead of printing it")->check(non_empty_path());
  sub->add_option("--plot", opts->plot_path, "Draw a Campbell diagram (with engine-order lines) into this PNG")
      ->check(non_empty_path());
  return [opts] { return run_modes(*opts); };
}

}  // namespace rotbeam::cli
