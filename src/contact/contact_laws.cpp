#include "rotbeam/contact_laws.hpp"

#include "laws.hpp"

namespace rotbeam {

std::shared_ptr<const ContactLaw> make_contact_law(const ContactSettings& settings, double wire_youngs_pa,
                                                   double wire_diameter_m) {
  switch (settings.model) {
    case ContactModel::hertz:
      return make_hertz_law(settings, hertz_stiffness(settings.hertz, wire_youngs_pa, wire_diameter_m),
                            hertz_tip_radius(settings.hertz, wire_diameter_m));
    case ContactModel::rigid: break;
  }
  return make_rigid_law(settings);
}

const ContactLaw& default_contact_law() {
  static const std::shared_ptr<const ContactLaw> law = make_rigid_law(ContactSettings{});
  return *law;
}

}  // namespace rotbeam
