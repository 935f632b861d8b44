#include "rotbeam/surface.hpp"
#include "rotbeam/units.hpp"

#include "rotbeam/casing.hpp"
#include "rotbeam/cylinder.hpp"
#include "rotbeam/plane.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rotbeam {

const char* surface_shape_name(SurfaceShape shape) {
  switch (shape) {
    case SurfaceShape::plane: return "plane";
    case SurfaceShape::cylinder: return "cylinder";
    case SurfaceShape::casing: return "casing";
  }
  return "?";
}

std::shared_ptr<const Surface> make_surface(const SurfaceParameters& p, const BeamModel& beam) {
  const auto finite = [](double v, const char* what) {
    if (!std::isfinite(v)) throw std::invalid_argument(std::string(what) + " must be finite, got " + std::to_string(v));
  };
  finite(p.depth_fraction, "surface depth fraction");
  switch (p.shape) {
    case SurfaceShape::plane: return std::make_shared<Plane>(plane_at_depth(beam, p.depth_fraction));
    case SurfaceShape::cylinder: {
      finite(p.radius_m, "cylinder radius");
      finite(p.speed_rpm, "cylinder speed");
      if (!(p.radius_m > 0.0)) throw std::invalid_argument("cylinder radius must be > 0, got " + std::to_string(p.radius_m));
      const double d = plane_at_depth(beam, p.depth_fraction).distance();
      return std::make_shared<Cylinder>(d, p.radius_m, rad_per_s_from_rpm(p.speed_rpm));
    }
    case SurfaceShape::casing: {
      finite(p.clearance_m, "casing clearance");
      finite(p.lobe_amplitude_m, "casing lobe amplitude");
      if (p.lobes < 0) throw std::invalid_argument("casing lobes must be >= 0, got " + std::to_string(p.lobes));
      LobeLaw law;
      if (p.lobe_law == "cosine")
        law = LobeLaw::cosine;
      else if (p.lobe_law == "benchmark")
        law = LobeLaw::benchmark;
      else
        throw std::invalid_argument("casing lobe law must be \"cosine\" or \"benchmark\", got \"" + p.lobe_law + "\"");
      return std::make_shared<Casing>(beam.tip_radius(), p.clearance_m, p.lobes, p.lobe_amplitude_m, law);
    }
  }
  throw std::invalid_argument("unknown surface shape");
}

}  // namespace rotbeam
