// The steppers' contract (SPEC §6): one interface under the pass driver, modelled on SUNDIALS'
// CVODE — a step call that returns a status, root functions with directions, statistics. The
// driver (pass_driver.hpp) owns the phase logic (free → impact → contact → separation, stick,
// Painlevé); a stepper only advances the state of its phase and reports what it crossed.
//
// Root functions, with the direction that counts:
//   gap_closes           free flight   C(t, q)            crosses 0 upward    (a touch: impact or contact)
//   multiplier_vanishes  contact       λ(t, q, q̇)         crosses 0 upward    (separation)
//   slip_stops           contact       s_t·V_t(t, q, q̇)   crosses 0 downward  (slip reversal, stick, lift-off)
//   gap_opens            compliant     C(t, q)            crosses 0 downward  (the end of a Hertz contact)
#pragma once

#include "rotbeam/contact_law.hpp"
#include "rotbeam/outcome.hpp"
#include "rotbeam/pass_options.hpp"
#include "rotbeam/surface.hpp"

#include <memory>
#include <optional>
#include <string>

namespace rotbeam {

enum class Phase { free, contact, stick };
const char* phase_name(Phase p);

/// The mechanical system of a pass: the beam on its hub, the surface and the contact law.
/// Read-only; any number of passes may share one.
struct System {
  const BeamModel& beam;
  const Surface& surface;
  ContactLaw law;
};

/// The state of one filament: time, modal coordinates and velocities, phase and slip direction.
struct FilamentState {
  explicit FilamentState(int n) : q(Eigen::VectorXd::Zero(n)), qd(Eigen::VectorXd::Zero(n)) {}
  double t = 0;            // [s]
  Eigen::VectorXd q, qd;   // [m], [m/s]
  Phase phase = Phase::free;
  double slip = 0;         // s_t ∈ {−1, 0, +1}: the friction acts against it (contact only)
};

/// Integrals over a step: the contact's (zero in free flight), its largest normal force, and the
/// beam's damping work (every phase).
struct StepIntegrals {
  double work = 0;               // ∫ q̇ᵀQ_contact dt [J]
  double friction_work = 0;      // ∫ F_t V_t dt [J]
  double normal_impulse = 0;     // ∫ F_n dt [N s]
  double contact_moment = 0;     // ∫ (X_t F_Y − Y_t F_X) dt, the contact force's angular impulse about the hub [N m s]
  double peak_normal_force = 0;  // the largest F_n over the step, its interior included [N]
  double damping_work = 0;       // −∫ q̇ᵀC q̇ dt ≤ 0, the work of the beam's damping (SPEC §11) [J]
  double surface_work = 0;       // ∫ F_t (V_s·t) dt [J]: a moving surface's work through friction
  double contact_dissipation = 0;  // ∫ −(F_n − kδ^{3/2})δ̇ dt ≤ 0, the compliant contact's damping (SPEC §11) [J]
};

enum class Root { none, gap_closes, multiplier_vanishes, slip_stops, gap_opens };

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
  ContactLoad load;                          // contact load at the step's end (contact steps)
  StepIntegrals integrals;                   // over the step (contact steps)
  std::optional<NumericalFailure> failure;   // status == failed
  std::optional<StepNote> note;
};

struct StepperStatistics {
  long steps = 0;
  long rhs_evaluations = 0;
  long corrector_iterations = 0;
  int corrector_iterations_max = 0;
};

/// What a stepper does itself, and so what the driver does for it.
struct StepperTraits {
  Scheme scheme;
  // True: the stepper locates V_t = 0 (Root::slip_stops). False: the driver checks the slip
  // direction from V_t before every contact step (the thesis's Appendix B does so).
  bool locates_slip_stops;
  // At a contact start whose acceleration-level multiplier is positive: true, the tip lifts off at
  // once; false, the stepper's own contact step decides (the thesis's corrector may keep contact).
  bool lifts_off_on_positive_multiplier;
};

/// How free flight begins. A pass start (the start of a run, or a revolution's section) depends on
/// the state alone: the adaptive step starts afresh and the thesis's grid starts there, so that one
/// revolution is the same map of the section state wherever it runs (SPEC §11).
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
  /// Sustained contact begins at `state` with the acceleration-level multiplier λ0.
  virtual void begin_contact(const FilamentState& state, double lambda0) = 0;
  /// A compliant (Hertz) contact begins at `state` (C = 0, approaching) with the Hunt–Crossley
  /// damping c [s/m] of this contact (contact_law.hpp); its steps end at Root::gap_opens. Only the
  /// adaptive scheme integrates it (the configuration refuses the thesis's with contact.model = "hertz").
  virtual void begin_compliant_contact(const FilamentState& state, double damping);
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

/// The stepper of options.scheme.
std::unique_ptr<Stepper> make_stepper(const System& system, const PassOptions& options);

}  // namespace rotbeam
