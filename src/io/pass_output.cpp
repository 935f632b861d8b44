#include "rotbeam/pass_output.hpp"

#include "rotbeam/atomic_file.hpp"
#include "rotbeam/detail/csv.hpp"
#include "rotbeam/folder_lock.hpp"
#include "rotbeam/ledger_output.hpp"
#include "rotbeam/output_columns.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <system_error>
#include <unistd.h>

namespace rotbeam {

using detail::csv_field;

namespace {

constexpr std::size_t kFlushBytes = 1 << 20;

void put(std::string& out, double v) { detail::append_number(out, v); }

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

std::string io_error(const std::filesystem::path& path, const char* what, int err) {
  return path.string() + ": " + what + " (" + std::generic_category().message(err) + ")";
}

}  // namespace

std::string history_header(int n) { return csv_header(output_file("history.csv"), n); }

std::string events_header() { return csv_header(output_file("events.csv"), 0); }

void append_history_line(std::string& out, const HistoryRow& r) {
  put(out, r.t);
  out += ',';
  put(out, r.theta * 180.0 / M_PI);
  out += ',';
  out += phase_name(r.phase);
  for (double v : {r.x_tip, r.y_tip, r.gap, r.vx, r.vy, r.normal_force, r.friction_force, r.lambda}) {
    out += ',';
    put(out, v);
  }
  for (Eigen::Index i = 0; i < r.q.size(); ++i) {
    out += ',';
    put(out, r.q[i]);
  }
  for (Eigen::Index i = 0; i < r.qd.size(); ++i) {
    out += ',';
    put(out, r.qd[i]);
  }
  out += ',';
  put(out, r.jacobi);
  out += ',';
  put(out, r.hub_torque);
  out += '\n';
}

void append_event_line(std::string& out, const PassEvent& e) {
  put(out, e.t);
  out += ',';
  put(out, e.theta * 180.0 / M_PI);
  out += ',';
  out += event_name(e.kind);
  for (double v : {e.y_tip, e.vx_before, e.vx_after, e.restitution, e.impulse, e.tangential_impulse, e.hub_work,
                   e.impact_loss, e.surface_work, e.frictional_heat, e.sliding_load}) {
    out += ',';
    if (!std::isnan(v)) put(out, v);  // empty: not defined for this kind of event
  }
  out += ',' + csv_field(e.detail) + '\n';
}

std::string history_csv(const PassResult& result, int n) {
  std::string out = history_header(n) + "\n";
  out.reserve(result.history.size() * (200 + 50 * n));
  for (const HistoryRow& r : result.history) append_history_line(out, r);
  return out;
}

std::string events_csv(const PassResult& result) {
  std::string out = events_header() + "\n";
  for (const PassEvent& e : result.events) append_event_line(out, e);
  return out;
}

std::string force_bins_csv(const PassResult& result) {
  std::string out = csv_header(output_file("force_bins.csv"), 0) + "\n";
  for (const ForceBin& b : result.force_bins) {
    for (double v : {b.from_deg, b.to_deg, b.normal_impulse_n_s, b.tangential_impulse_n_s, b.mean_normal_force_n,
                     b.mean_tangential_force_n}) {
      put(out, v);
      out += ',';
    }
    out += std::to_string(b.impacts);
    out += '\n';
  }
  return out;
}

std::string wear_profile_csv(const WearReport& w, const WearSettings& settings) {
  std::string out = csv_header(output_file("wear_profile.csv"), 0) + "\n";
  const double mpu = w.coordinate.metres_per_unit;
  for (const WearBin& b : w.profile) {
    const double area = w.track_width_m * (b.to - b.from) * mpu;
    const double volume = settings.surface_coefficient * b.sliding_load_n_m / settings.surface_hardness_pa;
    const double values[] = {b.from * mpu,  b.to * mpu,      b.from, b.to, b.sliding_load_n_m, volume,
                             volume / area, b.heat_j, (1.0 - settings.heat_to_filament) * b.heat_j / area};
    for (std::size_t k = 0; k < std::size(values); ++k) {
      if (k) out += ',';
      put(out, values[k]);
    }
    out += '\n';
  }
  return out;
}

nlohmann::json wear_json(const WearReport& w) {
  double deepest = 0, at = NAN;
  for (const WearBin& b : w.profile) {
    const double volume = w.amounts.sliding_load_n_m > 0 ? w.amounts.surface_volume_m3 * b.sliding_load_n_m / w.amounts.sliding_load_n_m : 0.0;
    const double depth = volume / (w.track_width_m * (b.to - b.from) * w.coordinate.metres_per_unit);
    if (depth > deepest) deepest = depth, at = 0.5 * (b.from + b.to);
  }
  const WearAmounts& a = w.amounts;
  return {{"per", w.revolutions > 0 ? "revolution" : "pass"},
          {"revolutions", w.revolutions},
          {"note", w.note},
          {"sliding_load_n_m", a.sliding_load_n_m},
          {"surface_volume_m3", a.surface_volume_m3},
          {"filament_volume_m3", a.filament_volume_m3},
          {"filament_length_loss_m", a.filament_length_m},
          {"frictional_heat_j", a.heat_j},
          {"heat_to_filament_j", a.heat_to_filament_j},
          {"heat_to_surface_j", a.heat_to_surface_j},
          {"max_removed_depth_m", deepest},
          {"max_removed_depth_at", number_or_null(at)},
          {"track_width_m", w.track_width_m},
          {"coordinate", w.coordinate.name},
          {"coordinate_unit", w.coordinate.unit},
          {"metres_per_unit", w.coordinate.metres_per_unit}};
}

std::string revolutions_header(int n) { return csv_header(output_file("revolutions.csv"), n); }

void append_revolution_line(std::string& out, const RevolutionRecord& r) {
  out += std::to_string(r.revolution);
  out += r.complete ? ",true" : ",false";
  for (double v : {r.t_start, r.t_end}) {
    out += ',';
    put(out, v);
  }
  out += ',' + std::to_string(r.impacts) + ',' + std::to_string(r.contact_episodes);
  for (double v : {r.first_impact_deg, r.last_separation_deg}) {
    out += ',';
    put(out, v);
  }
  for (const LedgerTermInfo& info : kLedgerTerms)
    if (info.report != LedgerReport::internal) {
      out += ',';
      put(out, r.ledger[info.term]);
    }
  for (double v : {r.ledger.energy_change_j, r.ledger.residual(), r.mean_hub_torque_n_m, r.mean_hub_power_w,
                   r.max_tip_deflection_ratio, r.section_distance, r.contact_time_s, r.stick_time_s,
                   r.peak_normal_force_n}) {
    out += ',';
    put(out, v);
  }
  for (const Eigen::VectorXd* v : {&r.q, &r.qd})
    for (Eigen::Index i = 0; i < v->size(); ++i) {
      out += ',';
      put(out, (*v)[i]);
    }
  out += '\n';
}

std::string revolutions_csv(const PassResult& result, int n) {
  std::string out = revolutions_header(n) + "\n";
  for (const RevolutionRecord& r : result.revolutions) append_revolution_line(out, r);
  return out;
}

nlohmann::json summary_json(const PassResult& result, const Config& config, const Surface& surface) {
  const PassSummary& s = result.summary;
  const PassOptions& sim = config.simulation;
  nlohmann::json j;
  j["impacts"] = s.impacts;
  j["plastic_impacts"] = s.plastic_impacts;
  j["contact_episodes"] = s.contact_episodes;
  j["first_impact_deg"] = number_or_null(s.first_impact_deg);
  j["last_separation_deg"] = number_or_null(s.last_separation_deg);
  j["contact_time_s"] = s.contact_time_s;
  j["stick_time_s"] = s.stick_time_s;
  j["peak_normal_force_n"] = s.peak_normal_force_n;
  j["mean_normal_force_n"] = s.mean_normal_force_n;
  j["binned_force"] = {{"bin_deg", s.binned_force.bin_deg},
                       {"peak_normal_force_n", s.binned_force.peak_normal_force_n},
                       {"peak_tangential_force_n", s.binned_force.peak_tangential_force_n},
                       {"peak_normal_at_deg", number_or_null(s.binned_force.peak_normal_at_deg)}};
  put_ledger_terms(j, s.ledger);
  j["hub_impulsive_work_j"] = s.hub_impulsive_work_j;
  j["energy_change_j"] = s.ledger.energy_change_j;
  j["ledger_residual_j"] = s.ledger.residual();
  j["ledger_terms"] = ledger_terms_json();
  j["max_tip_deflection_ratio"] = s.max_tip_deflection_ratio;
  j["validity"] = validity_name(s.validity);
  j["energy_audit_residual"] = s.energy_audit_residual;
  j["mean_hub_torque_n_m"] = number_or_null(s.mean_hub_torque_n_m);
  j["mean_hub_power_w"] = number_or_null(s.mean_hub_power_w);
  if (s.natural_frequencies_hz.size() > 0) {
    nlohmann::json f = nlohmann::json::array();
    for (double v : s.natural_frequencies_hz) f.push_back(number_or_null(v));
    j["natural_frequencies_hz"] = f;
  }
  j["revolutions"] = s.revolutions;
  // The last complete revolution (the steady one of a run that reached its steady state): what a rub
  // map or a brush reads per revolution.
  if (s.last_revolution) {
    const RevolutionRecord& r = *s.last_revolution;
    nlohmann::json last = {{"revolution", r.revolution},
                           {"impacts", r.impacts},
                           {"contact_episodes", r.contact_episodes},
                           {"contact_time_s", r.contact_time_s},
                           {"stick_time_s", r.stick_time_s},
                           {"peak_normal_force_n", r.peak_normal_force_n},
                           {"max_tip_deflection_ratio", r.max_tip_deflection_ratio},
                           {"energy_change_j", r.ledger.energy_change_j},
                           {"ledger_residual_j", r.ledger.residual()}};
    put_ledger_terms(last, r.ledger);
    j["last_revolution"] = last;
  } else {
    j["last_revolution"] = nullptr;
  }
  if (s.steady_state.sought) {
    const SteadyState& st = s.steady_state;
    nlohmann::json mu = nlohmann::json::array();
    for (const Multiplier& m : st.multipliers) mu.push_back({{"re", m.re}, {"im", m.im}, {"abs", m.magnitude()}});
    j["steady_state"] = {{"reached", st.reached},
                         {"after_revolutions", st.after_revolutions},
                         {"period_revolutions", st.period_revolutions},
                         {"tolerance", st.tolerance},
                         {"method", steady_method_name(st.method)},
                         {"multipliers", mu},
                         {"final_section_distance", number_or_null(st.final_distance)},
                         {"newton_iterations", st.newton_iterations},
                         {"map_evaluations", st.map_evaluations},
                         {"event_sequence_changes", st.event_sequence_changes},
                         {"jacobian", st.jacobian},
                         {"note", st.note}};
  } else {
    j["steady_state"] = nullptr;
  }
  j["wear"] = wear_json(wear_report(result, config.wear, surface, config.beam.diameter_m, sim.wear_profile_bins));
  j["ended_clear_deg"] = number_or_null(s.ended_clear_deg);
  j["steps"] = s.steps;
  j["rhs_evaluations"] = s.rhs_evaluations;
  j["corrector_iterations_max"] = s.corrector_iterations_max;
  j["wall_time_s"] = s.wall_time_s;
  j["scheme"] = scheme_name(s.scheme);
  if (s.scheme == Scheme::thesis)
    j["tolerances"] = {{"free_step_s", sim.free_step_s},
                       {"contact_step_s", sim.contact_step_s},
                       {"fine_contact_step_s", sim.fine_contact_step_s},
                       {"corrector_tolerance", sim.corrector_tolerance}};
  else
    j["tolerances"] = {{"rtol", sim.rtol}, {"atol", sim.atol}, {"max_step_s", sim.max_step_s}};
  j["warnings"] = s.warnings;
  nlohmann::json intervals = nlohmann::json::array();
  for (const ContactInterval& c : s.contact_intervals)
    intervals.push_back({{"t_start_s", c.t_start},
                         {"t_end_s", c.t_end},
                         {"theta_start_deg", c.theta_start * 180.0 / M_PI},
                         {"theta_end_deg", c.theta_end * 180.0 / M_PI},
                         {"y_start_m", c.y_start},
                         {"y_end_m", c.y_end},
                         {"revolution", c.revolution}});
  j["contact_intervals"] = intervals;
  if (result.failure)
    j["failure"] = {{"kind", failure_name(result.failure->kind)},
                    {"t_s", result.failure->t},
                    {"theta_deg", result.failure->theta * 180.0 / M_PI},
                    {"message", result.failure->message}};
  else
    j["failure"] = nullptr;
  j["surface"] = surface.describe();
  j["config"] = config.to_json();
  return j;
}

double available_disk_bytes(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::path existing = std::filesystem::absolute(dir, ec);
  if (ec) return 0.0;
  while (!std::filesystem::exists(existing, ec) && existing.has_parent_path() && existing != existing.parent_path())
    existing = existing.parent_path();
  const std::filesystem::space_info space = std::filesystem::space(existing, ec);
  return ec ? 0.0 : static_cast<double>(space.available);
}

void refuse_folders_under_file_names(const std::filesystem::path& dir, const std::vector<std::string>& names,
                                     const std::string& writer) {
  std::error_code ec;
  for (const std::string& name : names)
    if (std::filesystem::is_directory(std::filesystem::symlink_status(dir / name, ec)))
      throw std::runtime_error((dir / name).string() + ": is a folder, where " + writer + " writes its file " + name);
}

std::unique_ptr<FolderLock> open_study_folder(const std::filesystem::path& dir, const std::string& what,
                                              const std::vector<std::string>& files,
                                              const std::vector<std::string>& pictures) {
  namespace fs = std::filesystem;
  std::error_code ec;
  // Another kind of output, known by a file only it writes (its own kind's file is in `files`).
  const std::pair<const char*, const char*> kinds[] = {{"sweep.csv", "a sweep"},
                                                       {"history.csv", "a run"},
                                                       {"workpiece.csv", "a brush"},
                                                       {"wear_history.csv", "a wear run"},
                                                       {"branch.csv", "a continuation"},
                                                       {"report.md", "a reproduction"}};
  for (const auto& [file, kind] : kinds)
    if (std::find(files.begin(), files.end(), file) == files.end() && fs::exists(dir / file, ec))
      throw std::runtime_error(dir.string() + ": holds " + kind + " (" + file + "), not " + what +
                               "; give another folder");
  prepare_output_folder(dir);
  auto lock = std::make_unique<FolderLock>(dir);
  refuse_folders_under_file_names(dir, files, "the " + what.substr(what.find(' ') + 1));
  const bool older = fs::is_regular_file(fs::symlink_status(dir / "summary.json", ec));
  ec.clear();
  fs::remove(dir / "summary.json", ec);
  if (ec)
    throw std::runtime_error((dir / "summary.json").string() + ": cannot remove the older summary (" + ec.message() + ")");
  if (older)
    for (const std::string& drawn : pictures)  // the pictures, not a folder of the user's under their name
      if (fs::is_regular_file(fs::symlink_status(dir / drawn, ec))) fs::remove(dir / drawn, ec);
  return lock;
}

void prepare_output_folder(const std::filesystem::path& dir) {
  std::error_code ec;
  // A link to nowhere: "cannot create the output folder (File exists)" did not say why.
  if (std::filesystem::is_symlink(std::filesystem::symlink_status(dir, ec)) && !std::filesystem::exists(dir, ec))
    throw std::runtime_error(dir.string() + ": a link to " + std::filesystem::read_symlink(dir, ec).string() +
                             ", which does not exist; give a folder");
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw std::runtime_error(dir.string() + ": cannot create the output folder (" +
                             (ec ? ec.message() : std::string("not a folder")) + ")");
  const std::filesystem::path probe = dir / ".rotbeam-write-check";
  write_file_atomically(probe, "");
  std::filesystem::remove(probe, ec);
}

namespace {
// The suffixes this writer gives its temporaries after ".tmp.": "<pid>" or "<pid>.<piece>". Only
// those are a killed run's leftovers; a user's "history.csv.tmp.backup" is not touched.
bool is_temporary_suffix(const std::string& rest) {
  const std::size_t dot = rest.find('.');
  const auto digits = [](const std::string& s) {
    return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
  };
  return dot == std::string::npos ? digits(rest) : digits(rest.substr(0, dot)) && digits(rest.substr(dot + 1));
}
}  // namespace

namespace {
// True when `dir` holds files a run of rotbeam wrote: a summary.json with the run's `config` and
// `files`, or a history.csv or events.csv that begins with the run's header (a killed run's).
bool holds_run_files(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_regular_file(fs::symlink_status(dir / "summary.json", ec))) {
    std::ifstream in(dir / "summary.json");
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    if (j.is_object() && j.contains("config") && j.contains("files")) return true;
  }
  for (const auto& [name, header] : {std::pair<const char*, std::string>{"history.csv", "t_s,theta_deg,phase,"},
                                     std::pair<const char*, std::string>{"events.csv", events_header()}})
    if (fs::is_regular_file(fs::symlink_status(dir / name, ec))) {
      std::ifstream in(dir / name);
      std::string first(header.size(), '\0');
      if (in.read(first.data(), static_cast<std::streamsize>(first.size())) && first == header) return true;
    }
  return false;
}
}  // namespace

