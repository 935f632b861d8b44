// Convergence made visible (docs/model.md §10): one case rerun over a ladder of adaptive tolerances, thesis
// step sizes and mode counts, each run compared with the tightest adaptive run.
#pragma once

#include "rotbeam/config.hpp"
#include "rotbeam/job_runner.hpp"
#include "rotbeam/pass.hpp"

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rotbeam {

struct ConvergenceLadder {
  std::vector<double> rtols{1e-6, 1e-8, 1e-10, 1e-12};     // adaptive; the smallest is the reference
  // Thesis-scheme free-flight steps (contact step = free step / 10): the thesis's own 1e-6 s, then
  // halvings inside the range where the scheme keeps the reference's sequence of impacts and episodes
  // and is first order (on the base case from 4e-7 s down; at 5e-7 s and above it loses an episode).
  std::vector<double> thesis_free_steps{1e-6, 4e-7, 2e-7, 1e-7};
  std::vector<int> modes{3, 5, 8, 12};                      // adaptive at the reference tolerance × 100
};

struct ConvergenceRun {
  std::string label;      // e.g. "adaptive rtol=1e-08", "thesis h=1e-06/1e-07", "modes=8"
  std::string scheme;
  double rtol = 0, free_step_s = 0, contact_step_s = 0;
  int modes = 0;
  bool reference = false;
  PassSummary summary;
  std::string failure;    // empty unless the run stopped on a diagnosed failure
};

struct ConvergenceStudy {
  std::vector<ConvergenceRun> runs;  // the reference first
};

/// Runs the ladder for `base` (its other settings kept) on `jobs` threads (0: all cores); `stop`
/// ends it early (the runs not finished carry an `interrupted` failure or none at all);
/// `on_run_finished` reports progress.
ConvergenceStudy run_convergence(const Config& base, const ConvergenceLadder& ladder, int jobs,
                                 const StopToken* stop = nullptr,
                                 const std::function<void(const JobProgress&)>& on_run_finished = {});

/// The study as JSON: {"reference": label, "runs": [{label, scheme, rtol, …, metrics…, "difference": {…}}]}.
nlohmann::json convergence_json(const ConvergenceStudy& study);

}  // namespace rotbeam
