// The variational (tangent) equations of a pass (docs/model.md §11, "The map's Jacobian from the
// variational equations"): Φ(t) = ∂x(t)/∂x(t₀) for x = (q, q̇) (2n × 2n; the first n rows and columns
// in metres, the last n in m/s). Between events Φ obeys
//
//   Φ̇ = A(t) Φ,   A = [[0, 1], [∂q̈/∂q, ∂q̈/∂q̇]]
//
// with q̈ the vector field of the phase the filament is in (free flight, or a contact phase of the
// contact law with its episode held). At an event where the root function h(t, q, q̇) of the phase
// reaches zero and the state may jump, x⁺ = g(t, x⁻) (an impact; g the identity otherwise), and
// the phase's field changes from f⁻ to f⁺, Φ is multiplied by the saltation matrix
//
//   S = ∂g/∂x + (f⁺ − ∂g/∂x f⁻ − ∂g/∂t) ∇ₓhᵀ / ḣ⁻,   ḣ⁻ = ∇ₓh·f⁻ + ∂h/∂t
//
// (Müller 1995; Leine & Nijmeijer 2004, ch. 3; Bernardo et al. 2008, §2.5): the first-order effect of
// the event's time moving with the start. The derivatives of q̈, g and h are central differences of
// the model's own functions, so every beam model, surface and contact law has them.
#pragma once

#include "rotbeam/beam_model.hpp"
#include "rotbeam/kinematics.hpp"
#include "rotbeam/state.hpp"

#include <Eigen/Core>

#include <memory>

namespace rotbeam {

/// Scratch space of the tangent computations (one per pass; nothing is allocated per call).
struct TangentWorkspace {
  explicit TangentWorkspace(const BeamModel& beam);
  int n;
  double q_step, qd_step;   // central-difference steps on q [m] and q̇ [m/s]
  std::unique_ptr<BeamWorkspace> ws;
  TipKinematics tip;
  Eigen::VectorXd force, q, qd, a_plus, a_minus, qd_plus, qd_minus;
  Eigen::MatrixXd jump;     // ∂g/∂x of an impact (2n × 2n)
  Eigen::VectorXd jump_t;   // ∂g/∂t (2n)
  Eigen::VectorXd grad_h;   // ∇ₓh (2n)
  Eigen::VectorXd f_minus, f_plus;  // the fields before and after an event (2n)
  Eigen::MatrixXd saltation;        // S (2n × 2n)
  double h_rate = 0;                // ḣ⁻ of the last saltation
  Eigen::MatrixXd episode_jacobian; // ∂p/∂x at a touch, less its rate along the flow over ḣ⁻ (4 × 2n)
  Eigen::MatrixXd parameter_field;  // ∂q̈/∂p (n × 4)
  long field_evaluations = 0;       // evaluations of q̈ made for the Jacobians and the saltations
  long closed_form_evaluations = 0;  // free-flight Jacobians in closed form (BeamModel::free_flight_jacobian)
  bool closed_form = true;           // use the model's closed form where it has one (false: differences only)
};

/// q̈ [m/s²] of `phase` at (t, q, q̇) into qdd: free flight M⁻¹(−Ψ), a contact phase M⁻¹(Q − Ψ) with
/// Q from the contact law for `episode` (ContactLaw::evaluate).
void phase_acceleration(const System& system, Phase phase, const ContactEpisode& episode, double t,
                        const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                        TangentWorkspace& tw, Eigen::Ref<Eigen::VectorXd> qdd);

/// ∂q̈/∂q [1/s²] into jq and ∂q̈/∂q̇ [1/s] into jqd (n × n each) of `phase` at (t, q, q̇): in free
/// flight the beam model's closed form where it has one (BeamModel::free_flight_jacobian), else
/// central differences with the steps of tw (4n evaluations of q̈).
void phase_jacobian(const System& system, Phase phase, const ContactEpisode& episode, double t,
                    const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                    TangentWorkspace& tw, Eigen::Ref<Eigen::MatrixXd> jq, Eigen::Ref<Eigen::MatrixXd> jqd);

/// The root function whose zero is an event: the free flight's gap C(t, q) (a touch), or root k of
/// a contact phase (ContactLaw::root_value) with the phase's episode.
struct EventSurface {
  bool gap = true;  // true: C(t, q); false: root `root` of `phase`
  Phase phase = Phase::free;
  int root = 0;
  ContactEpisode episode;
};

/// The state and phase on one side of an event.
struct EventSide {
  double t = 0;
  Eigen::VectorXd q, qd;
  Phase phase = Phase::free;
  ContactEpisode episode;
};

/// The saltation matrix S (2n × 2n, into tw.saltation) of an event on `surface` from `before` to
/// `after` (q equal on both sides); `impact`: q̇ jumped by the contact law's impact
/// (ContactLaw::momentum_jump), differentiated in q, q̇⁻ and t; otherwise g is the identity. Returns
/// false (S undefined) where the approach rate ḣ⁻ vanishes (a grazing event: the map is not
/// differentiable there).
bool saltation_matrix(const System& system, const EventSurface& surface, const EventSide& before,
                      const EventSide& after, bool impact, TangentWorkspace& tw);

/// ∂p/∂x⁻ (4 × 2n, into tw.episode_jacobian) of the episode parameters p a touch sets from the state
/// (ContactLaw::episode_at_touch) with the event time's shift: ∂p/∂x − ṗ ∇ₓhᵀ/ḣ⁻, ṗ the rate of p
/// along the flow before the touch. Call after saltation_matrix for the same event (its ∇ₓh, ḣ⁻).
/// False where the law sets no parameter from the state.
bool episode_sensitivity(const System& system, const EventSide& before, TangentWorkspace& tw);

/// ∂q̈/∂p_k (into column k of tw.parameter_field, n × 4) of `phase` at (t, q, q̇) for the episode's
/// parameters k in `which` (bit k), by central differences (steps of 1e-6 of each parameter's size).
void parameter_field(const System& system, Phase phase, const ContactEpisode& episode, double t,
                     const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                     unsigned which, TangentWorkspace& tw);

}  // namespace rotbeam
