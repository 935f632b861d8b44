#include "rotbeam/wear_output.hpp"

#include "rotbeam/atomic_file.hpp"
#include "rotbeam/detail/csv.hpp"
#include "rotbeam/output_columns.hpp"
#include "rotbeam/pass_output.hpp"
#include "rotbeam/version.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace rotbeam {

namespace {

constexpr const char* kFiles[] = {"wear_history.csv", "wear_depth.csv", "summary.json"};
constexpr const char* kPictures[] = {"wear.png"};

void put(std::string& out, double v) { detail::append_number(out, v); }

void put_row(std::string& out, std::initializer_list<double> values) {
  bool first = true;
  for (double v : values) {
    if (!first) out += ',';
    first = false;
    put(out, v);
  }
  out += '\n';
}

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

std::string wear_history_csv(const WearRun& run) {
  std::string out = csv_header(output_file("wear_history.csv"), 0) + "\n";
  double lost = 0;
  for (const WearStep& s : run.steps) {
    out += std::to_string(s.step) + ',';
    put(out, s.time_h);
    out += ',';
    put(out, s.length_m);
    out += ',';
    put(out, lost);
    out += s.steady ? ",true," : ",false,";
    out += std::to_string(s.period_revolutions) + ',' + std::to_string(s.revolutions_run) + ',';
    // A step whose search did not finish (a failure, a stop, a filament that no longer reaches) has
    // no orbit: nan, not zeros.
    const double x = s.ran ? 1.0 : NAN;
    put_row(out, {s.section_distance, x * s.impacts_per_revolution, x * s.mean_normal_force_n, x * s.mean_hub_torque_n_m,
                  x * s.mean_hub_power_w, x * s.per_revolution.sliding_load_n_m, x * s.removal_rate_m3_h * 1e9,
                  x * s.length_rate_m_h * 1e3, x * s.heat_rate_w,
                  x * s.heat_rate_w * (s.per_revolution.heat_j > 0 ? s.per_revolution.heat_to_surface_j / s.per_revolution.heat_j : 0.0),
                  s.wall_time_s});
    lost += s.length_lost_m;
  }
  return out;
}

std::string wear_depth_csv(const WearRun& run, const WearSettings& w) {
  std::string out = csv_header(output_file("wear_depth.csv"), 0) + "\n";
  const double mpu = run.coordinate.metres_per_unit;
  for (const WearBin& b : run.removed_profile) {
    const double volume = w.surface_coefficient * b.sliding_load_n_m / w.surface_hardness_pa;
    put_row(out, {b.from * mpu, b.to * mpu, b.from, b.to, volume, removed_depth_m(b, w, run.coordinate, run.track_width_m),
                  b.heat_j});
  }
  return out;
}

nlohmann::json wear_run_json(const WearRun& run, const Config& config, const WearRunOptions& options) {
  nlohmann::json j;
  j["kind"] = "wear";
  j["rotbeam_version"] = kVersion;
  j["hours"] = options.hours;
  j["steps"] = options.steps;
  j["completed_steps"] = run.steps.empty() ? 0 : static_cast<int>(run.steps.size()) - 1;
  j["stopped_early"] = run.stopped_early;
  j["note"] = run.note;
  j["initial_length_m"] = config.beam.length_m;
  j["final_length_m"] = config.beam.length_m - run.length_lost_m;
  j["length_lost_m"] = run.length_lost_m;
  j["volume_removed_m3"] = run.volume_removed_m3;
  j["heat_j"] = run.heat_j;
  double deepest = 0, at = NAN;
  for (const WearBin& b : run.removed_profile) {
    const double d = removed_depth_m(b, config.wear, run.coordinate, run.track_width_m);
    if (d > deepest) deepest = d, at = 0.5 * (b.from + b.to);
  }
  j["max_removed_depth_m"] = deepest;
  j["max_removed_depth_at"] = number_or_null(at);
  j["coordinate"] = run.coordinate.name ? run.coordinate.name : "";
  j["coordinate_unit"] = run.coordinate.unit ? run.coordinate.unit : "";
  j["track_width_m"] = run.track_width_m;
  const WearStep* first = nullptr;
  const WearStep* last = nullptr;
  for (const WearStep& s : run.steps)
    if (s.ran) last = &s, first = first ? first : &s;
  j["warnings"] = run.warnings;
  if (first) {
    const WearStep& a = *first;
    const WearStep& b = *last;
    j["mean_normal_force_n"] = {{"start", a.mean_normal_force_n}, {"end", b.mean_normal_force_n}};
    j["force_change"] = a.mean_normal_force_n > 0 ? number_or_null(b.mean_normal_force_n / a.mean_normal_force_n - 1.0)
                                                  : nlohmann::json(nullptr);
    j["removal_rate_mm3_h"] = {{"start", a.removal_rate_m3_h * 1e9}, {"end", b.removal_rate_m3_h * 1e9}};
  }
  int not_steady = 0;
  for (const WearStep& s : run.steps) not_steady += s.ran && !s.steady;
  j["steps_not_steady"] = not_steady;
  if (run.failure)
    j["failure"] = {{"kind", failure_name(run.failure->kind)},
                    {"t_s", run.failure->t},
                    {"theta_deg", run.failure->theta * 180.0 / M_PI},
                    {"message", run.failure->message}};
  else
    j["failure"] = nullptr;
  j["config"] = config.to_json();
  return j;
}

WearFiles::WearFiles(const std::filesystem::path& dir)
    : dir_(dir),
      lock_(open_study_folder(dir, "a wear run", {std::begin(kFiles), std::end(kFiles)},
                              {std::begin(kPictures), std::end(kPictures)})) {}

WearFiles::~WearFiles() = default;

void WearFiles::commit(const WearRun& run, const Config& config, const WearRunOptions& options) {
  const std::string history = wear_history_csv(run), depth = wear_depth_csv(run, config.wear);
  write_file_atomically(dir_ / "wear_history.csv", history);
  write_file_atomically(dir_ / "wear_depth.csv", depth);
  nlohmann::json j = wear_run_json(run, config, options);
  j["files"] = {{"wear_history.csv", {{"bytes", history.size()}}}, {"wear_depth.csv", {{"bytes", depth.size()}}}};
  write_file_atomically(dir_ / "summary.json", j.dump(2) + "\n");
}

}  // namespace rotbeam
