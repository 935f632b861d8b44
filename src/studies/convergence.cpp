#include "rotbeam/convergence.hpp"

#include "rotbeam/case.hpp"
#include "rotbeam/config.hpp"
#include "rotbeam/job_runner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rotbeam {

namespace {

std::string label_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

nlohmann::json metrics(const PassSummary& s) {
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"last_separation_deg", num(s.last_separation_deg)},
          {"impacts", s.impacts},
          {"contact_episodes", s.contact_episodes},
          {"contact_time_s", s.contact_time_s},
          {"normal_impulse_n_s", s.ledger[LedgerTerm::normal_impulse]},
          {"peak_normal_force_n", s.peak_normal_force_n},
          {"friction_work_j", s.ledger[LedgerTerm::friction_work]},
          {"energy_audit_residual", s.energy_audit_residual},
          {"steps", s.steps},
          {"rhs_evaluations", s.rhs_evaluations},
          {"wall_time_s", s.wall_time_s}};
}

double relative(double a, double ref) {
  if (ref == 0.0) return a == 0.0 ? 0.0 : INFINITY;
  return (a - ref) / std::abs(ref);
}

}  // namespace

ConvergenceStudy run_convergence(const Config& base, const ConvergenceLadder& ladder, int jobs, const StopToken* stop,
                                 const std::function<void(const JobProgress&)>& on_run_finished) {
  std::vector<Config> configs;
  ConvergenceStudy study;
  const double ref_rtol = *std::min_element(ladder.rtols.begin(), ladder.rtols.end());
  auto add = [&](Config c, ConvergenceRun r) {
    configs.push_back(std::move(c));
    study.runs.push_back(std::move(r));
  };
  {
    Config c = base;
    c.simulation.scheme = Scheme::adaptive;
    c.simulation.rtol = ref_rtol;
    ConvergenceRun r;
    r.label = "adaptive rtol=" + label_number(ref_rtol) + " (reference)";
    r.scheme = "adaptive";
    r.rtol = ref_rtol;
    r.modes = c.beam.modes;
    r.reference = true;
    add(c, r);
  }
  for (double rtol : ladder.rtols) {
    if (rtol == ref_rtol) continue;
    Config c = base;
    c.simulation.scheme = Scheme::adaptive;
    c.simulation.rtol = rtol;
    ConvergenceRun r;
    r.label = "adaptive rtol=" + label_number(rtol);
    r.scheme = "adaptive";
    r.rtol = rtol;
    r.modes = c.beam.modes;
    add(c, r);
  }
  for (double h : ladder.thesis_free_steps) {
    Config c = base;
    c.simulation.scheme = Scheme::thesis;
    c.simulation.free_step_s = h;
    c.simulation.contact_step_s = h / 10.0;
    c.simulation.fine_contact_step_s = std::max(h / 100.0, 1e-13);  // h = 1e-11 gives 9.999999999999999e-14
    ConvergenceRun r;
    r.label = "thesis h=" + label_number(h) + "/" + label_number(h / 10.0);
    r.scheme = "thesis";
    r.free_step_s = h;
    r.contact_step_s = h / 10.0;
    r.modes = c.beam.modes;
    add(c, r);
  }
  const double modes_rtol = std::min(1e-8, 100.0 * ref_rtol);
  for (int n : ladder.modes) {
    Config c = base;
    c.simulation.scheme = Scheme::adaptive;
    c.simulation.rtol = modes_rtol;
    c.beam.modes = n;
    // Per-mode damping has one value per mode of beam.modes: refused here, before any run, not
    // inside the ladder's run after the others finished (the whole study was lost).
    const std::size_t ratios = c.beam.damping_ratio.size();
    if (ratios > 1 && static_cast<int>(ratios) != n)
      throw ConfigError("--modes " + std::to_string(n) + ": beam.damping_ratio has " + std::to_string(ratios) +
                        " values, one per mode of beam.modes = " + std::to_string(base.beam.modes) +
                        "; give it one number to compare mode counts");
    c.initial.modal_velocity.resize(n, 0.0);
    c.initial.modal_displacement.resize(n, 0.0);
    ConvergenceRun r;
    r.label = "modes=" + std::to_string(n) + " (rtol=" + label_number(modes_rtol) + ")";
    r.scheme = "adaptive";
    r.rtol = modes_rtol;
    r.modes = n;
    add(c, r);
  }
  for (Config& c : configs) {  // only the summary is needed
    c.simulation.output_interval_s = 1e30;
    c.simulation.near_surface_gap_m = 0.0;
  }

  // Every run of the ladder is built before any runs: a configuration that cannot be is refused
  // at once, naming its run.
  for (std::size_t i = 0; i < configs.size(); ++i) try {
      build_case(configs[i]);
    } catch (const ConfigError& e) {
      throw ConfigError(study.runs[i].label + ": " + e.what());
    }

  JobRunnerOptions runner;
  runner.threads = jobs;
  runner.stop = stop;
  runner.on_job_finished = on_run_finished;
  run_jobs(
      configs.size(),
      [&](std::size_t i) {
        const PassResult result = run_case(build_case(configs[i]), {nullptr, stop, {}});
        study.runs[i].summary = result.summary;
        if (result.failure)
          study.runs[i].failure = std::string(failure_name(result.failure->kind)) + ": " + result.failure->message;
      },
      runner);
  return study;
}

nlohmann::json convergence_json(const ConvergenceStudy& study) {
  const PassSummary& ref = study.runs.front().summary;
  nlohmann::json runs = nlohmann::json::array();
  for (const ConvergenceRun& r : study.runs) {
    nlohmann::json j = {{"label", r.label}, {"scheme", r.scheme}, {"modes", r.modes}, {"reference", r.reference}};
    if (r.scheme == "adaptive") j["rtol"] = r.rtol;
    else j["free_step_s"] = r.free_step_s, j["contact_step_s"] = r.contact_step_s;
    j["metrics"] = metrics(r.summary);
    j["difference"] = {
        {"last_separation_deg", std::isfinite(r.summary.last_separation_deg - ref.last_separation_deg)
                                    ? nlohmann::json(r.summary.last_separation_deg - ref.last_separation_deg)
                                    : nlohmann::json(nullptr)},
        {"impacts", r.summary.impacts - ref.impacts},
        {"contact_episodes", r.summary.contact_episodes - ref.contact_episodes},
        {"contact_time_rel", relative(r.summary.contact_time_s, ref.contact_time_s)},
        {"normal_impulse_rel", relative(r.summary.ledger[LedgerTerm::normal_impulse], ref.ledger[LedgerTerm::normal_impulse])},
        {"peak_normal_force_rel", relative(r.summary.peak_normal_force_n, ref.peak_normal_force_n)},
        {"friction_work_rel", relative(r.summary.ledger[LedgerTerm::friction_work], ref.ledger[LedgerTerm::friction_work])}};
    j["failure"] = r.failure.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.failure);
    runs.push_back(j);
  }
  return {{"reference", study.runs.front().label}, {"runs", runs}};
}

}  // namespace rotbeam