PassFiles::PassFiles(const std::filesystem::path& dir, int n, int history_revolutions)
    : dir_(dir), n_(n), window_(history_revolutions) {
  namespace fs = std::filesystem;
  // A sweep's folder (its sweep.csv) is not made a run's as well: `plot` would draw one of the two.
  if (fs::exists(dir / "sweep.csv"))
    throw std::runtime_error(dir.string() + ": holds a sweep (sweep.csv), not a run; give another folder");
  if (fs::exists(dir / "workpiece.csv"))
    throw std::runtime_error(dir.string() + ": holds a brush (workpiece.csv), not a run; give another folder");
  if (fs::exists(dir / "manifest.json") && fs::exists(dir / "report.md"))
    throw std::runtime_error(dir.string() + ": holds a reproduction (manifest.json, report.md), not a run; give another folder");
  prepare_output_folder(dir);
  lock_ = std::make_unique<FolderLock>(dir);  // one run at a time in a folder
  try {
    // A folder under one of the names the run writes would make the final rename fail after the
    // whole computation: refused before it starts.
    std::error_code ec;
    refuse_folders_under_file_names(dir, {"history.csv", "events.csv", "revolutions.csv", "force_bins.csv", "wear_profile.csv", "summary.json"},
                                    "the run");
    // With the lock held no live run writes here: temporaries are a killed run's leftovers.
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
      const std::string name = e.path().filename().string();
      for (const std::string stem :
           {"history.csv.tmp.", "events.csv.tmp.", "revolutions.csv.tmp.", "force_bins.csv.tmp.", "wear_profile.csv.tmp.",
            "summary.json.tmp."})
        if (name.rfind(stem, 0) == 0 && is_temporary_suffix(name.substr(stem.size()))) fs::remove(e.path(), ec);
    }
    // An older run's files (summary.json, or the history and events a killed run left) describe that
    // run: its pictures and animation (`rotbeam plot`, `rotbeam animate`), revolutions and force bins
    // are removed with it, so that nothing sits beside other data. In a folder without them, files
    // of these names are the user's and stay; so do they beside a user's summary.json that is not a
    // run's (`{"mine": 1}` deleted the user's energy.png).
    const bool older_run = holds_run_files(dir);
    if (older_run)
      for (const char* drawn : {"normal_force_vs_y.png", "tip_path.png", "modal_coordinates.png", "energy.png",
                                "impacts.png", "animation.gif", "animation.mp4"})
        if (fs::is_regular_file(fs::symlink_status(dir / drawn, ec))) fs::remove(dir / drawn, ec);
    ec.clear();
    fs::remove(dir / "summary.json", ec);  // the folder is not complete until commit()
    if (older_run && !ec) fs::remove(dir / "revolutions.csv", ec);  // the older run's, which this run may not write
    if (older_run && !ec) fs::remove(dir / "force_bins.csv", ec);
    if (older_run && !ec) fs::remove(dir / "wear_profile.csv", ec);
    if (ec)
      throw std::runtime_error((dir / "summary.json").string() + ": cannot remove the older summary (" + ec.message() + ")");
    open(history_, "history.csv", history_header(n));
    open(events_, "events.csv", events_header());
  } catch (...) {
    release();  // no destructor runs for a constructor that throws: leave no temporary and no lock
    throw;
  }
}

