// The columns of the CSV files, declared once (output_columns.hpp): every writer's header comes from
// the table and every value lands under its column's name (written with distinct values and read
// back by name), and the documentation names every column.
#include "rotbeam/brush_output.hpp"
#include "rotbeam/output_columns.hpp"
#include "rotbeam/pass_output.hpp"

#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <regex>
#include <sstream>

using namespace rotbeam;

namespace {

// The fields of one CSV line (double quotes around a field that holds a comma or a quote).
std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"') {
      if (quoted && i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else {
        quoted = !quoted;
      }
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else if (c != '\n') {
      out.back() += c;
    }
  }
  return out;
}

// {column: value} of a file's first data line, checked against the table's header for n modes.
std::map<std::string, std::string> by_name(const std::string& file, const std::string& text, int n) {
  std::istringstream in(text);
  std::string head, line;
  std::getline(in, head);
  std::getline(in, line);
  EXPECT_EQ(head, csv_header(output_file(file), n)) << file;
  const std::vector<std::string> names = fields(head), values = fields(line);
  EXPECT_EQ(names.size(), values.size()) << file << ": a line has as many values as the header has columns";
  std::map<std::string, std::string> out;
  for (std::size_t k = 0; k < names.size() && k < values.size(); ++k) out[names[k]] = values[k];
  return out;
}

