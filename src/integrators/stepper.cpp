#include "rotbeam/stepper.hpp"

#include <stdexcept>

namespace rotbeam {

std::unique_ptr<Stepper> make_stepper(const System& system, const PassOptions& options) {
  if (options.scheme == Scheme::thesis && !system.law.has_thesis_scheme())
    throw std::invalid_argument(std::string("the thesis scheme has no ") + system.law.name() +
                                " contact (contact.model = \"" + system.law.name() +
                                "\" needs simulation.scheme = \"adaptive\")");
  return options.scheme == Scheme::thesis ? make_thesis_stepper(system, options)
                                          : make_adaptive_stepper(system, options);
}

const char* scheme_name(Scheme s) { return s == Scheme::thesis ? "thesis" : "adaptive"; }

const char* factor_use_name(FactorUse u) {
  return u == FactorUse::always ? "true" : u == FactorUse::never ? "false" : "auto";
}

const char* steady_method_name(SteadyMethod m) { return m == SteadyMethod::shooting ? "shooting" : "brute_force"; }

const char* jacobian_method_name(JacobianMethod m) {
  return m == JacobianMethod::differences ? "differences" : "variational";
}

}  // namespace rotbeam
