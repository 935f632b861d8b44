// The ledger of a pass (docs/model.md, "Energy ledger"): every quantity the filament and the surface
// exchange that the outputs report, accumulated over the steps of a pass (from the rates the contact
// law and the beam give) and over its impacts (their jumps). The energy terms are signed as energy
// given to the filament and close the balance
//   hub + friction + surface + damping + impact loss + contact dissipation = ΔE,
// E = T + U plus the energy a compliant contact stores. The momenta (impulses) are the surface's
// share of the same exchange.
//
// A term is registered once, in kLedgerTerms: summary.json, revolutions.csv, the brush's ledger,
// the Python module's attributes and the pictures all iterate this table.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

namespace rotbeam {

/// The terms of the ledger, in the order of kLedgerTerms.
enum class LedgerTerm : int {
  hub_work,             // ω ∫τ dt with the impulsive part: from the hub's angular-momentum balance [J]
  friction_work,        // ∫ F_t V_t dt ≤ 0, V_t the slip relative to the surface [J]
  surface_work,         // ∫ F_t (V_s·t) dt + Σ P⃗·V_s: a moving surface's work through friction [J]
  damping_work,         // −∫ q̇ᵀC q̇ dt ≤ 0, the beam's own damping [J]
  impact_loss,          // the impacts' impulses' work on the tip less a moving surface's part (≤ 0) [J]
  contact_dissipation,  // −∫ (F_n − kδ^{3/2}) δ̇ dt ≤ 0, a compliant contact's damping [J]
  normal_impulse,       // ∫ F_n dt + Σ|P|, the momentum into the surface [N s]
  tangential_impulse,   // ∫ F_t dt + Σ P_t, friction's momentum on the tip along the tangent [N s]
  contact_moment,       // ∫ (X F_Y − Y F_X) dt + Σ (X P_Y − Y P_X), the contact's angular impulse about the hub [N m s]
  contact_work,         // ∫ q̇ᵀQ dt, the contact force's power in the rotating frame (the Jacobi-integral audit) [J]
  frictional_heat,      // ∫ |F_t||V_t| dt + Σ(−∫V_t dP_t), the heat friction makes at the contact (≥ 0) [J]
  sliding_load,         // ∫ F_n |V_t| dt + Σ ∫|V_t| dp, Archard's load times sliding distance [N m]
  count                 // (the number of terms)
};

inline constexpr std::size_t kLedgerTermCount = static_cast<std::size_t>(LedgerTerm::count);

/// How a term is reported.
enum class LedgerReport {
  energy,    // a term of the energy balance, in summary.json, revolutions.csv and the brush's ledger
  momentum,  // an exchange of momentum, reported beside the balance
  beside,    // where energy goes or what wears, reported beside the balance (heat, Archard's load–distance)
  internal,  // kept for the hub's work and the audit, not written
};

struct LedgerTermInfo {
  LedgerTerm term;
  const char* key;          // the name in summary.json, revolutions.csv and the Python attributes
  const char* unit;         // "J", "N s", …
  const char* label;        // a short name for pictures and tables
  LedgerReport report;
  bool integrated;          // the steps integrate it from a rate (the hub's work and the impacts' loss have none)
  const char* description;  // one line, with the unit
};

inline constexpr std::array<LedgerTermInfo, kLedgerTermCount> kLedgerTerms = {{
    {LedgerTerm::hub_work, "hub_work_j", "J", "hub", LedgerReport::energy, false,
     "the hub's work on the filament, ω∫τ dt with the impulsive part [J]"},
    {LedgerTerm::friction_work, "friction_work_j", "J", "friction", LedgerReport::energy, true,
     "friction's work on the tip, ∫F_t V_t dt with V_t the slip relative to the surface (≤ 0) [J]"},
    {LedgerTerm::surface_work, "surface_work_j", "J", "surface", LedgerReport::energy, true,
     "a moving surface's work on the tip through friction, in contact and at impacts (0 at rest) [J]"},
    {LedgerTerm::damping_work, "damping_work_j", "J", "damping", LedgerReport::energy, true,
     "the beam's own damping, −∫q̇ᵀCq̇ dt (≤ 0) [J]"},
    {LedgerTerm::impact_loss, "impact_loss_j", "J", "impacts", LedgerReport::energy, false,
     "the energy the impacts dissipate, their impulses' work less a moving surface's part (≤ 0) [J]"},
    {LedgerTerm::contact_dissipation, "contact_dissipation_j", "J", "contact damping", LedgerReport::energy, true,
     "a compliant contact's damping, −∫(F_n − kδ^{3/2})δ̇ dt (≤ 0; 0 under the rigid law) [J]"},
    {LedgerTerm::normal_impulse, "normal_impulse_n_s", "N s", "normal impulse", LedgerReport::momentum, true,
     "the momentum into the surface, ∫F_n dt plus the impacts' impulses [N s]"},
    {LedgerTerm::tangential_impulse, "tangential_impulse_n_s", "N s", "tangential impulse", LedgerReport::momentum, true,
     "friction's momentum on the tip along the surface's tangent, ∫F_t dt plus the impacts' [N s]"},
    {LedgerTerm::contact_moment, "contact_moment_n_m_s", "N m s", "contact moment", LedgerReport::internal, true,
     "the contact's angular impulse about the hub axis [N m s]"},
    {LedgerTerm::contact_work, "contact_work_j", "J", "contact work", LedgerReport::internal, true,
     "the contact force's work in the rotating frame, ∫q̇ᵀQ dt [J]"},
    {LedgerTerm::frictional_heat, "frictional_heat_j", "J", "frictional heat", LedgerReport::beside, true,
     "the heat friction makes at the contact, ∫|F_t||V_t| dt plus the impacts' −∫V_t dP_t (≥ 0; where friction's dissipation goes) [J]"},
    {LedgerTerm::sliding_load, "sliding_load_n_m", "N m", "load × slip", LedgerReport::beside, true,
     "Archard's load–distance integral, ∫F_n|V_t| dt plus the impacts' ∫|V_t| dp; a worn volume is k/H times it [N m]"},
}};

// Every term has its row, in the enumerators' order.
constexpr bool ledger_table_in_order() {
  for (std::size_t k = 0; k < kLedgerTermCount; ++k)
    if (static_cast<std::size_t>(kLedgerTerms[k].term) != k) return false;
  return true;
}
static_assert(ledger_table_in_order(), "kLedgerTerms: one row per LedgerTerm, in the enumerators' order");

/// The terms the steps integrate, in the table's order, and how many.
inline constexpr std::size_t kIntegratedTermCount = [] {
  std::size_t n = 0;
  for (const LedgerTermInfo& info : kLedgerTerms) n += info.integrated;
  return n;
}();
inline constexpr std::array<LedgerTerm, kIntegratedTermCount> kIntegratedTerms = [] {
  std::array<LedgerTerm, kIntegratedTermCount> out{};
  std::size_t n = 0;
  for (const LedgerTermInfo& info : kLedgerTerms)
    if (info.integrated) out[n++] = info.term;
  return out;
}();

/// The row of `term` in kLedgerTerms.
inline constexpr const LedgerTermInfo& ledger_term_info(LedgerTerm term) {
  return kLedgerTerms[static_cast<std::size_t>(term)];
}

/// A value for every term: the totals of a pass or a revolution, the rates of a contact load (per
/// second), the integrals of a step, or the jumps of an impact.
struct LedgerValues {
  std::array<double, kLedgerTermCount> value{};