PassFiles::~PassFiles() { release(); }

void PassFiles::release() noexcept {
  if (!committed_)
    for (Stream* s : {&history_, &events_, &revolutions_}) {
      if (s->file) std::fclose(s->file);
      s->file = nullptr;
      if (!s->temporary_path.empty()) std::remove(s->temporary_path.c_str());
      for (const std::filesystem::path& p : s->pieces) std::remove(p.c_str());
    }
  lock_.reset();
}

void PassFiles::open(Stream& s, const std::string& name, const std::string& header) {
  s.final_path = dir_ / name;
  s.temporary_path = dir_ / (name + ".tmp." + std::to_string(::getpid()));
  s.file = std::fopen(s.temporary_path.c_str(), "wb");
  if (!s.file) throw std::runtime_error(io_error(s.final_path, "cannot write", errno));
  s.header = header + "\n";
  s.buffer = s.header;
  s.buffer.reserve(kFlushBytes + 4096);
}

void PassFiles::rotate(Stream& s) {
  flush(s);
  if (std::fclose(s.file) != 0) throw std::runtime_error(io_error(s.final_path, "write failed", errno));
  s.file = nullptr;
  s.pieces.push_back(s.temporary_path);
  while (static_cast<int>(s.pieces.size()) > window_.complete_pieces_kept()) {
    std::remove(s.pieces.front().c_str());
    s.pieces.erase(s.pieces.begin());
    s.first_piece_has_header = false;
  }
  s.temporary_path = s.final_path;
  s.temporary_path += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(++piece_count_);
  s.file = std::fopen(s.temporary_path.c_str(), "wb");
  if (!s.file) throw std::runtime_error(io_error(s.final_path, "cannot write", errno));
}

