// Wording of the diagnostics both pass schemes give (internal).
#pragma once

#include "rotbeam/rigid_contact.hpp"

#include <cmath>
#include <sstream>
#include <string>

namespace rotbeam::detail {

/// A number with 6 significant digits, for messages.
inline std::string short_number(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

/// Painlevé's paradox for a λ + b|λ| = c (docs/model.md §4): two solutions for c > 0, none for c < 0.
inline std::string painleve_message(double a, double b, double c) {
  return "Painlevé's paradox: a λ + b|λ| = c has " +
         std::string(c > 0 ? "two admissible solutions" : "no admissible solution") + " (a = " + short_number(a) +
         " 1/kg, b = " + short_number(b) + " 1/kg, c = " + short_number(c) + " m/s², a − b = " + short_number(a - b) +
         ")";
}

/// Painlevé's paradox that the rigid law cannot resolve (docs/contact.md, "Painlevé's paradox"): why,
/// and what to change.
inline std::string painleve_unresolved_message(double a, double b, double c, const std::string& why) {
  return painleve_message(a, b, c) + ": " + why +
         "; contact.model = \"hertz\" resolves it with a compliant contact, a lower surface.friction avoids it";
}

/// A stick: V_t = 0 and the tangential force needed lies inside the friction cone.
inline std::string stick_message(const SlipDecision& s, double mu_eff) {
  return "the tip sticks (V_t = 0 and the tangential force needed, " + short_number(s.stick_tangential) +
         " N, is within the friction cone μF_n = " + short_number(mu_eff * std::abs(s.stick_normal)) +
         " N); the thesis scheme does not hold a stick: simulation.scheme = \"adaptive\" does (docs/contact.md)";
}

/// The detail of a stick_start event.
inline std::string stick_start_message(const SlipDecision& s, double mu_eff) {
  return "V_t = 0 and the tangential force needed, " + short_number(s.stick_tangential) +
         " N, lies within the friction cone μF_n = " + short_number(mu_eff * std::abs(s.stick_normal)) +
         " N: the tip sticks";
}

/// The detail of a stick_end event at which the tip slides in direction s_t.
inline std::string stick_end_message(double tangential, double direction) {
  return "the tangential force needed reached μF_n = " + short_number(std::abs(tangential)) +
         " N: the tip slides toward " + (direction > 0 ? "+t" : "−t");
}

/// V_t passed through 0 in contact and the tip now slides the other way.
inline std::string slip_reversal_message(double new_direction) {
  return std::string("V_t = 0; the tip now slides toward ") + (new_direction > 0 ? "+t" : "−t") +
         " (t: the surface tangent, +Y on the plane), friction acts against it";
}

/// A touch after which the tip leaves at once (the locked-tip normal force is positive).
inline std::string lift_off_message(double locked_lambda) {
  return "λ with the tip locked = " + short_number(locked_lambda) + " N > 0: no sustained contact";
}

}  // namespace rotbeam::detail
