#include "rotbeam/beam_factory.hpp"

#include "rotbeam/elastica_beam.hpp"
#include "rotbeam/extensible_beam.hpp"
#include "rotbeam/foreshortening_beam.hpp"

namespace rotbeam {

int max_modes(BeamTheory theory) { return theory == BeamTheory::elastica ? kMaxElasticaModes : kMaxModes; }

std::shared_ptr<const BeamModel> make_beam_model(const BeamParameters& p, double theta0_rad) {
  if (p.axial == BeamAxial::extensible) return std::make_shared<ExtensibleBeam>(make_extensible(p, theta0_rad));
  if (p.theory == BeamTheory::elastica) return std::make_shared<ElasticaBeam>(make_elastica(p, theta0_rad));
  return std::make_shared<ForeshorteningBeam>(make_beam(p, theta0_rad));
}

}  // namespace rotbeam
