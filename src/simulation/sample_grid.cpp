// The next time of a history grid (include/rotbeam/sample_grid.hpp).
#include "rotbeam/sample_grid.hpp"

#include <cmath>

namespace rotbeam {

// k = floor(t/h + 1e-9) + 1: a grid point within 1e-9 h after t counts as t's own (a row written at
// another grid's k'·h', the same time rounded differently, gives no second row a hair later); then
// k moved up while k·h does not exceed t, since once t/h is large (t = 0.03125 s with h = 1 ns, or
// t = 256 s with h = 10 µs) the 1e-9 is below t/h's resolution and k·h came out as t itself; and
// where h is below t's resolution, the next representable time.
double next_grid_time(double t, double h) {
  double k = std::floor(t / h + 1e-9) + 1.0;
  for (int i = 0; i < 4 && !(k * h > t); ++i) k += 1.0;
  const double next = k * h;
  return next > t ? next : std::nextafter(t, INFINITY);
}

}  // namespace rotbeam
