// The ground floor of a pass (docs/model.md, "One pass"): the phases a filament can be in, its
// state, and the mechanical system it belongs to. Every layer above uses these words; this header
// includes nothing of theirs (the system refers to its parts by reference).
#pragma once

#include <Eigen/Core>

#include <array>

namespace rotbeam {

class BeamModel;
class Surface;
class ContactLaw;

/// The phase of the filament's tip: in free flight, in sustained contact (sliding, or a compliant
/// contact), or stuck to the surface.
enum class Phase { free, contact, stick };

/// "free", "contact", "stick": history.csv's `phase`.
inline const char* phase_name(Phase p) {
  switch (p) {
    case Phase::free: return "free";
    case Phase::contact: return "contact";
    case Phase::stick: return "stick";
  }
  return "?";
}

/// The mechanical system of a pass: the beam on its hub, the surface and the contact law. Read-only;
/// any number of passes and threads may share one (the three parts are immutable).
struct System {
  const BeamModel& beam;
  const Surface& surface;
  const ContactLaw& law;
};

/// The number of a contact episode's parameters.
inline constexpr int kEpisodeParameters = 4;

/// What a contact episode carries besides (q, q̇), set by the contact law at its start and read by it
/// in its force (contact_law.hpp says what each law keeps in `parameter`).
struct ContactEpisode {
  double slip = 0;  // s_t ∈ [−1, +1]: the friction acts against it
  // The law's own (the rigid law: λ0, and 1 in [1] while the tip sticks; the compliant law:
  // Hunt–Crossley c).
  std::array<double, kEpisodeParameters> parameter{};
};

/// The state of one filament: time, modal coordinates and velocities, phase, and the contact episode
/// under way (contact phases only).
struct FilamentState {
  explicit FilamentState(int n) : q(Eigen::VectorXd::Zero(n)), qd(Eigen::VectorXd::Zero(n)) {}
  double t = 0;            // [s]
  Eigen::VectorXd q, qd;   // [m], [m/s]
  Phase phase = Phase::free;
  ContactEpisode episode;
  // Φ = ∂(q, q̇)/∂(q₀, q̇₀) (2n × 2n) where the pass integrates its variational equations
  // (PassOptions::tangent, tangent.hpp); empty otherwise.
  Eigen::MatrixXd tangent;
  // ∂(episode.parameter)/∂(q₀, q̇₀) (4 × 2n) where a contact episode's parameters were set from the
  // state at its touch (ContactLaw::episode_at_touch); empty otherwise.
  Eigen::MatrixXd episode_tangent;
};

}  // namespace rotbeam