  double& operator[](LedgerTerm t) { return value[static_cast<std::size_t>(t)]; }
  double operator[](LedgerTerm t) const { return value[static_cast<std::size_t>(t)]; }
  LedgerValues& operator+=(const LedgerValues& o) {
    for (std::size_t k = 0; k < kLedgerTermCount; ++k) value[k] += o.value[k];
    return *this;
  }
  LedgerValues& operator-=(const LedgerValues& o) {
    for (std::size_t k = 0; k < kLedgerTermCount; ++k) value[k] -= o.value[k];
    return *this;
  }
  friend LedgerValues operator-(LedgerValues a, const LedgerValues& b) { return a -= b; }
  friend LedgerValues operator+(LedgerValues a, const LedgerValues& b) { return a += b; }
  LedgerValues& operator*=(double s) {
    for (double& v : value) v *= s;
    return *this;
  }
};

/// The ledger of a pass or of one revolution: its terms and the change of the filament's energy.
struct Ledger : LedgerValues {
  double energy_change_j = 0;  // E = T + U (+ a compliant contact's stored energy) at the end less at the start [J]

  /// The sum of the energy terms [J].
  double energy_terms() const {
    double sum = 0;
    for (const LedgerTermInfo& info : kLedgerTerms)
      if (info.report == LedgerReport::energy) sum += (*this)[info.term];
    return sum;
  }
  /// The balance's residual, Σ energy terms − ΔE [J] (0 for an exact ledger).
  double residual() const { return energy_terms() - energy_change_j; }
};

/// The term whose key is `key`, if one is.
inline const LedgerTermInfo* find_ledger_term(std::string_view key) {
  for (const LedgerTermInfo& info : kLedgerTerms)
    if (key == info.key) return &info;
  return nullptr;
}

}  // namespace rotbeam
