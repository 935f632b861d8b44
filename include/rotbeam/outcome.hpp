// Typed outcomes of a pass: the kinds of events and of numerical failures, each with the name it
// carries in events.csv / summary.json and, for failures, the command line's exit code — one table.
#pragma once

#include <array>
#include <optional>
#include <utility>
#include <string>
#include <string_view>

namespace rotbeam {

/// What happened at an instant of a pass (events.csv `kind`, docs/model.md §7).
enum class EventKind {
  impact,             // a momentum-balance jump (docs/model.md §5)
  lift_off,           // a touch or plastic impact after which the tip leaves at once
  contact_start,      // sustained contact begins
  contact_end,        // sustained contact ends (λ reached 0, or the tip stopped sliding and lifts off)
  slip_reversal,      // V_t = 0 in contact and friction now acts the other way
  tip_distance_rule,  // thesis Step 5a: free steps after a separation until the tip is clear
  warning,            // a warning (also listed in summary.json `warnings`)
  failure,            // the numerical failure that stopped the pass
  end,                // the end of the pass
  clear,              // simulation.end_when_clear: the tip cannot reach the surface again before the end angle
  stick_start,        // the tip sticks: V_t = 0 and the tangential force it needs lies inside the friction cone
  stick_end,          // the stick ends: the tangential force reached μ F_n and the tip slides
};

/// Why a pass stopped before its end angle (summary.json `failure.kind`).
enum class FailureKind {
  painleve,        // a λ + b|λ| = c has no or two admissible solutions (docs/model.md §4)
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

/// A numerical breakdown: what, where and the quantities involved. The partial result is kept.
struct NumericalFailure {
  FailureKind kind = FailureKind::non_finite;
  double t = 0, theta = 0;  // [s], [rad]
  std::string message;
};

namespace detail {

// Exit codes 4–10 and 130 as documented in docs/cli.md (`chatter` shares `impacts`' code: both
// mean that impacts or phase changes accumulate without the pass advancing).
inline constexpr std::array<FailureInfo, 10> kFailures = {{
    {FailureKind::painleve, "painleve", 4, "Painlevé's paradox: no or two admissible contact multipliers"},
    {FailureKind::stick, "stick", 5, "the tip sticks (V_t = 0 inside the friction cone)"},
    {FailureKind::corrector, "corrector", 6, "the thesis scheme's corrector did not converge"},
    {FailureKind::step_underflow, "step_underflow", 7, "the tolerance cannot be met in double precision"},
    {FailureKind::non_finite, "non_finite", 8, "the state became non-finite"},
    {FailureKind::validity, "validity", 9, "the tip deflection left the model's range of validity"},
    {FailureKind::impacts, "impacts", 10, "impacts accumulate"},
    {FailureKind::chatter, "chatter", 10, "phase changes without time advancing"},
    {FailureKind::initial_state, "initial_state", 2, "the initial shape already touches the surface"},
    {FailureKind::interrupted, "interrupted", 130, "stopped on request; results up to there kept"},
}};

inline constexpr std::array<std::pair<EventKind, const char*>, 12> kEvents = {{
    {EventKind::impact, "impact"},
    {EventKind::lift_off, "lift_off"},
    {EventKind::contact_start, "contact_start"},
    {EventKind::contact_end, "contact_end"},
    {EventKind::slip_reversal, "slip_reversal"},
    {EventKind::tip_distance_rule, "tip_distance_rule"},
    {EventKind::warning, "warning"},
    {EventKind::failure, "failure"},
    {EventKind::end, "end"},
    {EventKind::clear, "clear"},
    {EventKind::stick_start, "stick_start"},
    {EventKind::stick_end, "stick_end"},
}};

}  // namespace detail

/// The row of `kind` (every kind has one).
inline const FailureInfo& failure_info(FailureKind kind) {
  for (const FailureInfo& f : detail::kFailures)
    if (f.kind == kind) return f;
  return detail::kFailures[4];  // unreachable: every enumerator has a row (checked in tests)
}

/// The name of an event kind as written in events.csv.
inline const char* event_name(EventKind kind) {
  for (const auto& [k, name] : detail::kEvents)
    if (k == kind) return name;
  return "?";
}

/// The kind of a name, if it is one (for readers of the output files).
inline std::optional<FailureKind> failure_from_name(std::string_view name) {
  for (const FailureInfo& f : detail::kFailures)
    if (name == f.name) return f.kind;
  return std::nullopt;
}

inline std::optional<EventKind> event_from_name(std::string_view name) {
  for (const auto& [k, n] : detail::kEvents)
    if (name == n) return k;
  return std::nullopt;
}

/// The name of a failure kind as written in the output files.
inline const char* failure_name(FailureKind kind) { return failure_info(kind).name; }

}  // namespace rotbeam
