// The wear profile's bins as a pass reports them (docs/wear.md; wear.hpp derives volumes and depths).
#pragma once

namespace rotbeam {

/// The complete revolutions whose wear profiles a run over many keeps (the longest steady period).
inline constexpr int kWearRevolutionsKept = 4;

/// One bin of a wear profile: [from, to) in the surface's coordinate (SurfaceCoordinate's unit), the
/// load–distance and heat the contact left in it.
struct WearBin {
  double from = 0, to = 0;
  double sliding_load_n_m = 0;  // [N m]
  double heat_j = 0;            // [J]
};

}  // namespace rotbeam
