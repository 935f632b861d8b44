// The momentum each accepted step and each impact delivers (force_record.hpp: MomentumDelivery), for a
// sink that asks (a brush sums its filaments' deliveries phase-shifted on the workpiece): the momentum
// into the surface and the hub's angular impulse, ΔH_z less the contact's angular impulse, so that ω
// times their sum over a revolution is its hub work exactly.
#pragma once

#include "energy_ledger.hpp"

namespace rotbeam {

class Deliveries final : public PassObserver {
public:
  Deliveries(PassContext& context, EnergyLedger& ledger) : ctx_(context), ledger_(ledger) {}

  void start(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;
  void step(const StepView& v) override;
  void impact(const ImpactView& v) override;

private:
  PassContext& ctx_;
  EnergyLedger& ledger_;  // H_z at a state
  double last_h_ = 0;     // H_z at the last accepted point [kg m²/s]
};

}  // namespace rotbeam
