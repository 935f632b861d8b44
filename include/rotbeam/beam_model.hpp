// The beam-model seam: what the contact algorithms, the steppers and the outputs need from a
// theory of the filament on its spinning hub (docs/model.md §2–§3, §7). A beam model is immutable and may
// be shared by any number of passes and threads; its scratch space is a BeamWorkspace made by the
// model itself (one per thread, reused by every call, nothing allocated per call).
//
// The quadratic-foreshortening model of the thesis is the first implementation
// (foreshortening_beam.hpp); another theory (e.g. the elastica) implements the same interface and
// plugs into the same surfaces, contact laws, steppers and outputs (docs/architecture.md).
#pragma once

#include "rotbeam/mass_factor.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <memory>

namespace rotbeam {

/// θ0 unless set: the filament starts along −Y (docs/model.md §1, §11) [deg].
inline constexpr double kDefaultStartAngleDeg = -90.0;

/// The hub's rigid rotation: θ(t) = θ0 + ω t, never wrapped (docs/model.md §1, §11).
struct HubMotion {
  double omega = 0;   // ω [rad/s]
  double theta0 = 0;  // θ0 [rad]
  /// Beam angle from +X at time t [rad].
  double theta(double t) const { return theta0 + omega * t; }
  /// Time at which the beam angle is θ [s].
  double time_at(double theta_rad) const { return (theta_rad - theta0) / omega; }
};

/// Scratch space of a beam model and the results of its last evaluation. Beam models derive their
/// own workspace from this one (see BeamModel::make_workspace).
struct BeamWorkspace {
  explicit BeamWorkspace(int n);
  virtual ~BeamWorkspace() = default;
  BeamWorkspace(const BeamWorkspace&) = delete;
  BeamWorkspace& operator=(const BeamWorkspace&) = delete;
  int n;
  Eigen::MatrixXd mass;                  // M(q) [kg]
  MassFactor mass_llt;                   // Cholesky factor of M(q) (mass_factor.hpp)
  Eigen::VectorXd psi;                   // Ψ(q, q̇): every term of the equations of motion but M q̈ [N]
  Eigen::VectorXd scratch, scratch2;     // free for the caller's solves (size n)
};

/// The tip in the hub frame (x along the undeformed filament from the hub centre, y across it, in
/// the sense of rotation) and its derivatives in the modal coordinates q.
struct HubFrameTip {
  explicit HubFrameTip(int n) : dx_dq(n), dy_dq(n) {}
  double x = 0, y = 0;       // [m]
  double xd = 0, yd = 0;     // rates relative to the hub frame [m/s]
  Eigen::VectorXd dx_dq, dy_dq;  // ∂x/∂q, ∂y/∂q (dimensionless)
  // The part of the relative acceleration that does not involve q̈:
  //   ẍ = ∂x/∂qᵀ q̈ + x_quadratic,  ÿ = ∂y/∂qᵀ q̈ + y_quadratic,  i.e. q̇ᵀ (∂²x/∂q²) q̇ and the same for y.
  double x_quadratic = 0, y_quadratic = 0;  // [m/s²]
};

/// The equations of motion linearised about the straight filament q = 0 (docs/model.md §3):
/// M0 q̈ + C q̇ + K q = 0, with M0 = M(0) [kg], K the bending plus linear centrifugal stiffness [N/m]
/// and C the beam's own damping [kg/s] (zero when undamped). G(0) = 0, so there is no gyroscopic
/// term. The modal analysis and the integrating factor of the adaptive scheme start from it.
struct Linearization {
  Eigen::MatrixXd mass, stiffness, damping;
};

/// Energies and hub angular momentum of the filament at (q, q̇) (docs/model.md §3, §7). All in joules
/// (moments of inertia in kg m², momenta in kg m²/s).
struct EnergyTerms {
  double t0 = 0, t1 = 0, t2 = 0;   // ½ω²∫(x²+y²)dm, ω∫(xẏ − yẋ)dm, ½q̇ᵀMq̇ [J]
  double potential = 0;            // U [J]
  double kinetic = 0;              // T = T0 + T1 + T2 [J]
  double jacobi = 0;               // h = T2 − T0 + U [J], conserved in free flight
  double spin_inertia = 0;         // J = ∫ (x² + y²) dm [kg m²]
  double relative_momentum = 0;    // ∫ (x ẏ − y ẋ) dm [kg m²/s]
  double angular_momentum = 0;     // H_z = ω J + ∫ (x ẏ − y ẋ) dm [kg m²/s]
};

class BeamModel {
public:
  virtual ~BeamModel() = default;

  /// Number of generalised coordinates n.
  virtual int modes() const = 0;
  /// The hub's rotation (ω, θ0).
  virtual HubMotion hub_motion() const = 0;
  /// Distance of the undeformed tip from the hub centre, r_h + L [m].
  virtual double tip_radius() const = 0;
  /// Filament length L [m] (the scale of the validity ratio |y_t|/L).
  virtual double beam_length() const = 0;
  /// True when the theory's geometry is exact at any deflection (the elastica), so that the
  /// deflection warning of simulation.deflection_warning_ratio (docs/model.md §10) does not apply.
  virtual bool geometrically_exact() const = 0;

