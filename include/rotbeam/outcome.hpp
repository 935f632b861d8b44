// Typed outcomes of a pass: the kinds of events and of numerical failures, each with the name it
// carries in events.csv / summary.json and, for failures, the command line's exit code — one table.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace rotbeam {

/// What happened at an instant of a pass (events.csv `kind`, SPEC §7).
enum class EventKind {
  impact,             // a momentum-balance jump (SPEC §5)
  lift_off,           // a touch or plastic impact after which the tip leaves at once
  contact_start,      // sustained contact begins
  contact_end,        // sustained contact ends (λ reached 0, or the tip stopped sliding and lifts off)
  slip_reversal,      // V_t = 0 in contact and friction now acts the other way
  tip_distance_rule,  // thesis Step 5a: free steps after a separation until the tip is clear
  warning,            // a warning (also listed in summary.json `warnings`)
  failure,            // the numerical failure that stopped the pass
  end,                // the end of the pass
};

/// Why a pass stopped before its end angle (summary.json `failure.kind`).
enum class FailureKind {
  painleve,        // a λ + b|λ| = c has no or two admissible solutions (SPEC §4)
  stick,           // V_t = 0 and the tangential force needed is inside the friction cone
  corrector,       // the thesis scheme's corrector did not converge
  step_underflow,  // the step-size control cannot meet the tolerance in double precision
  non_finite,      // the state became NaN or infinite
  validity,        // max |y_t|/L exceeded the warning ratio with deflection_limit_is_error
  impacts,         // more than simulation.max_impacts impacts
  chatter,         // phase changes without time advancing
  initial_state,   // the initial shape already touches the surface
  interrupted,     // a stop was requested (SIGINT/SIGTERM, or the caller's StopToken)
};

/// One row of the failure table: the name in the outputs, the command line's exit code
/// (docs/cli.md) and a short description.
struct FailureInfo {
  FailureKind kind;
  const char* name;
  int exit_code;
  const char* description;
};

/// The row of `kind` (every kind has one).
const FailureInfo& failure_info(FailureKind kind);
/// The name of an event or failure kind as written in the output files.
const char* event_name(EventKind kind);
inline const char* failure_name(FailureKind kind) { return failure_info(kind).name; }
/// The kind of a name, if it is one (for readers of the output files).
std::optional<FailureKind> failure_from_name(std::string_view name);
std::optional<EventKind> event_from_name(std::string_view name);

/// A numerical breakdown: what, where and the quantities involved. The partial result is kept.
struct NumericalFailure {
  FailureKind kind = FailureKind::non_finite;
  double t = 0, theta = 0;  // [s], [rad]
  std::string message;
};

}  // namespace rotbeam
