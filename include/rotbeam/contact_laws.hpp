// The contact laws rotbeam has (docs/contact.md) and the one place where contact.model chooses one.
#pragma once

#include "rotbeam/contact_law.hpp"

#include <memory>

namespace rotbeam {

/// The law of `settings` for a wire of Young's modulus `wire_youngs_pa` [Pa] and diameter
/// `wire_diameter_m` [m] (a compliant contact's stiffness comes from them): the rigid constraint with
/// Coulomb friction and momentum-balance impacts, or the Hertz compliant contact.
std::shared_ptr<const ContactLaw> make_contact_law(const ContactSettings& settings, double wire_youngs_pa,
                                                   double wire_diameter_m);

/// The rigid law with the default settings (friction 0.4, Yigit's restitution): for tests, benchmarks
/// and the C++ examples that build a System by hand.
const ContactLaw& default_contact_law();

}  // namespace rotbeam
