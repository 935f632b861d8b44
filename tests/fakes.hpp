// Fakes of the seams (beam_model.hpp, surface.hpp, contact_law.hpp, stepper.hpp) for tests that check
// logic, not physics: the pass driver's and the recorder's bookkeeping (sections, revolutions,
// failures, stops, the chatter guard, the early end) without building a case or integrating anything.
// Each fake does the least its contract asks and counts the calls a test may want to check.
#pragma once

#include "rotbeam/beam_model.hpp"
#include "rotbeam/contact_law.hpp"
#include "rotbeam/stepper.hpp"
#include "rotbeam/surface.hpp"

#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <span>
#include <vector>

namespace rotbeam::fakes {

/// A beam of n decoupled oscillators on a hub turning at ω [rad/s]: M = m I, Ψ = k q + c q̇, the tip
/// at (R, q₀) in the hub frame. Its energies are those of the oscillators (T2 = ½ m q̇ᵀq̇, U = ½ k qᵀq),
/// with T0 = ½ ω² m R² so that the Jacobi integral is finite; nothing of it is a filament.
class FakeBeam final : public BeamModel {
public:
  explicit FakeBeam(int n = 1, double omega = 100.0, double radius = 0.1) : n_(n), omega_(omega), radius_(radius) {}
  double m = 1e-3, k = 1.0, c = 0.0;  // [kg], [N/m], [kg/s]
  double excursion_bound = std::numeric_limits<double>::infinity();  // tip_excursion_bound's answer [m]

  int modes() const override { return n_; }
  HubMotion hub_motion() const override { return {omega_, 0.0}; }
  double tip_radius() const override { return radius_; }
  double beam_length() const override { return radius_; }
  bool geometrically_exact() const override { return false; }
  std::unique_ptr<BeamWorkspace> make_workspace() const override { return std::make_unique<BeamWorkspace>(n_); }
  void evaluate_mass(const Eigen::Ref<const Eigen::VectorXd>&, BeamWorkspace& ws) const override {
    ws.mass = m * Eigen::MatrixXd::Identity(n_, n_);
    ws.mass_llt.compute(ws.mass);
  }
  void evaluate_dynamics(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                         BeamWorkspace& ws) const override {
    evaluate_mass(q, ws);
    ws.psi = k * q + c * qd;
  }
  void tip(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
           HubFrameTip& out) const override {
    out.x = radius_;
    out.y = q[0];
    out.xd = 0;
    out.yd = qd[0];
    out.dx_dq.setZero();
    out.dy_dq.setZero();
    out.dy_dq[0] = 1;
    out.x_quadratic = out.y_quadratic = 0;
  }
  Eigen::Vector2d tip_position(const Eigen::Ref<const Eigen::VectorXd>& q) const override { return {radius_, q[0]}; }
  void shape(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& xi,
             Eigen::Ref<Eigen::MatrixXd> positions) const override {
    for (Eigen::Index i = 0; i < xi.size(); ++i) positions.row(i) << xi[i] * radius_, xi[i] * q[0];
  }
  double tip_deflection(const Eigen::Ref<const Eigen::VectorXd>& q) const override { return std::abs(q[0]); }
  EnergyTerms energy(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& qd,
                     BeamWorkspace&) const override {
    EnergyTerms e;
    e.t0 = 0.5 * omega_ * omega_ * m * radius_ * radius_;
    e.t2 = 0.5 * m * qd.squaredNorm();
    e.potential = 0.5 * k * q.squaredNorm();
    e.kinetic = e.t0 + e.t2;
    e.jacobi = e.t2 - e.t0 + e.potential;
    e.spin_inertia = m * radius_ * radius_;
    e.relative_momentum = m * radius_ * qd[0];
    e.angular_momentum = omega_ * e.spin_inertia + e.relative_momentum;
    return e;
  }
  double angular_momentum_rate(const Eigen::Ref<const Eigen::VectorXd>&, const Eigen::Ref<const Eigen::VectorXd>&,
                               const Eigen::Ref<const Eigen::VectorXd>& qdd, BeamWorkspace&) const override {
    return m * radius_ * qdd[0];
  }
  double dissipation(const Eigen::Ref<const Eigen::VectorXd>& qd) const override { return c * qd.squaredNorm(); }
  bool damped() const override { return c > 0; }
  Linearization linearization() const override {
    const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n_, n_);
    return {m * I, k * I, c * I};
  }
  double tip_excursion_bound(const Eigen::Ref<const Eigen::VectorXd>&, const Eigen::Ref<const Eigen::VectorXd>&,
                             BeamWorkspace&) const override {
    return excursion_bound;
  }

private:
  int n_;
  double omega_, radius_;
};

/// A surface whose gap is a function of time alone (default: 1 m clear everywhere, always). The angle
/// of first contact, the bound on an arc's gap and the deepest angle are the fields' values.
class FakeSurface final : public Surface {
public:
  std::function<double(double)> gap_of_time = [](double) { return -1.0; };  // C(t) [m]
  double contact_angle = NAN;       // first_contact_angle's answer [rad] (NaN: never)
  double arc_gap = 1.0;             // max_gap_on_arc's answer [m] (< 0: the arc is clear)
  mutable int arc_queries = 0;      // calls of max_gap_on_arc