void PassFiles::assemble(Stream& s) {
  if (s.pieces.empty() && s.first_piece_has_header) return;
  // The final file is written beside the pieces, then the current piece is replaced by it.
  flush(s);
  if (std::fclose(s.file) != 0) throw std::runtime_error(io_error(s.final_path, "write failed", errno));
  std::filesystem::path joined = s.final_path;
  joined += ".tmp." + std::to_string(::getpid()) + ".joined";
  std::FILE* out = std::fopen(joined.c_str(), "wb");
  if (!out) throw std::runtime_error(io_error(s.final_path, "cannot write", errno));
  std::uintmax_t bytes = 0;
  auto put_bytes = [&](const char* data, std::size_t size) {
    if (std::fwrite(data, 1, size, out) != size) {
      std::fclose(out);
      throw std::runtime_error(io_error(s.final_path, "write failed", errno));
    }
    bytes += size;
  };
  if (!s.first_piece_has_header) put_bytes(s.header.data(), s.header.size());
  std::vector<std::filesystem::path> parts = s.pieces;
  parts.push_back(s.temporary_path);
  std::vector<char> chunk(1 << 16);
  for (const std::filesystem::path& part : parts) {
    std::FILE* in = std::fopen(part.c_str(), "rb");
    if (!in) {
      std::fclose(out);
      throw std::runtime_error(io_error(part, "cannot read back", errno));
    }
    std::size_t got;
    while ((got = std::fread(chunk.data(), 1, chunk.size(), in)) > 0) put_bytes(chunk.data(), got);
    std::fclose(in);
    std::remove(part.c_str());
  }
  if (std::fclose(out) != 0) throw std::runtime_error(io_error(s.final_path, "write failed", errno));
  s.pieces.clear();
  s.temporary_path = joined;
  s.bytes = bytes;
  s.file = std::fopen(s.temporary_path.c_str(), "ab");  // close() below renames it into place
  if (!s.file) throw std::runtime_error(io_error(s.final_path, "cannot write", errno));
}