  /// A workspace for this model (the only kind its evaluations accept).
  virtual std::unique_ptr<BeamWorkspace> make_workspace() const = 0;
  /// ws.mass = M(q) and its Cholesky factor ws.mass_llt.
  virtual void evaluate_mass(const Eigen::Ref<const Eigen::VectorXd>& q, BeamWorkspace& ws) const = 0;
  /// ws.mass, ws.mass_llt and ws.psi = Ψ(q, q̇).
  virtual void evaluate_dynamics(const Eigen::Ref<const Eigen::VectorXd>& q,
                                 const Eigen::Ref<const Eigen::VectorXd>& qd, BeamWorkspace& ws) const = 0;
  /// The tip in the hub frame with its Jacobians and quadratic accelerations.
  virtual void tip(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                   HubFrameTip& out) const = 0;
  /// The tip position (x, y) in the hub frame [m] (cheap: for event functions).
  virtual Eigen::Vector2d tip_position(const Eigen::Ref<const Eigen::VectorXd>& q) const = 0;
  /// The filament's centreline in the hub frame [m] at the material points s = ξL (xi: ascending in
  /// [0, 1]) into positions (xi.size() × 2: x, y): for pictures and animations. At ξ = 1 it equals
  /// tip_position(q). Throws std::invalid_argument for points outside [0, 1] or out of order.
  virtual void shape(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& xi,
                     Eigen::Ref<Eigen::MatrixXd> positions) const = 0;
  /// The tip's deflection across the undeformed filament, |y_t| [m] (the validity measure |y_t|/L).
  virtual double tip_deflection(const Eigen::Ref<const Eigen::VectorXd>& q) const = 0;
  /// Every energy term at (q, q̇). Overwrites the workspace.
  virtual EnergyTerms energy(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                             BeamWorkspace& ws) const = 0;
  /// dH_z/dt at (q, q̇) given q̈ [N m] (the hub torque is this minus the contact force's moment).
  virtual double angular_momentum_rate(const Eigen::Ref<const Eigen::VectorXd>& q,
                                       const Eigen::Ref<const Eigen::VectorXd>& qd,
                                       const Eigen::Ref<const Eigen::VectorXd>& qdd, BeamWorkspace& ws) const = 0;

  /// The power the beam's own damping dissipates at q̇, q̇ᵀC q̇ ≥ 0 [W] (its generalised force −C q̇
  /// is part of Ψ). The damping is internal: it exerts no moment about the hub (docs/model.md §11).
  virtual double dissipation(const Eigen::Ref<const Eigen::VectorXd>& qd) const = 0;
  /// True when the beam has damping (dissipation is not identically zero).
  virtual bool damped() const = 0;
  /// M0, K and C of the linearisation about q = 0 (every matrix n × n).
  virtual Linearization linearization() const = 0;
  /// A bound δ [m] on the tip's distance from its undeformed position (r_h + L, 0) in the hub frame
  /// for all of a free flight that starts at (q, q̇) with ω constant, or +inf where the model gives
  /// none: the Jacobi integral, which free flight never increases, confines q (docs/model.md §7; docs/model.md
  /// "Free flight that cannot reach the surface"). Overwrites the workspace.
  virtual double tip_excursion_bound(const Eigen::Ref<const Eigen::VectorXd>& q,
                                     const Eigen::Ref<const Eigen::VectorXd>& qd, BeamWorkspace& ws) const = 0;

  /// q̈ = −M⁻¹Ψ of free flight into qdd (size n) with its derivatives ∂q̈/∂q [1/s²] into jq and
  /// ∂q̈/∂q̇ [1/s] into jqd (n × n), in closed form; false where the model has none (then the caller
  /// differentiates q̈ numerically, tangent.hpp). Overwrites the workspace.
  virtual bool free_flight_jacobian(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                                    BeamWorkspace& ws, Eigen::Ref<Eigen::VectorXd> qdd, Eigen::Ref<Eigen::MatrixXd> jq,
                                    Eigen::Ref<Eigen::MatrixXd> jqd) const {
    (void)q, (void)qd, (void)ws, (void)qdd, (void)jq, (void)jqd;
    return false;
  }

  /// The coordinates of the straight filament turning steadily with the hub (the state of a rigid
  /// turn, docs/model.md §9) into q (size n): zero for an inextensible filament, the centrifugal stretch
  /// for an extensible one (extensible_beam.hpp).
  virtual void rest_state(Eigen::Ref<Eigen::VectorXd> q) const { q.setZero(); }

  /// θ(t) [rad] and its inverse [s].
  double theta(double t) const { return hub_motion().theta(t); }
  double time_at(double theta_rad) const { return hub_motion().time_at(theta_rad); }
};

/// q̈ = M⁻¹(Q − Ψ) for a generalised force Q (nullptr: Q = 0, free flight) into qdd (size n).
/// Evaluates the dynamics into ws; allocates nothing.
void acceleration(const BeamModel& beam, const Eigen::Ref<const Eigen::VectorXd>& q,
                  const Eigen::Ref<const Eigen::VectorXd>& qd, const Eigen::VectorXd* generalized_force,
                  BeamWorkspace& ws, Eigen::Ref<Eigen::VectorXd> qdd);

/// The tip's distance from its clamp at (r_h, 0) in the hub frame, in units of L [-] (docs/model.md §10). An
/// inextensible filament has at most 1: above kReachLimit the model has left its geometry.
double tip_reach(const BeamModel& beam, const Eigen::Ref<const Eigen::VectorXd>& q);
inline constexpr double kReachLimit = 1.01;

}  // namespace rotbeam