  double gap(const Eigen::Vector2d&, double t) const override { return gap_of_time(t); }
  void contact_geometry(TipKinematics& tip) const override {
    tip.gap = gap_of_time(tip.t);
    tip.gap_rate = tip.gap_time_partial = tip.gamma = 0;
    tip.grad_gap = tip.grad_y;
    tip.normal_x = 0, tip.normal_y = 1, tip.tangent_x = -1, tip.tangent_y = 0;
    tip.surface_vx = tip.surface_vy = 0;
    tip.slip_speed = -tip.VX;
    tip.grad_tangent = -tip.grad_x;
    tip.gamma_tangent = 0;
  }
  double first_contact_angle(double, double) const override { return contact_angle; }
  double max_gap_on_arc(double, double, double, double) const override {
    ++arc_queries;
    return arc_gap;
  }
  double deepest_angle() const override { return 0.0; }
  double material_coordinate(const Eigen::Vector2d& position, double) const override { return position.x(); }
  SurfaceCoordinate coordinate() const override { return {"X", "m", 1.0, 0.0}; }
  nlohmann::json describe() const override { return {{"shape", "fake"}}; }
};

/// A contact law that resolves every touch by a rebound (free flight again, no impact, no force) and
/// counts the touches: the driver's transitions without any contact mechanics.
class FakeContactLaw final : public ContactLaw {
public:
  FakeContactLaw() : ContactLaw(ContactSettings{}) {}
  mutable int touches = 0;

  const char* name() const override { return "fake"; }
  bool has_thesis_scheme() const override { return false; }
  PhaseKind kind(Phase) const override { return PhaseKind::force; }
  std::span<const ContactRoot> roots(Phase) const override { return roots_; }
  ContactEvaluation evaluate(const System&, const ContactEpisode&, double, const Eigen::Ref<const Eigen::VectorXd>&,
                             const Eigen::Ref<const Eigen::VectorXd>&, BeamWorkspace&, TipKinematics&,
                             Eigen::Ref<Eigen::VectorXd> generalized_force) const override {
    generalized_force.setZero();
    return {};
  }
  ContactSample sample(const System&, const ContactEpisode&, double, const Eigen::Ref<const Eigen::VectorXd>&,
                       const Eigen::Ref<const Eigen::VectorXd>&, BeamWorkspace&, TipKinematics&) const override {
    return {};
  }
  double root_value(Phase, int, const System&, const ContactEpisode&, double, const Eigen::Ref<const Eigen::VectorXd>&,
                    const Eigen::Ref<const Eigen::VectorXd>&, BeamWorkspace&, TipKinematics&) const override {
    return -1.0;
  }
  void touch(PhaseControl& control) const override {
    ++touches;
    control.rebound();
  }

private:
  static constexpr ContactRoot roots_[1] = {{"fake end", true, "fake end"}};
};

/// One scripted outcome of ScriptedStepper::step: the state moves to min(t, t_stop) (t = +inf: to
/// t_stop) and the outcome is `status` (a root only when t was reached, not t_stop).
struct ScriptedStep {
  double t = std::numeric_limits<double>::infinity();  // [s]
  StepStatus status = StepStatus::advanced;
  Root root = Root::none;
  FailureKind failure = FailureKind::non_finite;  // status == failed
};

/// A stepper that integrates nothing: each step moves the time by at most `max_step` [s] (q, q̇ kept)
/// and follows its script, then steps freely to every t_stop. It records what the driver asked of it.
class ScriptedStepper final : public Stepper {
public:
  explicit ScriptedStepper(double max_step = 1e-4) : max_step_(max_step) {}
  std::deque<ScriptedStep> script;
  std::vector<FreeStart> free_starts;  // every begin_free's start
  std::vector<double> starts, stops;   // every step's start time and t_stop [s]
  int contact_starts = 0;

  StepperTraits traits() const override { return {Scheme::adaptive, true, true, false}; }
  void begin_free(const FilamentState&, FreeStart start) override { free_starts.push_back(start); }
  void begin_contact(const FilamentState&) override { ++contact_starts; }
  StepOutcome step(FilamentState& state, double t_stop) override {
    starts.push_back(state.t);
    stops.push_back(t_stop);
    ++stats_.steps;
    StepOutcome o;
    const double t_next = std::min(t_stop, state.t + max_step_);
    if (script.empty() || script.front().t > t_next) {
      state.t = t_next;
      return o;
    }
    const ScriptedStep s = script.front();
    script.pop_front();
    o.status = s.status;
    o.root = s.root;
    if (s.status == StepStatus::failed) {
      o.failure = NumericalFailure{s.failure, s.t, 0.0, "scripted failure"};
      return o;
    }
    state.t = s.t;
    return o;
  }
  const StepperStatistics& statistics() const override { return stats_; }

private:
  double max_step_;
  StepperStatistics stats_;
};

}  // namespace rotbeam::fakes
