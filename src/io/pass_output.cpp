#include "rotbeam/pass_output.hpp"

#include "rotbeam/atomic_file.hpp"
#include "rotbeam/detail/csv.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace rotbeam {

using detail::csv_field;

namespace {

void put(std::string& out, double v) {
  char buf[40];
  if (std::isnan(v)) {
    out += "nan";
    return;
  }
  std::snprintf(buf, sizeof buf, "%.17g", v);
  out += buf;
}

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

std::string history_header(int n) {
  std::string h = "t_s,theta_deg,phase,x_tip_m,y_tip_m,gap_m,vx_m_s,vy_m_s,normal_force_n,friction_force_n,lambda_n";
  for (int i = 1; i <= n; ++i) h += ",q" + std::to_string(i) + "_m";
  for (int i = 1; i <= n; ++i) h += ",qd" + std::to_string(i) + "_m_s";
  h += ",jacobi_j,hub_torque_n_m";
  return h;
}

std::string history_csv(const PassResult& result, int n) {
  std::string out = history_header(n) + "\n";
  out.reserve(result.history.size() * (200 + 50 * n));
  for (const HistoryRow& r : result.history) {
    const double vals[] = {r.t, r.theta * 180.0 / M_PI};
    put(out, vals[0]);
    out += ',';
    put(out, vals[1]);
    out += ',';
    out += phase_name(r.phase);
    for (double v : {r.x_tip, r.y_tip, r.gap, r.vx, r.vy, r.normal_force, r.friction_force, r.lambda}) {
      out += ',';
      put(out, v);
    }
    for (int i = 0; i < n; ++i) {
      out += ',';
      put(out, r.q[i]);
    }
    for (int i = 0; i < n; ++i) {
      out += ',';
      put(out, r.qd[i]);
    }
    out += ',';
    put(out, r.jacobi);
    out += ',';
    put(out, r.hub_torque);
    out += '\n';
  }
  return out;
}

std::string events_csv(const PassResult& result) {
  std::string out = "t_s,theta_deg,kind,y_tip_m,vx_before_m_s,vx_after_m_s,restitution,impulse_n_s,detail\n";
  for (const PassEvent& e : result.events) {
    put(out, e.t);
    out += ',';
    put(out, e.theta * 180.0 / M_PI);
    out += ',' + e.kind + ',';
    put(out, e.y_tip);
    for (double v : {e.vx_before, e.vx_after, e.restitution, e.impulse}) {
      out += ',';
      if (!std::isnan(v)) put(out, v);
    }
    out += ',' + csv_field(e.detail) + '\n';
  }
  return out;
}

nlohmann::json summary_json(const PassResult& result, const Config& config) {
  const PassSummary& s = result.summary;
  nlohmann::json j;
  j["impacts"] = s.impacts;
  j["plastic_impacts"] = s.plastic_impacts;
  j["contact_episodes"] = s.contact_episodes;
  j["first_impact_deg"] = number_or_null(s.first_impact_deg);
  j["last_separation_deg"] = number_or_null(s.last_separation_deg);
  j["contact_time_s"] = s.contact_time_s;
  j["peak_normal_force_n"] = s.peak_normal_force_n;
  j["mean_normal_force_n"] = s.mean_normal_force_n;
  j["normal_impulse_n_s"] = s.normal_impulse_n_s;
  j["friction_work_j"] = s.friction_work_j;
  j["max_tip_deflection_ratio"] = s.max_tip_deflection_ratio;
  j["energy_audit_residual"] = s.energy_audit_residual;
  j["steps"] = s.steps;
  j["rhs_evaluations"] = s.rhs_evaluations;
  j["corrector_iterations_max"] = s.corrector_iterations_max;
  j["wall_time_s"] = s.wall_time_s;
  j["scheme"] = s.scheme;
  if (s.scheme == "thesis")
    j["tolerances"] = {{"free_step_s", config.free_step_s},
                       {"contact_step_s", config.contact_step_s},
                       {"fine_contact_step_s", config.fine_contact_step_s},
                       {"corrector_tolerance", config.corrector_tolerance}};
  else
    j["tolerances"] = {{"rtol", config.rtol}, {"atol", config.atol}, {"max_step_s", config.max_step_s}};
  j["warnings"] = s.warnings;
  nlohmann::json intervals = nlohmann::json::array();
  for (const ContactInterval& c : s.contact_intervals)
    intervals.push_back({{"t_start_s", c.t_start},
                         {"t_end_s", c.t_end},
                         {"theta_start_deg", c.theta_start * 180.0 / M_PI},
                         {"theta_end_deg", c.theta_end * 180.0 / M_PI},
                         {"y_start_m", c.y_start},
                         {"y_end_m", c.y_end}});
  j["contact_intervals"] = intervals;
  if (result.failure)
    j["failure"] = {{"kind", result.failure->kind},
                    {"t_s", result.failure->t},
                    {"theta_deg", result.failure->theta * 180.0 / M_PI},
                    {"message", result.failure->message}};
  else
    j["failure"] = nullptr;
  j["config"] = config.to_json();
  return j;
}

void prepare_output_folder(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw std::runtime_error(dir.string() + ": cannot create the output folder (" +
                             (ec ? ec.message() : std::string("not a folder")) + ")");
  const std::filesystem::path probe = dir / ".rotbeam-write-check";
  write_file_atomically(probe, "");
  std::filesystem::remove(probe, ec);
}

void write_pass_outputs(const std::filesystem::path& dir, const PassResult& result, const Config& config) {
  prepare_output_folder(dir);
  const int n = config.physical.modes;
  write_file_atomically(dir / "history.csv", history_csv(result, n));
  write_file_atomically(dir / "events.csv", events_csv(result));
  write_file_atomically(dir / "summary.json", summary_json(result, config).dump(2) + "\n");
}

}  // namespace rotbeam
