// The steppers' contract (docs/model.md §6): one interface under the pass driver, modelled on SUNDIALS'
// CVODE — a step call that returns a status, root functions with directions, statistics. The
// driver (pass_driver.hpp) owns the phase logic and the contact law (contact_law.hpp) its
// transitions; a stepper only advances the state of its phase and reports what it crossed.
//
// Root functions, each oriented so that its event is a crossing from below zero to zero or above:
//   free flight   C(t, q)   (a touch: the gap closes)
//   contact       the contact law's roots of the phase (ContactLaw::roots), e.g. the rigid law's
//                 λ (separation) and −s_t V_t (the slip stops), the compliant law's −C (the gap opens)
#pragma once

#include "rotbeam/contact_law.hpp"
#include "rotbeam/ledger.hpp"
#include "rotbeam/outcome.hpp"
#include "rotbeam/pass_options.hpp"
#include "rotbeam/state.hpp"

#include <limits>
#include <memory>
#include <optional>
#include <string>

namespace rotbeam {

/// Integrals over a step: the ledger's terms (ledger.hpp; the contact's are zero in free flight, the
/// beam's damping work is there in every phase) and the largest normal force inside the step.
struct StepIntegrals {
  LedgerValues integral;
  double peak_normal_force = 0;  // the largest F_n over the step, its interior included [N]
  // The largest tip deflection |y_t| [m] inside the step where it lies between its ends (found on the
  // dense output), NaN where it does not or the scheme keeps no dense output: the validity's maximum.
  double peak_tip_deflection = std::numeric_limits<double>::quiet_NaN();
};

enum class Root {
  none,
  gap_closes,  // free flight: C = 0 (a touch)
  contact,     // a root of the contact law's phase: StepOutcome::contact_root says which
};

enum class StepStatus {
  advanced,  // an ordinary step: the state is at its end
  root,      // a root function crossed in its direction: the state is at the root
  failed,    // a numerical failure: the state is the last good one, `failure` says what and where
};

/// An event a scheme attaches to a step (the thesis's Step 5a tip-distance rule), with the
/// warning it implies (empty for none).
struct StepNote {
  EventKind kind = EventKind::tip_distance_rule;
  std::string detail;
  std::string warning;
};

struct StepOutcome {
  StepStatus status = StepStatus::advanced;
  Root root = Root::none;
  int contact_root = -1;                     // root == contact: its index in ContactLaw::roots(phase)
  ContactLoad load;                          // contact load at the step's end (contact steps)
  StepIntegrals integrals;                   // over the step (contact steps)
  std::optional<NumericalFailure> failure;   // status == failed
  std::optional<StepNote> note;
};

struct StepperStatistics {
  long steps = 0;
  long rhs_evaluations = 0;
  long tangent_evaluations = 0;  // evaluations of q̈ for the variational equations (PassOptions::tangent)
  long corrector_iterations = 0;
  int corrector_iterations_max = 0;
};

/// What a stepper does itself, and so what the driver does for it.
struct StepperTraits {
  Scheme scheme;
  // True: the stepper locates every root of the contact law's phase. False: only the contact's end;
  // the law's before_step runs before every contact step (the thesis's Appendix B checks the slip
  // direction from V_t there).
  bool locates_contact_roots;
  // At a contact start whose acceleration-level multiplier is positive: true, the tip lifts off at
  // once; false, the stepper's own contact step decides (the thesis's corrector may keep contact).
  bool lifts_off_on_positive_multiplier;
  // True: the stepper integrates a locked phase (PhaseKind::locked, a stick) and locates its roots;
  // false: a stick stops the pass with its diagnostic (the thesis scheme).
  bool holds_stick;
};

/// How free flight begins. A pass start (the start of a run, or a revolution's section) depends on
/// the state alone: the adaptive step starts afresh and the thesis's grid starts there, so that one
/// revolution is the same map of the section state wherever it runs (docs/model.md §11).
enum class FreeStart {
  pass_start,  // the start of a run or a revolution
  rebound,     // after an impact that bounces
  separation,  // after λ = 0 or a lift-off (the thesis's Step 4b–5a)
};

class Stepper {
public:
  virtual ~Stepper() = default;
  virtual StepperTraits traits() const = 0;
  /// Free flight begins at `state`.
  virtual void begin_free(const FilamentState& state, FreeStart start) = 0;
  /// A contact phase of the law begins at `state` (state.phase, state.episode set by the law).
  virtual void begin_contact(const FilamentState& state) = 0;
  /// One step of the current phase from `state`, never beyond t_stop.
  virtual StepOutcome step(FilamentState& state, double t_stop) = 0;
  /// The free-flight state at t inside the step just taken (CVODE's CVodeGetDky at order 0), into
  /// q [m] and qd [m/s]; false where the scheme keeps no dense output (the thesis's) or in contact.
  virtual bool interpolate(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd) {
    (void)t, (void)q, (void)qd;
    return false;
  }
  virtual const StepperStatistics& statistics() const = 0;
};

/// The thesis's scheme: fixed-step Butcher RK5 in free flight with C = 0 located on the RK5 step,
/// the predictor–corrector in contact, linear interpolation to λ = 0, Step 5a after a separation.
std::unique_ptr<Stepper> make_thesis_stepper(const System& system, const PassOptions& options);

/// The adaptive scheme: Dormand–Prince 5(4) with dense output (Boost.Odeint), roots located on the
/// dense output, projection onto C = 0, Ċ = 0 after every contact step.
std::unique_ptr<Stepper> make_adaptive_stepper(const System& system, const PassOptions& options);

/// The stepper of options.scheme. Throws std::invalid_argument for the thesis scheme under a contact law
/// it does not integrate (ContactLaw::has_thesis_scheme).
std::unique_ptr<Stepper> make_stepper(const System& system, const PassOptions& options);

}  // namespace rotbeam
