#include "energy_ledger.hpp"

#include "rotbeam/contact_law.hpp"

#include <algorithm>
#include <cmath>

namespace rotbeam {

EnergyLedger::EnergyLedger(PassContext& context) : ctx_(context), ws_(context.system.beam.make_workspace()) {}

double EnergyLedger::angular_momentum(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  return ctx_.system.beam.energy(q, qd, *ws_).angular_momentum;
}

double EnergyLedger::energy(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double& momentum,
                            double* jacobi) {
  const EnergyTerms e = ctx_.system.beam.energy(q, qd, *ws_);
  momentum = e.angular_momentum;
  if (jacobi) *jacobi = e.jacobi;
  return e.kinetic + e.potential + ctx_.system.law.stored_energy(ctx_.system, t, q);
}

void EnergyLedger::start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  t_start_ = t;
  energy_start_ = energy(t, q, qd, momentum_start_, &h_start_);
}

void EnergyLedger::step(const StepView& v) { ctx_.result.summary.ledger += v.integrals.integral; }

void EnergyLedger::impact(const ImpactView& v) {
  PassSummary& s = ctx_.result.summary;
  const ImpactResult& r = v.result;
  impact_jumps_ += r.delta_t2;
  LedgerValues jump;
  jump[LedgerTerm::normal_impulse] = std::abs(r.impulse);
  jump[LedgerTerm::tangential_impulse] = r.tangential_impulse;
  jump[LedgerTerm::contact_moment] = v.impulse_moment;
  // The impulse's work less a moving surface's part (which is the surface's work, not a loss).
  jump[LedgerTerm::impact_loss] = r.contact_work - r.surface_work;
  jump[LedgerTerm::surface_work] = r.surface_work;
  jump[LedgerTerm::frictional_heat] = r.frictional_heat;
  jump[LedgerTerm::sliding_load] = r.sliding_load;
  s.ledger += jump;
  s.hub_impulsive_work_j += v.hub_work;
}

void EnergyLedger::open_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  mark_t_ = t;
  mark_energy_ = energy(t, q, qd, mark_momentum_);
  mark_ = ctx_.result.summary.ledger;
}

void EnergyLedger::close_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, RevolutionRecord& r) {
  double momentum = 0;
  const double e = energy(t, q, qd, momentum);
  const double omega = ctx_.omega();
  static_cast<LedgerValues&>(r.ledger) = ctx_.result.summary.ledger - mark_;
  // The hub's work: ω times its angular impulse, ΔH_z less the contact's angular impulse.
  r.ledger[LedgerTerm::hub_work] = omega * (momentum - mark_momentum_ - r.ledger[LedgerTerm::contact_moment]);
  r.ledger.energy_change_j = e - mark_energy_;
  const double dt = t - mark_t_;
  const double hub_work = r.ledger[LedgerTerm::hub_work];
  r.mean_hub_torque_n_m = dt > 0.0 ? hub_work / (omega * dt) : 0.0;
  r.mean_hub_power_w = dt > 0.0 ? hub_work / dt : 0.0;
}

void EnergyLedger::finish_with_scale(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double energy_scale) {
  PassSummary& s = ctx_.result.summary;
  const EnergyTerms e = ctx_.system.beam.energy(q, qd, *ws_);
  const double scale = std::max({energy_scale, std::abs(e.jacobi), e.t2});
  s.energy_audit_residual = std::abs(e.jacobi - h_start_ - s.ledger[LedgerTerm::contact_work] -
                                     s.ledger[LedgerTerm::damping_work] - impact_jumps_) /
                            scale;
  // The hub's work from the angular-momentum balance: dH_z/dt = τ + (R × F)_z, with impulses at impacts.
  const double omega = ctx_.omega();
  s.ledger[LedgerTerm::hub_work] =
      omega * (e.angular_momentum - momentum_start_ - s.ledger[LedgerTerm::contact_moment]);
  s.ledger.energy_change_j =
      e.kinetic + e.potential + ctx_.system.law.stored_energy(ctx_.system, t, q) - energy_start_;
  if (ctx_.options.revolutions <= 0 && t > t_start_) {
    // One pass: the means over the pass.
    s.mean_hub_torque_n_m = s.ledger[LedgerTerm::hub_work] / (omega * (t - t_start_));
    s.mean_hub_power_w = s.ledger[LedgerTerm::hub_work] / (t - t_start_);
  }
}

}  // namespace rotbeam
