// `rotbeam brush`: a brush of many filaments at their steady state, and its force, torque and power
// on the workpiece (docs/brush.md).
#include "commands.hpp"
#include "common.hpp"

#include "rotbeam/brush.hpp"
#include "rotbeam/brush_output.hpp"

#include <cmath>
#include <toml++/toml.h>
#include <filesystem>
#include <iostream>
#include <memory>
#include <unistd.h>

namespace rotbeam::cli {

namespace {

struct BrushCommandOptions {
  CaseOptions case_options;
  std::string output_dir;
  int jobs = 0;
  bool json = false;
  bool quiet = false;
};

// "1 filament", "24 filaments".
std::string counted(long long n, const std::string& word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

void print_summary(const Config& config, const BrushResult& r, const std::string& dir) {
  const BrushSummary& s = r.summary;
  const BrushSettings& b = *config.brush;
  std::cout << "Brush: " << counted(s.filaments, "filament") << " (" << b.filaments << " around × "
            << counted(b.rows, "row") << ", " << s.distinct_filaments
            << (s.population ? " representatives run" : " distinct") << "), " << number_text(config.beam.speed_rpm) << " rpm, "
            << surface_text(config) << ", μ = " << config.contact.friction.mu << ", "
            << modes_text(config) << "\n";
  std::cout << "  filaments             " << s.steady << " steady, " << s.not_steady << " not steady, " << s.failed
            << " failed, " << s.filaments - s.reaching << " clear of the surface\n";
  if (s.reaching > 0 && s.steady + s.not_steady == 0) {
    // No filament that reaches the surface finished: no force, torque or zone to report.
    std::cout << "  results               none: no filament that reaches the surface finished (" << s.failed
              << " failed or not run)\n";
  } else {
    std::cout << "  mean force            " << fixed(s.mean_normal_force_n, 4) << " N normal, "
              << fixed(s.mean_tangential_force_n, 4) << " N tangential (over a revolution)\n";
    std::cout << "  peak binned force     " << fixed(s.peak_normal_force_n, 4) << " N normal, "
              << fixed(s.peak_tangential_force_n, 4) << " N tangential (per " << number_text(s.bin_deg)
              << "° bin of hub angle)\n";
    std::cout << "  hub                   mean torque " << s.mean_hub_torque_n_m * 1e3 << " mN m, mean power "
              << s.mean_hub_power_w * 1e3 << " mW\n";
    if (std::isfinite(s.contact_zone_from_deg))
      std::cout << "  contact zone          " << fixed(s.contact_zone_from_deg, 3) << "° to "
                << fixed(s.contact_zone_to_deg, 3) << "° of a filament's angle, "
                << fixed(s.contact_zone_width_m * 1e3, 3) << " mm along the surface\n";
    else
      std::cout << "  contact zone          none: no filament touched the surface\n";
    std::cout << "  ledger per revolution hub " << s.ledger[LedgerTerm::hub_work] * 1e3 << " mJ, friction "
              << s.ledger[LedgerTerm::friction_work] * 1e3
              << (s.ledger[LedgerTerm::surface_work] != 0.0
                      ? " mJ, surface " + number_text(s.ledger[LedgerTerm::surface_work] * 1e3)
                      : std::string())
              << " mJ, damping " << s.ledger[LedgerTerm::damping_work] * 1e3 << " mJ, impacts "
              << s.ledger[LedgerTerm::impact_loss] * 1e3 << " mJ, residual " << s.ledger_residual_max_j << " J\n";
  }
  std::cout << "  dimensionless         p = " << s.depth_ratio << ", Ω/ω₁ = " << s.speed_ratio;
  if (std::isfinite(s.force_ratio)) std::cout << ", F/(3EI·pL/L³) per filament = " << s.force_ratio;
  std::cout << "\n";
  if (s.population) {
    const PopulationEstimate& p = *s.population;
    std::cout << "  population            " << s.distinct_filaments << " representatives (" << p.lengths << " lengths × "
              << p.diameters << " diameters), estimated error: mean normal force " << number_text(p.normal_force_error)
              << ", hub torque " << number_text(p.hub_torque_error) << " (tolerance " << number_text(p.tolerance)
              << (p.converged ? ", met" : ", not met") << ")\n";
  }
  if (s.seed_spread_normal_force > 0.0)
    std::cout << "  another seed          mean normal force ± " << number_text(100.0 * s.seed_spread_normal_force)
              << " %, hub torque ± " << number_text(100.0 * s.seed_spread_hub_torque) << " % (one standard deviation)\n";
  if (s.at_edge_of_model + s.outside_model + s.barely_reaching > 0)
    std::cout << "  filaments to watch    " << s.outside_model << " outside the model, " << s.at_edge_of_model
              << " at its edge, " << s.barely_reaching << " barely reaching (own depth below a quarter of the nominal)\n";
  std::cout << "  wall time             " << fixed(s.wall_time_s, 2) << " s\n";
  for (const std::string& w : s.warnings) std::cout << "  warning: " << w << "\n";
  std::cout << "  wrote " << (std::filesystem::path(dir) / "workpiece.csv").string()
            << ", profile.csv, filaments.csv, representatives.csv, wear_profile.csv, summary.json\n";
}

int run_brush_command(const BrushCommandOptions& o) {
  if (o.jobs < 0) throw ConfigError("--jobs " + std::to_string(o.jobs) + ": must be >= 0");
  const Config config = o.case_options.load();
  if (!config.brush) {
    // A [brush] table without keys is there, but describes no brush: said as such (it was reported
    // as no [brush] section).
    bool empty_table = false;
    if (o.case_options.config_path) try {
        const toml::table root = toml::parse_file(*o.case_options.config_path);
        empty_table = root.contains("brush") && root["brush"].is_table();
      } catch (const std::exception&) {
        empty_table = false;  // read once already by load(): only the message's wording is at stake
      }
    if (empty_table)
      throw ConfigError("brush: the [brush] section of " + path_text(*o.case_options.config_path) +
                        " holds no keys (give brush.filaments, e.g. filaments = 24 in it or --set brush.filaments=24)");
    throw ConfigError("brush: the configuration has no [brush] section (give brush.filaments, e.g. --set brush.filaments=24)");
  }
  if (o.output_dir.empty()) throw ConfigError("-o DIR: an output folder is required");
  // Every drawn filament is validated before the folder is made: bad input leaves nothing behind.
  brush_filament_configs(config, brush_filaments(config));
  std::unique_ptr<BrushFiles> files;
  try {
    files = std::make_unique<BrushFiles>(o.output_dir);
  } catch (const std::exception& e) {
    throw ConfigError(std::string("-o ") + e.what());
  }
  install_interrupt_handlers();
  BrushOptions options;
  options.threads = o.jobs;
  options.stop = &interrupt_token();
  const bool terminal = !o.quiet && isatty(STDERR_FILENO);
  auto line = std::make_unique<LiveLine>(terminal);
  line->set([](double e) { return "filaments under way, " + fixed(e, 0) + " s elapsed"; });
  options.on_progress = [&line](const BrushProgress& p) {
    const int finished = p.finished, total = p.total;
    const double at = p.elapsed_s, eta = p.eta_s;
    line->set([=](double e) {
      return std::to_string(finished) + "/" + std::to_string(total) + " distinct filaments at their steady state, " +
             fixed(e, 0) + " s elapsed, ETA " + fixed(std::max(0.0, eta - (e - at)), 0) + " s";
    });
  };
  const BrushResult r = run_brush(config, options);
  line.reset();
  files->commit(r, config);
  if (o.json)
    std::cout << brush_summary_json(r, config).dump(2) << "\n";
  else
    print_summary(config, r, o.output_dir);
  if (r.summary.failure) {
    const NumericalFailure& f = *r.summary.failure;
    if (f.kind == FailureKind::interrupted) {
      print_error("interrupted: " + counted(r.summary.failed, "filament") + " not finished; the files in " +
                  o.output_dir + " hold the others");
      return kInterrupted;
    }
    const std::string first = "filament " + std::to_string(r.summary.failed_filament + 1) + " failed (" +
                              failure_name(f.kind) + ") at t = " + number_text(f.t) + " s, θ = " +
                              fixed(f.theta * 180.0 / M_PI, 4) + " deg: " + f.message;
    if (r.summary.steady + r.summary.not_steady == 0) {  // no filament that reaches the surface finished
      print_error(first + "; no filament that reaches the surface finished: the brush has no result");
      return exit_code_for_failure(f.kind);
    }
    print_error("partial brush: " + counted(r.summary.failed, "filament") + " of " +
                std::to_string(r.summary.reaching) + " failed, the first: " + first + "; the sums in " + o.output_dir +
                " leave them out and miss an estimated " + fixed(100.0 * r.summary.missing_force_fraction, 2) +
                " % of the mean normal force (summary.json missing_force_fraction, filaments.csv status)");
    return kPartialBrush;
  }
  if (!r.summary.error.empty()) {
    print_error(r.summary.error + "; the sums in " + o.output_dir + " leave it out");
    return kRuntimeFailure;
  }
  return kSuccess;
}

}  // namespace

Command add_brush_command(CLI::App& app) {
  auto opts = std::make_shared<BrushCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "brush", "A brush of many filaments at their steady state: force, torque and power on the workpiece");
  opts->case_options.add_to(*sub);
  sub->add_option("-o,--output", opts->output_dir, "Output folder (created if needed)")->required()->check(non_empty_path());
  sub->add_option("--jobs", opts->jobs, "Threads (default: all cores)");
  sub->add_flag("--json", opts->json, "Print summary.json instead of the human summary");
  sub->add_flag("--quiet", opts->quiet, "No progress line on stderr");
  return [opts] { return run_brush_command(*opts); };
}

}  // namespace rotbeam::cli
