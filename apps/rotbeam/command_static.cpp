// `rotbeam static`: the static equilibrium of the filament in the hub frame under a tip load normal
// to the undeformed filament, for either beam theory, at rest or spinning (static_equilibrium.hpp).
#include "commands.hpp"
#include "common.hpp"

#include "rotbeam/beam_factory.hpp"
#include "rotbeam/static_equilibrium.hpp"

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

namespace rotbeam::cli {

namespace {

struct StaticOptions {
  CaseOptions case_options;
  double tip_load_n = NAN;
  bool json = false;
};

int run_static(const StaticOptions& o) {
  if (!std::isfinite(o.tip_load_n)) throw ConfigError("--tip-load-n " + number_text(o.tip_load_n) + ": must be a finite number of newtons");
  const Config config = o.case_options.load_filament("static");
  install_interrupt_handlers();
  const auto beam = make_beam_model(config.beam);
  StaticEquilibrium s;
  try {
    s = static_equilibrium(*beam, o.tip_load_n, &interrupt_token());
  } catch (const std::runtime_error& e) {
    if (interrupt_token().stop_requested()) {
      print_error("static equilibrium interrupted");
      return kInterrupted;
    }
    throw;
  }
  const double L = config.beam.length_m;
  const double load_parameter = o.tip_load_n * L * L / bending_stiffness(config.beam);
  const std::vector<std::string> warnings = static_warnings(*beam, s, o.tip_load_n, config.simulation.deflection_warning_ratio, load_parameter);
  if (o.json) {
    nlohmann::json j = {{"theory", beam_theory_name(config.beam.theory)},
                        {"modes", config.beam.modes},
                        {"speed_rpm", config.beam.speed_rpm},
                        {"centrifugal", config.beam.centrifugal},
                        {"tip_load_n", o.tip_load_n},
                        {"load_parameter", load_parameter},
                        {"tip_x_m", s.tip_x},
                        {"tip_y_m", s.tip_y},
                        {"tip_deflection_ratio", std::abs(s.tip_y) / L},
                        {"q", std::vector<double>(s.q.data(), s.q.data() + s.q.size())},
                        {"residual_n", s.residual},
                        {"iterations", s.iterations},
                        {"load_steps", s.load_steps},
                        {"load_scale_n", s.load_scale},
                        {"warnings", warnings}};
    std::cout << j.dump(2) << "\n";
    return kSuccess;
  }
  std::cout << "Static equilibrium: " << beam_theory_name(config.beam.theory) << ", " << config.beam.modes << " modes, "
            << given_text(config.beam.speed_rpm) << " rpm"
            << (config.beam.centrifugal ? "" : " (centrifugal terms off)") << ", in the hub frame\n"
            << "  tip load         P       = " << given_text(o.tip_load_n) << " N normal to the undeformed filament"
            << " (PL²/EI = " << number_text(load_parameter) << ")\n"
            << "  tip position     x_t     = " << fixed(s.tip_x, 9) << " m from the hub centre (undeformed "
            << fixed(beam->tip_radius(), 9) << " m)\n"
            << "                   y_t     = " << fixed(s.tip_y, 9) << " m\n"
            << "  deflection       |y_t|/L = " << fixed(std::abs(s.tip_y) / L, 6) << ", shortening "
            << fixed((beam->tip_radius() - s.tip_x) / L, 6) << " L\n"
            << "  q =";
  for (Eigen::Index i = 0; i < s.q.size(); ++i) std::cout << " " << number_text(s.q[i]);
  std::cout << " m\n  Newton: " << s.iterations << " iterations in " << s.load_steps << " load step"
            << (s.load_steps == 1 ? "" : "s") << ", residual " << number_text(s.residual) << " N\n";
  for (const std::string& w : warnings) std::cout << "  warning: " << w << "\n";
  return kSuccess;
}

}  // namespace

Command add_static_command(CLI::App& app) {
  auto opts = std::make_shared<StaticOptions>();
  CLI::App* sub = app.add_subcommand(
      "static", "Static equilibrium under a tip load normal to the undeformed filament (hub frame, either theory)");
  opts->case_options.add_to(*sub);
  sub->add_option("--tip-load-n", opts->tip_load_n, "Tip load P [N], a dead load along the hub frame's y")->required();
  sub->add_flag("--json", opts->json, "Print a JSON object (tip_x_m, tip_y_m, q, …)");
  return [opts] { return run_static(*opts); };
}

}  // namespace rotbeam::cli
