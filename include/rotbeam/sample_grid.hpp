// The output grids of a pass's history (output.interval_s, output.near_surface_interval_s): the
// times k·h, k a whole number, at which rows are written (docs/cli.md, history.csv).
#pragma once

namespace rotbeam {

/// The first time of the grid k·h [s] strictly after t [s]: always > t, whatever t and h > 0, so a
/// loop that writes rows at successive grid times always advances. Where h is below t's resolution
/// (t/h beyond 2^52) it is the next representable time after t.
double next_grid_time(double t, double h);

}  // namespace rotbeam
