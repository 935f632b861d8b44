// What the surface receives from a filament (docs/model.md §7, output.bin_deg): one bin of hub angle and its
// momentum, one step's or one impact's delivery, and the peaks of the binned force. Words only;
// the bins themselves are the simulation layer's ForceBins (force_bins.hpp).
#pragma once

#include <cmath>

namespace rotbeam {

/// One bin of hub angle [from_deg, to_deg) and what the surface received in it. Normal is along
/// the surface's normal into the surface (≥ 0); tangential along the surface's tangent t (+Y on
/// the thesis's plane), the force on the surface, so the opposite of friction on the tip.
struct ForceBin {
  double from_deg = 0, to_deg = 0;           // hub angle relative to the surface's deepest point [°]
  double normal_impulse_n_s = 0;             // momentum into the surface [N s]
  double tangential_impulse_n_s = 0;         // momentum along the tangent [N s]
  double mean_normal_force_n = 0;            // normal_impulse / the bin's duration [N]
  double mean_tangential_force_n = 0;        // tangential_impulse / the bin's duration [N]
  int impacts = 0;                           // impacts in the bin
  double hub_angular_impulse_n_m_s = 0;      // ∫τ dt of the hub on the filament(s) over the bin [N m s]
  double mean_hub_torque_n_m = 0;            // hub_angular_impulse / the bin's duration [N m]
};

/// What one accepted step (span_deg > 0) or one impact (span_deg = 0, impact = true) of a pass
/// delivered, at relative hub angle from_deg (docs/model.md §11: (−180°, 180°], 0° at the surface's deepest
/// point): the momentum into the surface and the hub's angular impulse on the filament, ΔH_z less the
/// contact's angular impulse, so that ω times their sum over a revolution is its hub work exactly.
struct MomentumDelivery {
  double from_deg = 0;                   // [°]
  double span_deg = 0;                   // ≥ 0 [°]
  double normal_n_s = 0;                 // ≥ 0, into the surface [N s]
  double tangential_n_s = 0;             // along the surface's tangent, on the surface [N s]
  double hub_angular_impulse_n_m_s = 0;  // [N m s]
  double along_m = NAN;                  // where the tip touched (contact or impact), along the surface's tangent [m]
  bool impact = false;
};

/// The peaks of the binned force (summary.json's binned_force).
struct BinnedForcePeaks {
  double bin_deg = 0;                  // [°]
  double peak_normal_force_n = 0;      // the largest mean normal force of a bin [N]
  double peak_tangential_force_n = 0;  // the largest |mean tangential force| of a bin [N]
  double peak_normal_at_deg = 0;       // the centre of the bin of the normal peak [°] (NaN: no momentum)
};

}  // namespace rotbeam