double value(const std::map<std::string, std::string>& row, const std::string& name) {
  const auto it = row.find(name);
  if (it == row.end()) ADD_FAILURE() << "no column " << name;
  return it == row.end() ? NAN : std::stod(it->second);
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(OutputColumns, HistoryValuesLandUnderTheirNames) {
  HistoryRow r;
  r.t = 1.5, r.theta = 0.25, r.phase = Phase::contact, r.x_tip = 3, r.y_tip = 4, r.gap = 5, r.vx = 6, r.vy = 7;
  r.normal_force = 8, r.friction_force = 9, r.lambda = 10, r.jacobi = 11, r.hub_torque = 12;
  r.q = Eigen::Vector2d(13, 14);
  r.qd = Eigen::Vector2d(15, 16);
  std::string text = history_header(2) + "\n";
  append_history_line(text, r);
  const auto row = by_name("history.csv", text, 2);
  EXPECT_EQ(row.at("phase"), "contact");
  EXPECT_DOUBLE_EQ(value(row, "theta_deg"), 0.25 * 180 / M_PI);
  for (const auto& [name, v] : std::map<std::string, double>{{"t_s", 1.5}, {"x_tip_m", 3}, {"y_tip_m", 4}, {"gap_m", 5},
                                                             {"vx_m_s", 6}, {"vy_m_s", 7}, {"normal_force_n", 8},
                                                             {"friction_force_n", 9}, {"lambda_n", 10}, {"jacobi_j", 11},
                                                             {"hub_torque_n_m", 12}, {"q1_m", 13}, {"q2_m", 14},
                                                             {"qd1_m_s", 15}, {"qd2_m_s", 16}})
    EXPECT_EQ(value(row, name), v) << name;
}

TEST(OutputColumns, EventValuesLandUnderTheirNames) {
  PassEvent e;
  e.t = 1, e.theta = 0.5, e.y_tip = 2, e.kind = EventKind::impact, e.vx_before = 3, e.vx_after = 4, e.restitution = 5;
  e.impulse = 6, e.hub_work = 7, e.detail = "a detail, \"quoted\"";
  std::string text = events_header() + "\n";
  append_event_line(text, e);
  const auto row = by_name("events.csv", text, 0);
  EXPECT_EQ(row.at("kind"), "impact");
  EXPECT_EQ(row.at("detail"), e.detail);
  for (const auto& [name, v] : std::map<std::string, double>{{"t_s", 1}, {"y_tip_m", 2}, {"vx_before_m_s", 3},
                                                             {"vx_after_m_s", 4}, {"restitution", 5}, {"impulse_n_s", 6},
                                                             {"hub_work_j", 7}})
    EXPECT_EQ(value(row, name), v) << name;
}

TEST(OutputColumns, RevolutionValuesLandUnderTheirNames) {
  RevolutionRecord r;
  r.revolution = 3, r.complete = true, r.t_start = 1, r.t_end = 2, r.impacts = 4, r.contact_episodes = 5;
  r.first_impact_deg = 6, r.last_separation_deg = 7, r.mean_hub_torque_n_m = 8, r.mean_hub_power_w = 9;
  r.max_tip_deflection_ratio = 10, r.section_distance = 11, r.contact_time_s = 12, r.peak_normal_force_n = 13;
  double v = 100;
  for (double& term : r.ledger.value) term = ++v;
  r.ledger.energy_change_j = 0.5;
  r.q = Eigen::Vector2d(21, 22);
  r.qd = Eigen::Vector2d(23, 24);
  std::string text = revolutions_header(2) + "\n";
  append_revolution_line(text, r);
  const auto row = by_name("revolutions.csv", text, 2);
  EXPECT_EQ(row.at("complete"), "true");
  for (const LedgerTermInfo& t : kLedgerTerms)
    if (t.report != LedgerReport::internal) EXPECT_EQ(value(row, t.key), r.ledger[t.term]) << t.key;
  EXPECT_EQ(row.count("contact_moment_n_m_s"), 0u) << "an internal term is not written";
  EXPECT_EQ(value(row, "ledger_residual_j"), r.ledger.residual());
  for (const auto& [name, x] : std::map<std::string, double>{
           {"revolution", 3}, {"t_start_s", 1}, {"t_end_s", 2}, {"impacts", 4}, {"contact_episodes", 5},
           {"first_impact_deg", 6}, {"last_separation_deg", 7}, {"energy_change_j", 0.5}, {"mean_hub_torque_n_m", 8},
           {"mean_hub_power_w", 9}, {"max_tip_deflection_ratio", 10}, {"section_distance", 11}, {"contact_time_s", 12},
           {"peak_normal_force_n", 13}, {"q1_m", 21}, {"q2_m", 22}, {"qd1_m_s", 23}, {"qd2_m_s", 24}})
    EXPECT_EQ(value(row, name), x) << name;
}

TEST(OutputColumns, BinsAndBrushValuesLandUnderTheirNames) {
  ForceBin b;
  b.from_deg = 1, b.to_deg = 2, b.normal_impulse_n_s = 3, b.tangential_impulse_n_s = 4, b.mean_normal_force_n = 5;
  b.mean_tangential_force_n = 6, b.impacts = 7, b.hub_angular_impulse_n_m_s = 8, b.mean_hub_torque_n_m = 9;
  PassResult pass;
  pass.force_bins = {b};
  const auto bins = by_name("force_bins.csv", force_bins_csv(pass), 0);
  for (const auto& [name, x] : std::map<std::string, double>{{"theta_from_deg", 1}, {"theta_to_deg", 2},
                                                             {"normal_impulse_n_s", 3}, {"tangential_impulse_n_s", 4},
                                                             {"mean_normal_force_n", 5}, {"mean_tangential_force_n", 6},
                                                             {"impacts", 7}})
    EXPECT_EQ(value(bins, name), x) << name;

  BrushResult brush;
  brush.workpiece = {b};
  const auto work = by_name("workpiece.csv", workpiece_csv(brush, 10.0), 0);
  for (const auto& [name, x] : std::map<std::string, double>{{"normal_force_n", 5}, {"tangential_force_n", 6},
                                                             {"hub_angular_impulse_n_m_s", 8}, {"hub_torque_n_m", 9},
                                                             {"hub_power_w", 90}, {"impacts", 7}})
    EXPECT_EQ(value(work, name), x) << name;
  BrushFilament f;
  f.index = 0, f.row = 1, f.position = 2, f.phase_deg = 3, f.length_m = 4, f.diameter_m = 5, f.depth_fraction = 6;
  FilamentSteadyState d;
  d.ran = d.steady = true;
  d.period_revolutions = 7, d.revolutions_run = 8, d.mean_normal_force_n = 9, d.mean_tangential_force_n = 10;
  d.mean_hub_torque_n_m = 11, d.mean_hub_power_w = 12, d.impacts_per_revolution = 13, d.contact_time_s = 14;
  d.peak_normal_force_n = 15, d.max_tip_deflection_ratio = 16, d.first_contact_deg = 17, d.last_contact_deg = 18;
  d.ledger_residual_max_j = 19;
  brush.filaments = {f};
  brush.distinct = {d};
  const auto fil = by_name("filaments.csv", filaments_csv(brush), 0);
  EXPECT_EQ(fil.at("status"), "steady");
  EXPECT_EQ(fil.at("reaches"), "true");
  for (const auto& [name, x] : std::map<std::string, double>{
           {"filament", 1}, {"row", 2}, {"position", 3}, {"phase_deg", 3}, {"length_m", 4}, {"diameter_m", 5},
           {"depth_fraction", 6}, {"distinct", 1}, {"period_revolutions", 7}, {"revolutions_run", 8},
           {"mean_normal_force_n", 9}, {"mean_tangential_force_n", 10}, {"mean_hub_torque_n_m", 11},
           {"mean_hub_power_w", 12}, {"impacts_per_revolution", 13}, {"contact_time_s", 14},
           {"peak_normal_force_n", 15}, {"max_tip_deflection_ratio", 16}, {"first_contact_deg", 17},
           {"last_contact_deg", 18}, {"ledger_residual_j", 19}})
    EXPECT_EQ(value(fil, name), x) << name;
}

// The paragraph of docs/cli.md (a run's files) or docs/brush.md (a brush's) that describes a file —
// of those that begin with its name, the one naming most of its columns — names every column of the
// table (profile.csv has workpiece.csv's, and says so).
TEST(OutputColumns, TheDocumentationNamesEveryColumn) {
  const std::string docs = read(std::string(ROTBEAM_SOURCE_DIR) + "/docs/cli.md") +
                           read(std::string(ROTBEAM_SOURCE_DIR) + "/docs/brush.md");
  ASSERT_GT(docs.size(), 1000u);
  const auto column_name = [](const OutputColumn& c) {
    std::string name = c.name;
    if (const std::size_t at = name.find("{i}"); at != std::string::npos) name.replace(at, 3, "1");
    return name;
  };
  const auto names = [](const std::string& text, const std::string& name) {
    return std::regex_search(text, std::regex("\\b" + name + "\\b"));
  };
  for (const OutputFile& f : output_files()) {
    const std::string file = f.name == "profile.csv" ? "workpiece.csv" : f.name;
    std::string best;
    int best_count = -1;
    for (const std::string& opening : {"\n* `" + file + "`", "\n`" + file + "`"})
      for (std::size_t start = docs.find(opening); start != std::string::npos; start = docs.find(opening, start + 1)) {
        const std::size_t end =
            std::min({docs.find("\n* `", start + 1), docs.find("\n\n`", start + 1), docs.find("\n## ", start + 1)});
        const std::string text = docs.substr(start, end == std::string::npos ? std::string::npos : end - start);
        int count = 0;
        for (const OutputColumn& c : f.columns) count += names(text, column_name(c));
        if (count > best_count) best = text, best_count = count;
      }
    ASSERT_FALSE(best.empty()) << "no paragraph on " << f.name;
    for (const OutputColumn& c : f.columns) {
      EXPECT_TRUE(names(best, column_name(c))) << f.name << ": " << c.name;
      EXPECT_FALSE(c.description.empty()) << f.name << ": " << c.name;
    }
  }
}
