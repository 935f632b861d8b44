// `rotbeam converge`: a case over a ladder of tolerances, thesis steps and mode counts (docs/model.md §10).
#include "commands.hpp"
#include "common.hpp"

#include "rotbeam/beam_factory.hpp"
#include "rotbeam/convergence.hpp"
#include "rotbeam/detail/parse.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>
#include <unistd.h>

namespace rotbeam::cli {

namespace {

struct ConvergeOptions {
  CaseOptions case_options;
  std::string rtols, steps, modes;
  int jobs = 0;
  bool json = false;
  bool quiet = false;
};

template <class T>
std::vector<T> parse_list(const std::string& text, const std::string& option, int max_modes = kMaxModes) {
  std::vector<T> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    double v = 0;
    if (!detail::parse_finite_number(item, v) || !(v > 0))
      throw ConfigError(option + " " + text + ": '" + item + "' is not a positive number");
    if constexpr (std::is_integral_v<T>) {
      if (v != std::floor(v) || v > max_modes)
        throw ConfigError(option + " " + text + ": '" + item + "' must be a whole number of modes up to " + std::to_string(max_modes));
    }
    // A rung given twice (1e-8,1e-8 or 1e-8,1.0e-8) is the same run twice, one row compared with itself.
    if (std::find(out.begin(), out.end(), static_cast<T>(v)) != out.end())
      throw ConfigError(option + " " + text + ": '" + item + "' is given twice (give each value once)");
    out.push_back(static_cast<T>(v));
  }
  if (out.empty()) throw ConfigError(option + ": give a comma-separated list");
  return out;
}

// A ladder value must be one the configuration accepts for the key it sets (one definition of the ranges).
void check_as_key(const std::string& option, const std::string& text, const std::string& key, double value) {
  char literal[64];
  std::snprintf(literal, sizeof literal, "%.17g", value);
  try {
    load_config_values(std::nullopt, {{key, literal}});
  } catch (const ConfigError& e) {
    throw ConfigError(option + " " + text + ": " + e.what());
  }
}

std::string cell(double v, int width, const char* format) {
  char buf[64];
  if (!std::isfinite(v)) std::snprintf(buf, sizeof buf, "%*s", width, "–");
  else std::snprintf(buf, sizeof buf, format, width, v);
  return buf;
}

int run_converge(const ConvergeOptions& o) {
  const Config config = o.case_options.load_filament("converge");
  ConvergenceLadder ladder;
  if (!o.rtols.empty()) ladder.rtols = parse_list<double>(o.rtols, "--rtols");
  // The thesis's scheme has no compliant contact: under hertz its ladder is left out, and refused when asked for.
  const bool compliant = config.contact.model != ContactModel::rigid;
  if (o.steps == "none" || (compliant && o.steps.empty())) ladder.thesis_free_steps.clear();
  else if (!o.steps.empty()) ladder.thesis_free_steps = parse_list<double>(o.steps, "--steps");
  if (compliant && !ladder.thesis_free_steps.empty())
    throw ConfigError("--steps " + o.steps + ": the thesis scheme's ladder, which has no compliant contact (contact.model = \"" +
                      contact_model_name(config.contact.model) + "\"): leave --steps out or give --steps none");
  if (!o.modes.empty()) ladder.modes = parse_list<int>(o.modes, "--modes", max_modes(config.beam.theory));
  for (double r : ladder.rtols) check_as_key("--rtols", o.rtols, "simulation.rtol", r);
  for (double h : ladder.thesis_free_steps) {  // contact step h/10, fine step h/100
    check_as_key("--steps", o.steps, "simulation.free_step_s", h);
    check_as_key("--steps", o.steps, "simulation.contact_step_s", h / 10);
    check_as_key("--steps", o.steps, "simulation.fine_contact_step_s", std::max(h / 100, 1e-13));
  }
  if (o.jobs < 0) throw ConfigError("--jobs " + std::to_string(o.jobs) + ": must be >= 0");
  // The ladder varies rtol only: well below atol/10 the error control is set by simulation.atol
  // (measured on the base case at atol = 1e-12: rtol 1e-14, 1e-16 and 1e-300 take the same steps),
  // so the reference is no tighter than its label says.
  const double tightest = *std::min_element(ladder.rtols.begin(), ladder.rtols.end());
  if (tightest < 0.1 * config.simulation.atol && !o.quiet)
    std::cerr << "rotbeam: note: --rtols " << number_text(tightest) << ": below about " << number_text(0.1 * config.simulation.atol)
              << " the steps are set by simulation.atol = " << number_text(config.simulation.atol)
              << ", not by rtol; for a tighter reference lower simulation.atol too" << std::endl;
  install_interrupt_handlers();
  ConvergenceStudy study;
  {
    LiveLine line(!o.quiet && isatty(STDERR_FILENO));
    line.set([](double e) { return "  runs under way, " + duration_text(e) + " elapsed"; });
    study = run_convergence(config, ladder, o.jobs, &interrupt_token(), [&line](const JobProgress& p) {
      // The ETA counts down from the last estimate between finished runs.
      line.set([p](double e) {
        return "  " + std::to_string(p.finished) + "/" + std::to_string(p.total) + " runs, " + duration_text(e) +
               " elapsed, ETA " + duration_text(std::max(0.0, p.eta_s - (e - p.elapsed_s)));
      });
    });
  }
  if (interrupt_token().stop_requested()) {
    print_error("convergence study interrupted");
    return kInterrupted;
  }
  if (o.json) {
    std::cout << convergence_json(study).dump(2) << "\n";
    return kSuccess;
  }
  const PassSummary& ref = study.runs.front().summary;
  std::cout << "Convergence of " << given_text(config.beam.speed_rpm) << " rpm, "
            << surface_text(config) << ", μ = " << given_text(config.contact.friction.mu) << ", "
            << modes_text(config) << "; differences (Δ) from " << study.runs.front().label << "\n\n";
  std::printf("%-32s %9s %9s %5s %5s %10s %11s %9s %11s %10s %10s %9s %8s\n", "run", "sep_deg", "Δsep_deg", "imp",
              "epis", "t_cont_ms", "impulse_mNs", "Δimp_rel", "peak_Fn_N", "Δpeak_rel", "W_f_mJ", "Δcont_rel",
              "wall_s");
  for (const ConvergenceRun& r : study.runs) {
    const PassSummary& s = r.summary;
    const double dsep = s.last_separation_deg - ref.last_separation_deg;
    auto rel = [](double a, double b) { return b == 0 ? (a == 0 ? 0.0 : NAN) : (a - b) / std::abs(b); };
    std::printf("%-32s %s %s %5d %5d %s %s %s %s %s %s %s %s%s\n", r.label.c_str(),
                cell(s.last_separation_deg, 9, "%*.4f").c_str(), cell(dsep, 9, "%*.1e").c_str(), s.impacts,
                s.contact_episodes, cell(s.contact_time_s * 1e3, 10, "%*.5f").c_str(),
                cell(s.ledger[LedgerTerm::normal_impulse] * 1e3, 11, "%*.6f").c_str(),
                cell(rel(s.ledger[LedgerTerm::normal_impulse], ref.ledger[LedgerTerm::normal_impulse]), 9, "%*.1e").c_str(),
                cell(s.peak_normal_force_n, 11, "%*.5f").c_str(),
                cell(rel(s.peak_normal_force_n, ref.peak_normal_force_n), 10, "%*.1e").c_str(),
                cell(s.ledger[LedgerTerm::friction_work] * 1e3, 10, "%*.5f").c_str(),
                cell(rel(s.contact_time_s, ref.contact_time_s), 9, "%*.1e").c_str(),
                cell(s.wall_time_s, 8, "%*.3f").c_str(), r.failure.empty() ? "" : ("  stopped: " + r.failure).c_str());
  }
  return kSuccess;
}

}  // namespace

