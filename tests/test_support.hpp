// Helpers the tests share to build a mechanical system by hand (the cases of a configuration go
// through build_case instead).
#pragma once

#include "rotbeam/contact_laws.hpp"

#include <memory>
#include <sstream>
#include <string>

namespace rotbeam::test {

/// The rigid contact law with `friction` and `impact` (a System refers to it: keep it alive while the
/// system is used, e.g. `run_pass({beam, plane, *rigid_law({0.4, false})}, …)` within one expression).
inline std::shared_ptr<const ContactLaw> rigid_law(FrictionModel friction = {}, ImpactLaw impact = {}) {
  ContactSettings settings;
  settings.friction = friction;
  settings.impact = impact;
  return make_contact_law(settings, 0.0, 0.0);  // the rigid law needs no wire properties
}

/// stderr without the progress lines a pass writes in a log (`rotbeam: progress: …`, after 10 s when
/// stderr is not a terminal, docs/cli.md): a slow build (the sanitizers') reaches them in runs that
/// are quick otherwise, and they are no message: a message's one line is counted without them.
inline std::string without_progress_lines(const std::string& err) {
  std::istringstream in(err);
  std::string out;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("rotbeam: progress: ", 0) != 0) out += line + "\n";
  if (!err.empty() && err.back() != '\n' && !out.empty()) out.pop_back();
  return out;
}

}  // namespace rotbeam::test
