// The contact laws of src/contact/ (private to the contact layer): each is made here and chosen in
// contact_laws.cpp. A new law is a file of this folder with its maker declared below.
#pragma once

#include "rotbeam/contact_law.hpp"

#include <memory>

namespace rotbeam {

/// The thesis's rigid unilateral constraint with Coulomb friction and momentum-balance impacts
/// (rigid_law.cpp).
std::shared_ptr<const ContactLaw> make_rigid_law(const ContactSettings& settings);

/// Hertz sphere-on-flat compliance with Hunt–Crossley damping and regularised friction, of contact
/// stiffness `stiffness` k [N/m^{3/2}] and tip radius R [m] (hertz_law.cpp).
std::shared_ptr<const ContactLaw> make_hertz_law(const ContactSettings& settings, double stiffness, double tip_radius);

}  // namespace rotbeam
