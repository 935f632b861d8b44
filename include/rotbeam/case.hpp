// A case ready to run (the simulation layer's entry point): the beam model, the surface, the
// contact law, the initial conditions and the pass options built from a configuration, then run
// as a whole pass or to its first impact.
#pragma once

#include "rotbeam/config.hpp"
#include "rotbeam/first_impact.hpp"
#include "rotbeam/pass.hpp"

#include <memory>

namespace rotbeam {

struct Case {
  std::shared_ptr<const BeamModel> beam;
  std::shared_ptr<const Surface> surface;
  std::shared_ptr<const ContactLaw> law;
  InitialConditions initial;
  PassOptions options;
  /// The mechanical system (references into this case: keep the case alive while it is used).
  System system() const { return {*beam, *surface, *law}; }
};

/// Builds the case a (validated) configuration describes. Throws ConfigError naming the key when
/// a value is outside what the model can build, and for a brush's configuration (brush.hpp runs it).
Case build_case(const Config& config);

/// Runs the case's pass (PassControl: where rows and events go, and the stop token); with
/// simulation.until_steady, to its periodic steady state (run_to_steady_state, steady_state.hpp).
PassResult run_case(const Case& c, const PassControl& control = {});

/// What a run of the case will record before it runs: the history rows its sampling interval
/// gives over the recorded span (one pass: from the flexible start to the end angle; many
/// revolutions: the last output.history_revolutions of them), their size in history.csv and in
/// memory (PassResult plus the Python arrays). An upper bound where the run may stop earlier
/// (simulation.until_steady); unknown (known = false) with output.interval_s = 0, every step.
struct HistoryEstimate {
  bool known = false;
  bool upper_bound = false;  // the run may end earlier
  double rows = 0, csv_bytes = 0, memory_bytes = 0;
  // At least this many: a row is taken at the first step an interval after the last, and no step
  // is longer than the scheme's largest, so rows ≥ span / (interval + largest step).
  double min_rows = 0, min_csv_bytes = 0, min_memory_bytes = 0;
  // The key whose interval gives most of the rows: output.interval_s, or
  // output.near_surface_interval_s when the rows near the surface are the most.
  std::string sampling_key = "output.interval_s";
};
HistoryEstimate estimate_history(const Case& c);

/// Throws ConfigError naming output.interval_s when the history a run of c is announced to record
/// (the central estimate, csv_bytes or memory_bytes; not when it is only an upper bound) would not fit
/// in `available_bytes` (of disk for history.csv when `in_memory` is false, of memory otherwise);
/// 0 available means unknown (no check). Returns the estimate.
HistoryEstimate check_history_fits(const Case& c, double available_bytes, bool in_memory);

/// The steps a run of the case will take, estimated before it runs, and the step key that sets
/// most of them. The adaptive scheme's steps are at most simulation.max_step_s: it takes at least
/// the integrated time over that (at_least). The thesis scheme's steps are fixed: free_step_s in
/// flight; contact_step_s in contact (fine_contact_step_s instead while |λ| < fine_below_n, when it
/// is the shorter), counted over the stretch where the undeformed tip lies beyond the surface, once
/// per pass or revolution, which a bounce shortens: an estimate from above of the contact.
struct StepEstimate {
  double steps = 0;
  bool at_least = false;
  std::string key;             // "simulation.max_step_s", "simulation.free_step_s", …
  double step_s = 0;           // that key's value
  double governed_s = 0;       // the simulated time taken in steps of step_s
  std::string governed;        // what that time is: "motion", "flight" or "contact"
  // The wall time of those steps [s]: steps × the evaluations of q̈ a step takes (7 adaptive, 6
  // thesis) × one evaluation's time, measured on this machine at the start state (a few ms).
  double evaluation_s = 0;
  double wall_s = 0;
};
StepEstimate estimate_steps(const Case& c);

/// "4.2 GB", "310 MB", "12 kB": a size for messages.
std::string size_text(double bytes);

/// Runs the case to its first impact (the thesis's RK5 with simulation.free_step_s; control: the
/// stop token and progress, as for a pass). Throws ConfigError naming contact.model for a compliant
/// law, which has no impact.
FirstImpactResult run_first_impact(const Case& c, const PassControl& control = {});

}  // namespace rotbeam
