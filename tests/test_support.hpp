// Helpers the tests share to build a mechanical system by hand (the cases of a configuration go
// through build_case instead).
#pragma once

#include "rotbeam/contact_laws.hpp"

#include <memory>

namespace rotbeam::test {

/// The rigid contact law with `friction` and `impact` (a System refers to it: keep it alive while the
/// system is used, e.g. `run_pass({beam, plane, *rigid_law({0.4, false})}, …)` within one expression).
inline std::shared_ptr<const ContactLaw> rigid_law(FrictionModel friction = {}, ImpactLaw impact = {}) {
  ContactSettings settings;
  settings.friction = friction;
  settings.impact = impact;
  return make_contact_law(settings, 0.0, 0.0);  // the rigid law needs no wire properties
}

}  // namespace rotbeam::test