void PassFiles::flush(Stream& s) {
  if (s.buffer.empty()) return;
  const std::size_t written = std::fwrite(s.buffer.data(), 1, s.buffer.size(), s.file);
  if (written != s.buffer.size()) throw std::runtime_error(io_error(s.final_path, "write failed", errno));
  s.bytes += written;
  s.buffer.clear();
}

void PassFiles::close(Stream& s) {
  flush(s);
  const int rc = std::fclose(s.file);
  s.file = nullptr;
  if (rc != 0) throw std::runtime_error(io_error(s.final_path, "write failed", errno));
  std::error_code ec;
  std::filesystem::rename(s.temporary_path, s.final_path, ec);
  if (ec) throw std::runtime_error(s.final_path.string() + ": cannot rename into place (" + ec.message() + ")");
  s.temporary_path.clear();
}

void PassFiles::row(const HistoryRow& row) {
  if (window_.starts_piece(row.t)) start_next_piece();
  append_history_line(history_.buffer, row);
  if (history_.buffer.size() >= kFlushBytes) flush(history_);
}

void PassFiles::event(const PassEvent& event) {
  if (window_.starts_piece(event.t)) start_next_piece();
  append_event_line(events_.buffer, event);
  if (events_.buffer.size() >= kFlushBytes) flush(events_);
}

