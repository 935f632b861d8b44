#include "rotbeam/surface.hpp"

#include "rotbeam/plane.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rotbeam {

std::shared_ptr<const Surface> make_surface(const SurfaceParameters& p, const BeamModel& beam) {
  if (!std::isfinite(p.depth_fraction))
    throw std::invalid_argument("surface depth fraction must be finite, got " + std::to_string(p.depth_fraction));
  return std::make_shared<Plane>(plane_at_depth(beam, p.depth_fraction));
}

}  // namespace rotbeam
