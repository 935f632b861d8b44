#include "rotbeam/brush_output.hpp"

#include "rotbeam/atomic_file.hpp"
#include "rotbeam/detail/csv.hpp"
#include "rotbeam/folder_lock.hpp"
#include "rotbeam/ledger_output.hpp"
#include "rotbeam/output_columns.hpp"
#include "rotbeam/pass_output.hpp"
#include "rotbeam/units.hpp"

#include <charconv>
#include <complex>
#include <cmath>

namespace rotbeam {

namespace {

void put(std::string& out, double v) { detail::append_number(out, v); }

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

constexpr const char* kFiles[] = {"workpiece.csv", "profile.csv", "filaments.csv", "representatives.csv", "spectrum.csv",
                                  "wear_profile.csv", "summary.json"};
constexpr const char* kPictures[] = {"brush_force.png", "brush_profile.png", "brush_filaments.png", "brush_spectrum.png"};

}  // namespace

namespace {
std::string bins_csv(const std::vector<ForceBin>& bins, double omega) {
  std::string out = csv_header(output_file("workpiece.csv"), 0) + "\n";
  for (const ForceBin& b : bins) {
    for (double v : {b.from_deg, b.to_deg, b.normal_impulse_n_s, b.tangential_impulse_n_s, b.mean_normal_force_n,
                     b.mean_tangential_force_n, b.hub_angular_impulse_n_m_s, b.mean_hub_torque_n_m,
                     b.mean_hub_torque_n_m * omega}) {
      put(out, v);
      out += ',';
    }
    out += std::to_string(b.impacts);
    out += '\n';
  }
  return out;
}
}  // namespace

std::string workpiece_csv(const BrushResult& result, double omega) { return bins_csv(result.workpiece, omega); }

std::string profile_csv(const BrushResult& result, double omega) { return bins_csv(result.profile, omega); }

namespace {

// How a filament run ended, in filaments.csv's and representatives.csv's words.
const char* run_status(const FilamentSteadyState& d) {
  if (!d.reaches) return "clear";
  if (d.failure && d.failure->kind == FailureKind::interrupted) return "interrupted";
  if (d.ran) return d.steady ? "steady" : "not_steady";
  if (d.failure) return "failed";
  return d.error.empty() ? "interrupted" : "error";  // never started: the stop came first
}

}  // namespace

std::string filaments_csv(const BrushResult& result) {
  std::string out = csv_header(output_file("filaments.csv"), 0) + "\n";
  const bool estimated = !result.estimates.empty();
  for (const BrushFilament& f : result.filaments) {
    const FilamentSteadyState& d = result.distinct[f.group];
    out += std::to_string(f.index + 1) + ',' + std::to_string(f.row + 1) + ',' + std::to_string(f.position + 1) + ',';
    for (double v : {f.phase_deg, f.length_m, f.diameter_m, f.depth_fraction}) {
      put(out, v);
      out += ',';
    }
    const bool reaches = f.depth_fraction > 0.0;
    out += std::to_string(f.group + 1) + ',' + (reaches ? "true" : "false") + ',';
    out += run_status(d);
    out += ',' + std::to_string(d.period_revolutions) + ',' + std::to_string(d.revolutions_run);
    // The population's values are the filament's own, interpolated; the rest are its nearest
    // representative's.
    const FilamentEstimate e = estimated ? result.estimates[f.index] : FilamentEstimate{};
    const bool own = estimated && reaches;
    for (double v : {own ? e.mean_normal_force_n : estimated ? 0.0 : d.mean_normal_force_n,
                     own ? e.mean_tangential_force_n : estimated ? 0.0 : d.mean_tangential_force_n,
                     own ? e.mean_hub_torque_n_m : estimated ? 0.0 : d.mean_hub_torque_n_m,
                     own ? e.mean_hub_power_w : estimated ? 0.0 : d.mean_hub_power_w,
                     own ? e.impacts_per_revolution : estimated ? 0.0 : d.impacts_per_revolution,
                     own ? e.contact_time_s : estimated ? 0.0 : d.contact_time_s,
                     own ? e.peak_normal_force_n : estimated ? 0.0 : d.peak_normal_force_n,
                     own ? e.max_tip_deflection_ratio : estimated ? 0.0 : d.max_tip_deflection_ratio,
                     d.first_contact_deg, d.last_contact_deg,
                     own ? e.ledger_residual_max_j : estimated ? 0.0 : d.ledger_residual_max_j}) {
      out += ',';
      put(out, v);
    }
    out += '\n';
  }
  return out;
}

std::string representatives_csv(const BrushResult& result) {
  std::string out = csv_header(output_file("representatives.csv"), 0) + "\n";
  for (std::size_t g = 0; g < result.distinct.size(); ++g) {
    const FilamentSteadyState& d = result.distinct[g];
    const RunFilament& r = result.run[g];
    out += std::to_string(g + 1) + ',';
    for (double v : {r.length_m, r.diameter_m, r.depth_fraction, r.weight}) {
      put(out, v);
      out += ',';
    }
    out += std::to_string(r.nearest) + ',' + run_status(d) + ',' + std::to_string(d.period_revolutions) + ',' +
           std::to_string(d.revolutions_run);
    for (double v : {d.mean_normal_force_n, d.mean_tangential_force_n, d.mean_hub_torque_n_m, d.mean_hub_power_w,
                     d.impacts_per_revolution, d.contact_time_s, d.peak_normal_force_n, d.max_tip_deflection_ratio}) {
      out += ',';
      put(out, v);
    }
    out += '\n';
  }
  return out;
}

std::vector<SpectrumLine> workpiece_spectrum(const BrushResult& result, double omega) {
  const std::vector<ForceBin>& bins = result.workpiece;
  const double period = 2.0 * M_PI / omega;
  const int orders = static_cast<int>(bins.size()) / 2;
  std::vector<SpectrumLine> out;
  out.reserve(orders + 1);
  for (int h = 0; h <= orders; ++h) {
    std::complex<double> n, t, q;
    for (const ForceBin& b : bins) {
      const double centre = (0.5 * (b.from_deg + b.to_deg)) * M_PI / 180.0;
      const std::complex<double> e = std::polar(1.0, -h * centre);
      n += b.normal_impulse_n_s * e;
      t += b.tangential_impulse_n_s * e;
      q += b.hub_angular_impulse_n_m_s * e;
    }
    const double scale = (h == 0 ? 1.0 : 2.0) / period;  // one-sided amplitudes; the mean at order 0
    out.push_back({h, h / period, scale * std::abs(n), scale * std::abs(t), scale * std::abs(q)});
  }
  return out;
}

std::string spectrum_csv(const BrushResult& result, double omega, int filaments_around) {
  std::string out = csv_header(output_file("spectrum.csv"), 0) + "\n";
  for (const SpectrumLine& l : workpiece_spectrum(result, omega)) {
    out += std::to_string(l.order) + ',';
    for (double v : {l.frequency_hz, static_cast<double>(l.order) / std::max(1, filaments_around), l.normal_force_n,
                     l.tangential_force_n, l.hub_torque_n_m}) {
      put(out, v);
      out += ',';
    }
    out.back() = '\n';
  }
  return out;
}

WearReport brush_wear_report(const BrushResult& result, const Config& config) {
  WearReport w;
  w.revolutions = 1;
  w.profile = result.wear_profile;
  double load = 0, heat = 0;
  for (const WearBin& b : w.profile) load += b.sliding_load_n_m, heat += b.heat_j;
  w.amounts = wear_amounts(config.wear, load, heat, config.beam.diameter_m);
  w.track_width_m = config.wear.track_width_m > 0.0 ? config.wear.track_width_m : config.beam.diameter_m;
  w.coordinate = {result.wear_coordinate.c_str(), result.wear_coordinate_unit.c_str(), result.wear_metres_per_unit, result.wear_period};
  w.note = "per revolution: every finished filament's steady orbit, summed; the filaments' volume and length "
           "loss at the nominal diameter";
  return w;
}

nlohmann::json brush_summary_json(const BrushResult& result, const Config& config) {
  const BrushSummary& s = result.summary;
  nlohmann::json j;
  j["kind"] = "brush";
  j["method"] = s.method == BrushMethod::population ? "population" : "filaments";
  if (s.population) {
    const PopulationEstimate& p = *s.population;
    j["population"] = {{"tolerance", p.tolerance},
                       {"converged", p.converged},
                       {"rounds", p.rounds},
                       {"representatives", s.distinct_filaments},
                       {"length_nodes", p.lengths},
                       {"diameter_nodes", p.diameters},
                       {"exact_filaments", p.exact_filaments},
                       {"estimated_error",
                        {{"mean_normal_force", p.normal_force_error},
                         {"mean_tangential_force", p.tangential_force_error},
                         {"mean_hub_torque", p.hub_torque_error}}},
                       {"note", "estimated errors are relative to the sums, against the filament-by-filament "
                                "route over the same filaments (docs/brush.md)"}};
  } else {
    j["population"] = nullptr;
  }
  j["wear"] = wear_json(brush_wear_report(result, config));
  j["filaments"] = s.filaments;
  j["distinct_filaments"] = s.distinct_filaments;
  j["reaching_filaments"] = s.reaching;
  j["steady_filaments"] = s.steady;
  j["not_steady_filaments"] = s.not_steady;
  j["failed_filaments"] = s.failed;
  {
    nlohmann::json list = nlohmann::json::array();
    for (int i : s.failed_indices) list.push_back(i + 1);
    j["failed_filament_list"] = list;
  }
  j["missing_force_fraction"] = number_or_null(s.missing_force_fraction);
  j["seed_spread"] = {{"mean_normal_force", s.seed_spread_normal_force},
                      {"mean_hub_torque", s.seed_spread_hub_torque},
                      {"note", "the standard deviation, relative to the sum, between brushes drawn with other seeds, "
                               "estimated from this brush's filaments (sqrt(N)·σ/|sum|)"}};
  j["roll_up"] = {{"at_edge_of_model", s.at_edge_of_model},
                  {"outside_model", s.outside_model},
                  {"barely_reaching", s.barely_reaching},
                  {"clear", s.filaments - s.reaching},
                  {"note", "filaments by the validity of their run (docs/model.md §10), those whose own depth is below a "
                           "quarter of the nominal one, and those that do not reach"}};
  j["revolution_period_s"] = s.revolution_period_s;
  j["mean_normal_force_n"] = s.mean_normal_force_n;
  j["mean_tangential_force_n"] = s.mean_tangential_force_n;
  j["peak_normal_force_n"] = s.peak_normal_force_n;
  j["peak_tangential_force_n"] = s.peak_tangential_force_n;
  j["peak_normal_at_deg"] = number_or_null(s.peak_normal_at_deg);
  j["mean_hub_torque_n_m"] = s.mean_hub_torque_n_m;
  j["mean_hub_power_w"] = s.mean_hub_power_w;
  j["bin_deg"] = s.bin_deg;
  j["contact_zone"] = {{"from_deg", number_or_null(s.contact_zone_from_deg)},
                       {"to_deg", number_or_null(s.contact_zone_to_deg)},
                       {"angle_deg", s.contact_zone_deg},
                       {"width_m", s.contact_zone_width_m}};
  nlohmann::json ledger = {{"energy_change_j", s.ledger.energy_change_j}, {"residual_j", s.ledger_residual_max_j}};
  put_ledger_terms(ledger, s.ledger);
  j["ledger_per_revolution"] = ledger;
  j["ledger_terms"] = ledger_terms_json();
  j["dimensionless"] = {
      {"depth_ratio", s.depth_ratio},
      {"speed_ratio", s.speed_ratio},
      {"force_ratio", s.force_ratio},
      {"definitions",
       {{"depth_ratio", "p = d/L, the nominal filament's depth over its length"},
        {"speed_ratio", "Ω/ω₁: hub speed over the nominal cantilever's first bending frequency at rest, "
                        "ω₁ = 1.87510² √(EI/(ρAL⁴))"},
        {"force_ratio", "mean normal force per filament over 3EI·pL/L³, the static tip force that bends the "
                        "nominal cantilever by the depth"}}}};
  j["wall_time_s"] = s.wall_time_s;
  j["max_tip_deflection_ratio"] = s.max_tip_deflection_ratio;
  j["validity"] = validity_name(s.validity);
  j["warnings"] = s.warnings;
  if (s.failure)
    j["failure"] = {{"kind", failure_name(s.failure->kind)},
                    {"filament", s.failed_filament + 1},
                    {"t_s", s.failure->t},
                    {"theta_deg", s.failure->theta * 180.0 / M_PI},
                    {"message", s.failure->message}};
  else
    j["failure"] = nullptr;
  j["error"] = s.error.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.error);
  j["config"] = config.to_json();
  return j;
}