void PassFiles::start_next_piece() {
  rotate(history_);
  rotate(events_);
}

void PassFiles::revolution(const RevolutionRecord& r) {
  if (!revolutions_.file) open(revolutions_, "revolutions.csv", revolutions_header(n_));
  append_revolution_line(revolutions_.buffer, r);
  if (revolutions_.buffer.size() >= kFlushBytes) flush(revolutions_);
  window_.revolution(r);
}

void PassFiles::commit(const PassResult& result, const Config& config, const Surface& surface) {
  assemble(history_);
  assemble(events_);
  close(history_);
  close(events_);
  if (revolutions_.file) close(revolutions_);
  const std::string bins = force_bins_csv(result);
  write_file_atomically(dir_ / "force_bins.csv", bins);
  const std::string wear = wear_profile_csv(
      wear_report(result, config.wear, surface, config.beam.diameter_m, config.simulation.wear_profile_bins), config.wear);
  write_file_atomically(dir_ / "wear_profile.csv", wear);
  nlohmann::json j = summary_json(result, config, surface);
  j["files"] = {{"history.csv", {{"bytes", history_.bytes}}},
                {"events.csv", {{"bytes", events_.bytes}}},
                {"force_bins.csv", {{"bytes", bins.size()}}},
                {"wear_profile.csv", {{"bytes", wear.size()}}}};
  if (!revolutions_.final_path.empty()) j["files"]["revolutions.csv"] = {{"bytes", revolutions_.bytes}};
  write_file_atomically(dir_ / "summary.json", j.dump(2) + "\n");
  committed_ = true;
}

