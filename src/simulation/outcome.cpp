#include "rotbeam/outcome.hpp"

#include <array>

namespace rotbeam {

namespace {

// Exit codes 4–10 and 130 as documented in docs/cli.md (`chatter` shares `impacts`' code: both
// mean that impacts or phase changes accumulate without the pass advancing).
constexpr std::array<FailureInfo, 10> kFailures = {{
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

constexpr std::array<std::pair<EventKind, const char*>, 9> kEvents = {{
    {EventKind::impact, "impact"},
    {EventKind::lift_off, "lift_off"},
    {EventKind::contact_start, "contact_start"},
    {EventKind::contact_end, "contact_end"},
    {EventKind::slip_reversal, "slip_reversal"},
    {EventKind::tip_distance_rule, "tip_distance_rule"},
    {EventKind::warning, "warning"},
    {EventKind::failure, "failure"},
    {EventKind::end, "end"},
}};

}  // namespace

const FailureInfo& failure_info(FailureKind kind) {
  for (const FailureInfo& f : kFailures)
    if (f.kind == kind) return f;
  return kFailures[4];  // unreachable: every enumerator has a row (checked in tests)
}

const char* event_name(EventKind kind) {
  for (const auto& [k, name] : kEvents)
    if (k == kind) return name;
  return "?";
}

std::optional<FailureKind> failure_from_name(std::string_view name) {
  for (const FailureInfo& f : kFailures)
    if (name == f.name) return f.kind;
  return std::nullopt;
}

std::optional<EventKind> event_from_name(std::string_view name) {
  for (const auto& [k, n] : kEvents)
    if (name == n) return k;
  return std::nullopt;
}

}  // namespace rotbeam
