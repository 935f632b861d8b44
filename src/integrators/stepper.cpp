#include "rotbeam/stepper.hpp"

namespace rotbeam {

std::unique_ptr<Stepper> make_stepper(const System& system, const PassOptions& options) {
  return options.scheme == Scheme::thesis ? make_thesis_stepper(system, options)
                                          : make_adaptive_stepper(system, options);
}

const char* scheme_name(Scheme s) { return s == Scheme::thesis ? "thesis" : "adaptive"; }

const char* factor_use_name(FactorUse u) {
  return u == FactorUse::always ? "true" : u == FactorUse::never ? "false" : "auto";
}

const char* steady_method_name(SteadyMethod m) { return m == SteadyMethod::shooting ? "shooting" : "brute_force"; }

}  // namespace rotbeam
