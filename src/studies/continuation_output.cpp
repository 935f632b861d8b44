#include "rotbeam/continuation_output.hpp"

#include "rotbeam/atomic_file.hpp"
#include "rotbeam/detail/csv.hpp"
#include "rotbeam/output_columns.hpp"
#include "rotbeam/pass_output.hpp"
#include "rotbeam/version.hpp"

#include <cmath>

namespace rotbeam {

namespace {

constexpr const char* kFiles[] = {"branch.csv", "summary.json"};
constexpr const char* kPictures[] = {"continuation.png"};

void put(std::string& out, double v) {
  out += ',';
  detail::append_number(out, v);
}

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json failure_json(const std::optional<NumericalFailure>& f) {
  if (!f) return nullptr;
  return {{"kind", failure_name(f->kind)}, {"t_s", f->t}, {"theta_deg", f->theta * 180.0 / M_PI}, {"message", f->message}};
}

}  // namespace

std::string branch_csv(const OrbitContinuation& run) {
  const int dim = 2 * run.modes;
  std::string out = csv_header(output_file("branch.csv"), dim) + "\n";
  for (const BranchPoint& p : run.result.points) {
    out += std::to_string(p.branch) + ',' + std::to_string(p.period);
    put(out, p.parameter);
    out += p.stable ? ",true" : ",false";
    put(out, p.multipliers.empty() ? NAN : p.multipliers.front().magnitude());
    put(out, p.arclength);
    out += ',' + std::to_string(p.corrector_iterations) + ',' + std::to_string(p.jacobian_event_changes) + ',' +
           std::to_string(p.metrics.impacts) + ',' + std::to_string(p.metrics.contact_episodes);
    for (double v : {p.metrics.normal_impulse_n_s, p.metrics.peak_normal_force_n, p.metrics.mean_hub_torque_n_m,
                     p.metrics.mean_hub_power_w, p.metrics.max_tip_deflection_ratio})
      put(out, v);
    for (int i = 0; i < dim; ++i) put(out, i < p.z.size() ? p.z[i] : NAN);
    for (int i = 0; i < dim; ++i) put(out, i < static_cast<int>(p.multipliers.size()) ? p.multipliers[static_cast<std::size_t>(i)].re : NAN);
    for (int i = 0; i < dim; ++i) put(out, i < static_cast<int>(p.multipliers.size()) ? p.multipliers[static_cast<std::size_t>(i)].im : NAN);
    out += '\n';
  }
  return out;
}

nlohmann::json continuation_json(const OrbitContinuation& run) {
  const ContinuationResult& r = run.result;
  nlohmann::json j;
  j["kind"] = "continuation";
  j["rotbeam_version"] = kVersion;
  j["parameter"] = run.options.parameter;
  j["from"] = run.options.from;
  j["to"] = run.options.to;
  j["period"] = run.period;
  j["modes"] = run.modes;
  j["complete"] = !r.stopped;
  j["start"] = run.start_note;
  j["points"] = r.points.size();
  int stable = 0;
  for (const BranchPoint& p : r.points) stable += p.stable;
  j["stable_points"] = stable;
  nlohmann::json branches = nlohmann::json::array();
  for (const BranchSummary& b : r.branches)
    branches.push_back({{"branch", b.branch}, {"period", b.period}, {"points", b.points}, {"start", b.start}, {"end", b.end}});
  j["branches"] = branches;
  nlohmann::json special = nlohmann::json::array();
  for (const SpecialPoint& s : r.special) {
    nlohmann::json o = {{"kind", special_kind_name(s.kind)},
                        {"branch", s.branch},
                        {"parameter", s.parameter},
                        {"between_rows", {s.before, s.before + 1}},
                        {"multiplier", {{"re", number_or_null(s.multiplier.re)}, {"im", number_or_null(s.multiplier.im)}}},
                        {"note", s.note}};
    if (s.kind == SpecialKind::period_doubling)
      o["doubled_branch"] = s.doubled_branch >= 0 ? nlohmann::json(s.doubled_branch) : nlohmann::json(nullptr);
    special.push_back(o);
  }
  j["special_points"] = special;
  nlohmann::json crossings = nlohmann::json::array();
  for (const EngineOrderCrossing& c : run.crossings)
    crossings.push_back({{"order", c.order}, {"mode", c.mode}, {"speed_rpm", c.speed_rpm}, {"frequency_hz", c.frequency_hz}});
  j["engine_order_crossings"] = crossings;
  j["map_evaluations"] = r.map_evaluations;
  j["revolutions"] = r.revolutions;
  j["wall_time_s"] = run.wall_time_s;
  j["tolerance"] = run.options.tolerance > 0 ? run.options.tolerance : run.config_from.simulation.steady_tolerance;
  j["failure"] = failure_json(r.failure);
  j["config"] = run.config_from.to_json();
  return j;
}

ContinuationFiles::ContinuationFiles(const std::filesystem::path& dir)
    : dir_(dir),
      lock_(open_study_folder(dir, "a continuation", {std::begin(kFiles), std::end(kFiles)},
                              {std::begin(kPictures), std::end(kPictures)})) {}

ContinuationFiles::~ContinuationFiles() = default;

void ContinuationFiles::commit(const OrbitContinuation& run) {
  const std::string branch = branch_csv(run);
  write_file_atomically(dir_ / "branch.csv", branch);
  nlohmann::json j = continuation_json(run);
  j["files"] = {{"branch.csv", {{"bytes", branch.size()}}}};
  write_file_atomically(dir_ / "summary.json", j.dump(2) + "\n");
}

}  // namespace rotbeam
