#include "rotbeam/stepper.hpp"

#include <stdexcept>

namespace rotbeam {

std::unique_ptr<Stepper> make_stepper(const System& system, const PassOptions& options) {
  return options.scheme == Scheme::thesis ? make_thesis_stepper(system, options)
                                          : make_adaptive_stepper(system, options);
}

void Stepper::begin_compliant_contact(const FilamentState&, double) {
  throw std::logic_error(std::string("the ") + scheme_name(traits().scheme) +
                         " scheme has no compliant contact (contact.model = \"hertz\" needs simulation.scheme = \"adaptive\")");
}

const char* scheme_name(Scheme s) { return s == Scheme::thesis ? "thesis" : "adaptive"; }

const char* factor_use_name(FactorUse u) {
  return u == FactorUse::always ? "true" : u == FactorUse::never ? "false" : "auto";
}

const char* steady_method_name(SteadyMethod m) { return m == SteadyMethod::shooting ? "shooting" : "brute_force"; }

}  // namespace rotbeam
