#include "rotbeam/output_columns.hpp"

#include "rotbeam/ledger.hpp"
#include "rotbeam/outcome.hpp"
#include "rotbeam/state.hpp"

#include <stdexcept>

namespace rotbeam {

namespace {

OutputColumn number(const char* name, const char* unit, const char* description) {
  return {name, unit, ColumnKind::number, description, {}};
}
OutputColumn optional(const char* name, const char* unit, const char* description) {
  return {name, unit, ColumnKind::optional_number, description, {}};
}
OutputColumn integer(const char* name, const char* description) { return {name, "1", ColumnKind::integer, description, {}}; }

std::vector<std::string> phase_words() {
  std::vector<std::string> w;
  for (Phase p : {Phase::free, Phase::contact, Phase::stick}) w.push_back(phase_name(p));
  return w;
}

std::vector<std::string> event_words() {
  std::vector<std::string> w;
  for (const auto& [kind, name] : detail::kEvents) w.push_back(name);
  return w;
}

std::vector<OutputFile> make_files() {
  std::vector<OutputFile> files;
  files.push_back(
      {"history.csv",
       {number("t_s", "s", "time since θ0"),
        number("theta_deg", "degree", "hub angle θ"),
        {"phase", "", ColumnKind::word, "the tip's phase", phase_words()},
        number("x_tip_m", "m", "tip X in the global frame"),
        number("y_tip_m", "m", "tip Y in the global frame"),
        number("gap_m", "m", "the gap C (≤ 0 clear of the surface)"),
        number("vx_m_s", "m/s", "tip velocity V_X"),
        number("vy_m_s", "m/s", "tip velocity V_Y"),
        number("normal_force_n", "N", "normal force of sustained contact"),
        number("friction_force_n", "N", "friction force on the tip along the surface's tangent"),
        number("lambda_n", "N", "the contact multiplier λ (≤ 0 in contact)"),
        number("q{i}_m", "m", "modal coordinate i"),
        number("qd{i}_m_s", "m/s", "modal velocity i"),
        number("jacobi_j", "J", "the Jacobi integral h = T2 − T0 + U"),
        number("hub_torque_n_m", "N m", "the torque the hub supplies, dH_z/dt − (X_t F_Y − Y_t F_X)")}});
  files.push_back({"events.csv",
                   {number("t_s", "s", "time of the event"),
                    number("theta_deg", "degree", "hub angle of the event"),
                    {"kind", "", ColumnKind::word, "what happened", event_words()},
                    optional("y_tip_m", "m", "tip Y at the event (empty for a failure)"),
                    optional("vx_before_m_s", "m/s", "normal approach speed Ċ before an impact"),
                    optional("vx_after_m_s", "m/s", "normal speed Ċ after an impact"),
                    optional("restitution", "1", "the restitution an impact used"),
                    optional("impulse_n_s", "N s", "an impact's impulse along the surface's normal"),
                    optional("tangential_impulse_n_s", "N s",
                             "an impact's impulse along the surface's tangent (friction's; 0 without it)"),
                    optional("hub_work_j", "J", "the hub's work during an impact"),
                    optional("impact_loss_j", "J", "an impact's loss: its impulses' work on the tip less a moving surface's part"),
                    optional("surface_work_j", "J", "a moving surface's work through an impact's friction"),
                    optional("frictional_heat_j", "J", "the heat an impact's friction makes (docs/wear.md)"),
                    optional("sliding_load_n_m", "N m", "an impact's Archard load–distance ∫|V_t| dp (docs/wear.md)"),
                    {"detail", "", ColumnKind::text, "the event in words", {}}}});
  const std::vector<OutputColumn> bins_head = {
      number("theta_from_deg", "degree", "the bin's first hub angle, relative to the surface's deepest point"),
      number("theta_to_deg", "degree", "the bin's end"),
      number("normal_impulse_n_s", "N s", "momentum into the surface in the bin"),
      number("tangential_impulse_n_s", "N s", "momentum along the surface's tangent (the force on the surface)")};
  OutputFile bins{"force_bins.csv", bins_head};
  bins.columns.push_back(number("mean_normal_force_n", "N", "normal impulse over the bin's duration"));
  bins.columns.push_back(number("mean_tangential_force_n", "N", "tangential impulse over the bin's duration"));
  bins.columns.push_back(integer("impacts", "impacts in the bin"));
  files.push_back(bins);

  // `rotbeam wear` (docs/wear.md).
  files.push_back(
      {"wear_history.csv",
       {integer("step", "the slow-time step, 0 …"),
        number("time_h", "h", "operating time at the step's start"),
        number("length_m", "m", "the filament's free length L"),
        number("length_lost_m", "m", "the length lost since the start of the run"),
        {"steady", "", ColumnKind::boolean, "whether the steady state was reached within simulation.revolutions", {}},
        integer("period_revolutions", "the steady orbit's period (0: not reached)"),
        integer("revolutions_run", "revolutions the steady-state search ran"),
        number("section_distance", "1", "the section state's relative change over the orbit's period at the search's end"),
        number("impacts_per_revolution", "1", "impacts per revolution on the orbit (its mean)"),
        number("mean_normal_force_n", "N", "the normal impulse per revolution over its duration"),
        number("mean_hub_torque_n_m", "N m", "the hub's mean torque"),
        number("mean_hub_power_w", "W", "the hub's mean power"),
        number("sliding_load_n_m", "N m", "Archard's load–distance per revolution"),
        number("removal_rate_mm3_h", "mm^3/h", "the surface's worn volume per hour of operation"),
        number("length_rate_mm_h", "mm/h", "the filament's length lost per hour"),
        number("heat_w", "W", "the frictional heat made per second"),
        number("heat_to_surface_w", "W", "its share that flows into the surface"),
        number("wall_time_s", "s", "the steady-state search's wall time")}});
  // `rotbeam continue` (docs/continuation.md): 2n columns per {i}, the section state's n + n components.
  files.push_back(
      {"branch.csv",
       {integer("branch", "0, 1, …: branches in the order followed (summary.json's `branches` says how each began)"),
        integer("period", "revolutions per orbit, M"),
        number("parameter", "the key's", "the continued key's value"),
        {"stable", "", ColumnKind::boolean, "whether every multiplier has |μ| < 1", {}},
        number("max_abs_multiplier", "1", "the largest |μ|"),
        number("arclength", "1", "along the branch in the scaled unknowns (docs/continuation.md)"),
        integer("corrector_iterations", "Newton iterations the corrector took (its map evaluations less one)"),
        integer("jacobian_event_changes", "evaluations of the Jacobian's stencil whose impacts or episodes differed"),
        integer("impacts", "impacts over one period"),
        integer("contact_episodes", "sustained-contact episodes over one period"),
        number("normal_impulse_n_s", "N s", "the momentum into the surface over one period"),
        number("peak_normal_force_n", "N", "the largest normal contact force over the period"),
        number("mean_hub_torque_n_m", "N m", "the hub's mean torque over the period"),
        number("mean_hub_power_w", "W", "the hub's mean power over the period"),
        number("max_tip_deflection_ratio", "1", "the largest |y_t|/L over the period"),
        number("z{i}", "1", "the section state: q_i/L for i ≤ n, then q̇_(i−n)/(ωL)"),
        number("mu{i}_re", "1", "multiplier i's real part, largest |μ| first"),
        number("mu{i}_im", "1", "multiplier i's imaginary part")}});
  files.push_back(
      {"wear_depth.csv",
       {number("position_from_m", "m", "the bin's start along the surface (as in wear_profile.csv)"),
        number("position_to_m", "m", "the bin's end"),
        number("coordinate_from", "m or degree", "the bin's start in the surface's own coordinate"),
        number("coordinate_to", "m or degree", "the bin's end in that coordinate"),
        number("surface_volume_m3", "m^3", "the surface's worn volume in the bin over the whole run"),
        number("removed_depth_m", "m", "that volume over the track's width times the bin's length"),
        number("heat_j", "J", "the frictional heat made in the bin over the run")}});

  files.push_back(
      {"wear_profile.csv",
       {number("position_from_m", "m",
               "the bin's start along the surface: Y on a plane, the arc at the nominal radius from angle 0 on a round surface"),
        number("position_to_m", "m", "the bin's end"),
        number("coordinate_from", "m or degree", "the bin's start in the surface's own coordinate (summary.json wear.coordinate_unit)"),
        number("coordinate_to", "m or degree", "the bin's end in that coordinate"),
        number("sliding_load_n_m", "N m", "Archard's load–distance ∫F_n|V_t| dt the contact left in the bin"),
        number("surface_volume_m3", "m^3", "the surface's worn volume in the bin, k_s S / H_s"),
        number("removed_depth_m", "m", "that volume over the track's width times the bin's length"),
        number("heat_j", "J", "the frictional heat made in the bin"),
        number("surface_heat_j_m2", "J/m^2", "the surface's share of it per unit area of the track")}});

  OutputFile revs{"revolutions.csv",
                  {integer("revolution", "1, 2, …"),
                   {"complete", "", ColumnKind::boolean, "false for a revolution cut short", {}},
                   number("t_start_s", "s", "the revolution's start"),
                   number("t_end_s", "s", "its end"),
                   integer("impacts", "impacts in the revolution"),
                   integer("contact_episodes", "contact episodes that ended in it"),
                   number("first_impact_deg", "degree", "first touch, relative angle (nan: none)"),
                   number("last_separation_deg", "degree", "last separation, relative angle (nan: none)")}};
  for (const LedgerTermInfo& t : kLedgerTerms)
    if (t.report != LedgerReport::internal) revs.columns.push_back(number(t.key, t.unit, t.description));
  for (const OutputColumn& c :
       {number("energy_change_j", "J", "change of E = T + U (+ the contact's stored energy)"),
        number("ledger_residual_j", "J", "the energy terms' sum less the energy change"),
        number("mean_hub_torque_n_m", "N m", "hub work over the revolution's angle"),
        number("mean_hub_power_w", "W", "hub work over the revolution's duration"),
        number("max_tip_deflection_ratio", "1", "largest |y_t|/L"),
        number("section_distance", "1", "relative change of the section state from the previous revolution"),
        number("contact_time_s", "s", "time in sustained contact"),
        number("stick_time_s", "s", "the part of it in which the tip stuck"),
        number("peak_normal_force_n", "N", "largest normal force"),
        number("q{i}_m", "m", "modal coordinate i at the revolution's end"),
        number("qd{i}_m_s", "m/s", "modal velocity i at the revolution's end")})
    revs.columns.push_back(c);
  files.push_back(revs);

  OutputFile workpiece{"workpiece.csv", bins_head};
  for (const OutputColumn& c :
       {number("normal_force_n", "N", "mean normal force on the workpiece over the bin"),
        number("tangential_force_n", "N", "mean tangential force on the workpiece over the bin"),
        number("hub_angular_impulse_n_m_s", "N m s", "what the hub gives the filaments in the bin"),
        number("hub_torque_n_m", "N m", "its mean torque over the bin"),
        number("hub_power_w", "W", "its mean power, ω times the torque"),
        integer("impacts", "impacts in the bin")})
    workpiece.columns.push_back(c);
  files.push_back(workpiece);
  OutputFile profile = workpiece;
  profile.name = "profile.csv";
  files.push_back(profile);

  // A filament's steady state per revolution, as filaments.csv and representatives.csv give it.
  const std::vector<OutputColumn> steady_means = {
        integer("period_revolutions", "its orbit's period"),
        integer("revolutions_run", "revolutions run"),
        number("mean_normal_force_n", "N", "normal impulse per revolution over the period"),
        number("mean_tangential_force_n", "N", "tangential impulse per revolution over the period"),
        number("mean_hub_torque_n_m", "N m", "hub work per revolution over 2π"),
        number("mean_hub_power_w", "W", "hub work per revolution over the period"),
        number("impacts_per_revolution", "1", "impacts per revolution"),
        number("contact_time_s", "s", "contact time per revolution"),
        number("peak_normal_force_n", "N", "largest normal force over the orbit"),
        number("max_tip_deflection_ratio", "1", "largest |y_t|/L over the orbit")};
  OutputFile filaments{"filaments.csv",
                       {integer("filament", "its index, 1 …"),
                        integer("row", "its row, 1 …"),
                        integer("position", "its place in the row, 1 …"),
                        number("phase_deg", "degree", "how far ahead of the reference filament it sits"),
                        number("length_m", "m", "its length"),
                        number("diameter_m", "m", "its diameter"),
                        number("depth_fraction", "1", "its own depth over its length"),
                        integer("distinct", "the distinct filament it is a copy of (by population: its nearest representative), 1 …"),
                        {"reaches", "", ColumnKind::boolean, "its tip reaches the surface", {}},
                        {"status", "", ColumnKind::word, "how its run ended", filament_status_words()}}};
  filaments.columns.insert(filaments.columns.end(), steady_means.begin(), steady_means.end());
  for (const OutputColumn& c : {number("first_contact_deg", "degree", "relative angle of its first delivery of momentum"),
                                number("last_contact_deg", "degree", "relative angle of its last"),
                                number("ledger_residual_j", "J", "the largest residual of its ledger per revolution")})
    filaments.columns.push_back(c);
  files.push_back(filaments);
  files.push_back(
      {"spectrum.csv",
       {integer("order", "the harmonic of the revolution, 0 …"),
        number("frequency_hz", "Hz", "order times the revolution's frequency"),
        number("passing_multiple", "1", "order over brush.filaments: whole numbers are the filament-passing frequency's multiples"),
        number("normal_force_n", "N", "amplitude of the workpiece's normal force at this order (the mean at order 0)"),
        number("tangential_force_n", "N", "amplitude of its tangential force"),
        number("hub_torque_n_m", "N m", "amplitude of the hub torque")}});
  OutputFile representatives{
      "representatives.csv",
      {integer("representative", "the filament run, 1 … (filaments.csv's distinct)"),
       number("length_m", "m", "its length"),
       number("diameter_m", "m", "its diameter"),
       number("depth_fraction", "1", "its own depth over its length"),
       number("weight", "1", "the filaments it stands for: its copies, or by population the sum of their interpolation weights"),
       integer("nearest", "the filaments of which it is the nearest (its copies)"),
       {"status", "", ColumnKind::word, "how its run ended", filament_status_words()}}};
  representatives.columns.insert(representatives.columns.end(), steady_means.begin(), steady_means.end());
  files.push_back(representatives);
  return files;
}

}  // namespace

const std::vector<std::string>& filament_status_words() {
  static const std::vector<std::string> words = {"steady", "not_steady", "clear", "failed", "error", "interrupted"};
  return words;
}

const std::vector<OutputFile>& output_files() {
  static const std::vector<OutputFile> files = make_files();
  return files;
}

const OutputFile& output_file(std::string_view name) {
  for (const OutputFile& f : output_files())
    if (f.name == name) return f;
  throw std::invalid_argument("no output file " + std::string(name));
}

std::string csv_header(const OutputFile& file, int modes) {
  std::string h;
  for (const OutputColumn& c : file.columns) {
    const std::size_t at = c.name.find("{i}");
    if (at == std::string::npos) {
      h += (h.empty() ? "" : ",") + c.name;
      continue;
    }
    for (int i = 1; i <= modes; ++i)
      h += (h.empty() ? "" : ",") + c.name.substr(0, at) + std::to_string(i) + c.name.substr(at + 3);
  }
  return h;
}

}  // namespace rotbeam
