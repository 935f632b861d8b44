// The next time of a history grid (include/rotbeam/sample_grid.hpp).
#include "rotbeam/sample_grid.hpp"

#include <cmath>

namespace rotbeam {

// From k = floor(t/h) + 1, moved up while k·h does not exceed t: t/h falls a hair below k where
// t = k·h was written, at any t (a guard on t/h alone, floor(t/h + 1e-9), fails once t/h is large,
// e.g. t = 0.03125 s with h = 1 ns, or t = 256 s with h = 10 µs).
double next_grid_time(double t, double h) {
  double k = std::floor(t / h) + 1.0;
  for (int i = 0; i < 4 && !(k * h > t); ++i) k += 1.0;
  const double next = k * h;
  return next > t ? next : std::nextafter(t, INFINITY);
}

}  // namespace rotbeam
