// The energy ledger of a pass and of each revolution (docs/model.md §7, §11; ledger.hpp): the terms the steps
// integrate and the impacts jump, the hub's work from the angular-momentum balance, the change of the
// filament's energy (with the energy a compliant contact stores), and the audit of the Jacobi integral
// in the rotating frame, h_end − h_start = ∫q̇ᵀQ dt − ∫q̇ᵀCq̇ dt + Σ impacts' jumps of T2.
#pragma once

#include "pass_observer.hpp"

#include <memory>

namespace rotbeam {

class EnergyLedger final : public PassObserver {
public:
  explicit EnergyLedger(PassContext& context);

  void start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;
  void step(const StepView& v) override;
  void impact(const ImpactView& v) override;
  void open_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;
  void close_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, RevolutionRecord& r) override;
  /// The pass's ledger and its audit, relative to `energy_scale` (the largest |h| or T2 seen) [J].
  void finish_with_scale(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double energy_scale);
  /// H_z at (q, q̇) [kg m²/s] (overwrites the ledger's workspace).
  double angular_momentum(const Eigen::VectorXd& q, const Eigen::VectorXd& qd);

private:
  // E = T + U plus what the contact stores, at (t, q, q̇) [J]; its H_z into momentum.
  double energy(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double& momentum, double* jacobi = nullptr);

  PassContext& ctx_;
  std::unique_ptr<BeamWorkspace> ws_;
  double h_start_ = 0, impact_jumps_ = 0;
  double energy_start_ = 0, momentum_start_ = 0;  // E and H_z at the start
  double t_start_ = 0;
  // The open revolution's start.
  double mark_t_ = 0, mark_energy_ = 0, mark_momentum_ = 0;
  LedgerValues mark_;
};

}  // namespace rotbeam
