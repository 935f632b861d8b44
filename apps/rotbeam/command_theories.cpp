// `rotbeam theories`: one case under both beam theories side by side (the thesis's quadratic
// foreshortening and the elastica), so that a user sees what the thesis model costs at their
// deflection (docs/model.md "The elastica").
#include "commands.hpp"
#include "common.hpp"

#include "rotbeam/case.hpp"
#include "rotbeam/job_runner.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

namespace rotbeam::cli {

namespace {

struct TheoriesOptions {
  CaseOptions case_options;
  bool json = false;
};

constexpr std::array<BeamTheory, 2> kTheories = {BeamTheory::foreshortening, BeamTheory::elastica};

struct Outcome {
  PassSummary summary;
  std::string failure;  // empty: the pass ran to its end; else what stopped it, where and why
};

nlohmann::json outcome_json(const Outcome& r) {
  const PassSummary& s = r.summary;
  return {{"last_separation_deg", s.last_separation_deg}, {"normal_impulse_n_s", s.ledger[LedgerTerm::normal_impulse]},
          {"peak_normal_force_n", s.peak_normal_force_n},  {"contact_time_s", s.contact_time_s},
          {"max_tip_deflection_ratio", s.max_tip_deflection_ratio},
          {"validity", validity_name(s.validity)},
          {"impacts", s.impacts},                         {"contact_episodes", s.contact_episodes},
          {"wall_time_s", s.wall_time_s},                 {"failure", r.failure.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.failure)}};
}

std::string cell(double v, const char* format) {
  char buf[64];
  if (!std::isfinite(v)) std::snprintf(buf, sizeof buf, "%12s", "–");
  else std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

int run_theories(const TheoriesOptions& o) {
  const Config config = o.case_options.load_filament("theories");
  // Each theory's configuration is validated as a file would be (the foreshortening model takes
  // fewer modes than the elastica: the refusal names beam.modes).
  std::array<Config, 2> configs;
  for (std::size_t k = 0; k < kTheories.size(); ++k) {
    Config c = config;
    c.beam.theory = kTheories[k];
    // The deflection limit is the thesis model's: it does not apply to the elastica's run.
    if (kTheories[k] == BeamTheory::elastica) c.simulation.deflection_limit_is_error = false;
    try {
      configs[k] = revalidate(c);
    } catch (const ConfigError& e) {
      throw ConfigError(std::string(e.what()) + " (rotbeam theories runs the case under beam.theory = \"" +
                        beam_theory_name(kTheories[k]) + "\" too)");
    }
  }
  install_interrupt_handlers();
  std::array<Outcome, 2> out;
  run_jobs(
      kTheories.size(),
      [&](std::size_t k) {
        const Case c = build_case(configs[k]);
        const PassResult r = run_case(c, {nullptr, &interrupt_token(), {}});
        out[k].summary = r.summary;
        if (r.failure)
          out[k].failure = std::string(failure_name(r.failure->kind)) + " at t = " + number_text(r.failure->t) +
                           " s, θ = " + fixed(r.failure->theta * 180.0 / M_PI, 4) + " deg: " + r.failure->message;
      },
      {2, {}, &interrupt_token(), {}});
  if (interrupt_token().stop_requested()) {
    print_error("interrupted");
    return kInterrupted;
  }
  const PassSummary& a = out[0].summary;
  const PassSummary& b = out[1].summary;
  auto rel = [](double x, double y) { return y == 0 ? NAN : (x - y) / std::abs(y); };
  // A pass that stopped covers only part of the case: its sums set against the other's whole pass
  // are no difference of the theories (it printed +1038 %). Not computed then, and said on stderr.
  std::string stopped;
  for (std::size_t k = 0; k < kTheories.size(); ++k)
    if (!out[k].failure.empty())
      stopped += (stopped.empty() ? "" : "; ") + std::string("the ") + beam_theory_name(kTheories[k]) +
                 " pass stopped (" + out[k].failure + ")";
  const bool comparable = stopped.empty();
  const auto report = [&]() {
    if (comparable) return kSuccess;
    print_error("theories: " + stopped + "; no difference computed: a stopped pass is not comparable");
    return kRuntimeFailure;
  };
  if (o.json) {
    nlohmann::json j;
    for (std::size_t k = 0; k < kTheories.size(); ++k) j[beam_theory_name(kTheories[k])] = outcome_json(out[k]);
    if (comparable)
      j["difference"] = {{"last_separation_deg", b.last_separation_deg - a.last_separation_deg},
                         {"normal_impulse_relative", rel(b.ledger[LedgerTerm::normal_impulse], a.ledger[LedgerTerm::normal_impulse])},
                         {"peak_normal_force_relative", rel(b.peak_normal_force_n, a.peak_normal_force_n)},
                         {"contact_time_relative", rel(b.contact_time_s, a.contact_time_s)},
                         {"max_tip_deflection_ratio", b.max_tip_deflection_ratio - a.max_tip_deflection_ratio}};
    else
      j["difference"] = nullptr;
    std::cout << j.dump(2) << "\n";
    return report();
  }
  std::cout << "Both beam theories: " << given_text(config.beam.speed_rpm) << " rpm, " << surface_text(config)
            << ", μ = " << given_text(config.contact.friction.mu) << ", " << config.beam.modes << " modes\n\n";
  std::printf("%-16s %12s %12s %12s %12s %12s %8s %8s %8s\n", "theory", "sep_deg", "impulse_mNs", "peak_Fn_N",
              "t_cont_ms", "max|y_t|/L", "impacts", "episodes", "wall_s");
  for (std::size_t k = 0; k < kTheories.size(); ++k) {
    const PassSummary& s = out[k].summary;
    std::printf("%-16s %s %s %s %s %s %8d %8d %8.3f%s\n", beam_theory_name(kTheories[k]),
                cell(s.last_separation_deg, "%12.4f").c_str(), cell(s.ledger[LedgerTerm::normal_impulse] * 1e3, "%12.6f").c_str(),
                cell(s.peak_normal_force_n, "%12.5f").c_str(), cell(s.contact_time_s * 1e3, "%12.5f").c_str(),
                cell(s.max_tip_deflection_ratio, "%12.5f").c_str(), s.impacts, s.contact_episodes, s.wall_time_s,
                out[k].failure.empty() ? "" : ("  stopped: " + out[k].failure).c_str());
  }
  // Where the foreshortening pass left its validity, a line says so: the elastica is the reference.
  const auto say_validity = [&]() {
    const PassSummary& fore = out[0].summary;
    if (fore.validity == Validity::within) return;
    std::printf("validity         foreshortening %s (max |y_t|/L = %.3g > %g: %s; docs/model.md §10); the "
                "elastica's geometry is exact at any deflection\n",
                validity_name(fore.validity), fore.max_tip_deflection_ratio, config.simulation.deflection_warning_ratio,
                fore.validity == Validity::outside ? "outside the model, not physical"
                                                   : "the quadratic foreshortening at the edge of its validity");
  };
  if (!comparable) {
    std::printf("%-16s not comparable: a pass stopped before its end\n", "elastica − fore");
    say_validity();
    std::fflush(stdout);
    return report();
  }
  std::printf("%-16s %s %s %s %s %s\n", "elastica − fore", cell(b.last_separation_deg - a.last_separation_deg, "%+12.4f").c_str(),
              cell(100 * rel(b.ledger[LedgerTerm::normal_impulse], a.ledger[LedgerTerm::normal_impulse]), "%+11.2f%%").c_str(),
              cell(100 * rel(b.peak_normal_force_n, a.peak_normal_force_n), "%+11.2f%%").c_str(),
              cell(100 * rel(b.contact_time_s, a.contact_time_s), "%+11.2f%%").c_str(),
              cell(b.max_tip_deflection_ratio - a.max_tip_deflection_ratio, "%+12.5f").c_str());
  say_validity();
  return report();
}

}  // namespace

Command add_theories_command(CLI::App& app) {
  auto opts = std::make_shared<TheoriesOptions>();
  CLI::App* sub = app.add_subcommand(
      "theories", "Run a case under both beam theories (foreshortening, elastica) and compare them side by side");
  opts->case_options.add_to(*sub);
  sub->add_flag("--json", opts->json, "Print both summaries and their differences as JSON");
  return [opts] { return run_theories(*opts); };
}

}  // namespace rotbeam::cli
