// `rotbeam impact`: the first impact of a pass — the Table 5-3 quantities (docs/model.md §7, §8).
#include "commands.hpp"
#include "common.hpp"

#include "rotbeam/case.hpp"
#include "rotbeam/impact_output.hpp"

#include <cmath>
#include <iostream>

namespace rotbeam::cli {

namespace {

struct ImpactOptions {
  CaseOptions case_options;
  bool json = false;
  bool quiet = false;
};

int run_impact(const ImpactOptions& o) {
  const Config config = o.case_options.load_filament("impact");
  install_interrupt_handlers();
  FirstImpactResult r;
  {
    PassProgressLine progress(o.quiet);
    r = run_first_impact(build_case(config), {nullptr, &interrupt_token(), progress.callback()});
  }
  if (r.failure && r.failure->kind == FailureKind::interrupted) {
    print_error("interrupted at t = " + number_text(r.failure->t) + " s, θ = " +
                number_text(r.failure->theta * 180.0 / M_PI) + " deg, before the first impact");
    return exit_code_for_failure(r.failure->kind);
  }
  if (r.failure) {
    print_error("numerical failure (" + std::string(failure_name(r.failure->kind)) + ") at t = " +
                number_text(r.failure->t) + " s, θ = " + number_text(r.failure->theta * 180.0 / M_PI) +
                " deg before the first impact: " + r.failure->message);
    return exit_code_for_failure(r.failure->kind);
  }
  if (!r.found) {
    print_error("no impact: the tip stays clear of the surface up to the end angle " +
                fixed(config.simulation.end_angle_deg, 3) + " deg (closest gap " + std::to_string(r.min_gap) + " m)");
    if (o.json) std::cout << "null\n";  // a script reading the JSON gets a value, not empty input
    return kNoImpact;
  }
  const double theta_deg = r.theta * 180.0 / M_PI;
  const ImpactResult& im = r.impact;
  if (o.json) {
    const nlohmann::json j = impact_json(r, config);
    std::cout << j.dump(2) << "\n";
    return kSuccess;
  }
  std::string start = config.initial.start;
  if (config.initial.start == "flexible") {
    start = "flexible, q̇(0) = [";
    for (std::size_t i = 0; i < config.initial.modal_velocity.size(); ++i)
      start += (i ? ", " : "") + fixed(config.initial.modal_velocity[i], 3);
    start += "] m/s";
  }
  std::cout << "First impact: " << given_text(config.beam.speed_rpm) << " rpm, "
            << surface_text(config) << ", " << modes_text(config) << ", "
            << start << "\n"
            << "  time             t       = " << fixed(r.t, 7) << " s\n"
            << "  hub angle        θ       = " << fixed(theta_deg, 4) << " deg\n"
            << "  tip position     Y_t     = " << fixed(r.y_tip, 6) << " m\n"
            << "  normal velocity  V_X(−0) = " << fixed(im.vx_before, 4) << " m/s\n"
            << "                   V_X(+0) = " << fixed(im.vx_after, 4) << " m/s\n"
            << "  change           ΔV_X    = " << fixed(im.vx_before - im.vx_after, 4) << " m/s\n"
            << "  restitution  −V_X(+0)/V_X(−0) = " << fixed(-im.vx_after / im.vx_before, 4) << "\n"
            << "  impulse          P       = " << fixed(im.impulse * 1e6, 4) << " µN s\n\n"
            << "Table 5-3 row:  rpm | V_X(−0) | V_X(+0) | ΔV_X | −V_X(+0)/V_X(−0)\n"
            << "                " << fixed(config.beam.speed_rpm, 0) << " | " << fixed(im.vx_before, 4) << " | "
            << fixed(im.vx_after, 4) << " | " << fixed(im.vx_before - im.vx_after, 4) << " | "
            << fixed(-im.vx_after / im.vx_before, 4) << "\n";
  return kSuccess;
}

}  // namespace

Command add_impact_command(CLI::App& app) {
  auto opts = std::make_shared<ImpactOptions>();
  CLI::App* sub = app.add_subcommand("impact", "The first impact of a pass: the Table 5-3 quantities");
  opts->case_options.add_to(*sub);
  sub->add_flag("--json", opts->json,
                "Print a JSON object (t_s, theta_deg, y_tip_m, vx_before_m_s, vx_after_m_s, delta_vx_m_s, restitution, …)");
  sub->add_flag("--quiet", opts->quiet, "No progress line on stderr (shown otherwise on a terminal for searches over a second)");
  return [opts] { return run_impact(*opts); };
}

}  // namespace rotbeam::cli