BrushFiles::BrushFiles(const std::filesystem::path& dir)
    : dir_(dir),
      lock_(open_study_folder(dir, "a brush", {std::begin(kFiles), std::end(kFiles)},
                              {std::begin(kPictures), std::end(kPictures)})) {}

BrushFiles::~BrushFiles() = default;

void BrushFiles::commit(const BrushResult& result, const Config& config) {
  const double omega = rad_per_s_from_rpm(config.beam.speed_rpm);
  const std::string workpiece = workpiece_csv(result, omega);
  const std::string profile = profile_csv(result, omega);
  const std::string filaments = filaments_csv(result);
  const std::string representatives = representatives_csv(result);
  const std::string spectrum = spectrum_csv(result, omega, config.brush ? config.brush->filaments : 1);
  write_file_atomically(dir_ / "workpiece.csv", workpiece);
  write_file_atomically(dir_ / "spectrum.csv", spectrum);
  write_file_atomically(dir_ / "representatives.csv", representatives);
  write_file_atomically(dir_ / "profile.csv", profile);
  write_file_atomically(dir_ / "filaments.csv", filaments);
  const std::string wear = wear_profile_csv(brush_wear_report(result, config), config.wear);
  write_file_atomically(dir_ / "wear_profile.csv", wear);
  nlohmann::json j = brush_summary_json(result, config);
  j["files"] = {{"workpiece.csv", {{"bytes", workpiece.size()}}},
                {"profile.csv", {{"bytes", profile.size()}}},
                {"filaments.csv", {{"bytes", filaments.size()}}},
                {"representatives.csv", {{"bytes", representatives.size()}}},
                {"spectrum.csv", {{"bytes", spectrum.size()}}},
                {"wear_profile.csv", {{"bytes", wear.size()}}}};
  write_file_atomically(dir_ / "summary.json", j.dump(2) + "\n");
}

}  // namespace rotbeam