Command add_converge_command(CLI::App& app) {
  auto opts = std::make_shared<ConvergeOptions>();
  CLI::App* sub = app.add_subcommand(
      "converge", "Rerun a case over tolerances, thesis step sizes and mode counts; compare with the tightest run");
  opts->case_options.add_to(*sub);
  sub->add_option("--rtols", opts->rtols, "Adaptive tolerances, comma-separated (default 1e-6,1e-8,1e-10,1e-12; the smallest is the reference)")
      ->check(non_empty_list("1e-6,1e-8"));
  sub->add_option("--steps", opts->steps, "Thesis free-flight steps [s] (contact step = step/10; default 1e-6,4e-7,2e-7,1e-7: the thesis's step, then halvings where the scheme is first order; none: no thesis runs, the default under contact.model = \"hertz\")")
      ->check(non_empty_list("1e-6,5e-7"));
  sub->add_option("--modes", opts->modes, "Mode counts (default 3,5,8,12)")
      ->check(non_empty_list("3,5,8"));
  sub->add_option("--jobs", opts->jobs, "Threads (default: all cores)");
  sub->add_flag("--json", opts->json, "Print the study as JSON");
  sub->add_flag("--quiet", opts->quiet, "No progress line on stderr (shown otherwise on a terminal)");
  return [opts] { return run_converge(*opts); };
}

}  // namespace rotbeam::cli