bool complete_run_folder(const std::filesystem::path& dir, nlohmann::json* summary) {
  namespace fs = std::filesystem;
  std::ifstream in(dir / "summary.json");
  if (!in) return false;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
    // A run's summary names at least history.csv and events.csv; a brush's its two tables.
    const bool brush = j.contains("kind") && j["kind"] == "brush";
    j.at("files").at(brush ? "workpiece.csv" : "history.csv");
    j.at("files").at(brush ? "filaments.csv" : "events.csv");
    for (const auto& [name, entry] : j.at("files").items()) {
      std::error_code ec;
      const std::uintmax_t size = fs::file_size(dir / name, ec);
      if (ec || size != entry.at("bytes").get<std::uintmax_t>()) return false;
    }
  } catch (const std::exception&) {
    return false;
  }
  if (summary) *summary = std::move(j);
  return true;
}

void write_pass_outputs(const std::filesystem::path& dir, const PassResult& result, const Config& config,
                        const Surface& surface) {
  PassFiles files(dir, coordinate_count(config.beam));
  for (const HistoryRow& r : result.history) files.row(r);
  for (const PassEvent& e : result.events) files.event(e);
  for (const RevolutionRecord& r : result.revolutions) files.revolution(r);  // the window was applied in memory
  files.commit(result, config, surface);
}

}  // namespace rotbeam
