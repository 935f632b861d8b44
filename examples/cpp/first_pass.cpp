// Using the rotbeam C++ library directly: the base case's first impact, a whole pass with the
// adaptive scheme, the linear modes, and the same pass from a configuration with overrides.
//   build/examples/cpp/first_pass
#include "rotbeam/case.hpp"
#include "rotbeam/contact_laws.hpp"
#include "rotbeam/modal_analysis.hpp"
#include "rotbeam/plane.hpp"

#include <cstdio>

int main() {
  using namespace rotbeam;

  // 1. The filament on its hub (modal integrals are computed once per mode count) and the surface.
  BeamParameters p;  // thesis Table 5-1, 550 rpm, 5 modes
  const ForeshorteningBeam beam = make_beam(p);
  const Plane plane = plane_at_depth(beam, 0.02);  // 2 % depth
  ContactSettings contact;  // the rigid law, μ = 0.4, Yigit's restitution
  contact.friction.mu = 0.4;
  const std::shared_ptr<const ContactLaw> law = make_contact_law(contact, p.youngs_modulus_pa, p.diameter_m);
  const System system{beam, plane, *law};

  // 2. The first impact of a rigid start (thesis Table 5-3, first row).
  InitialConditions rigid;  // q = q̇ = 0 at the geometric contact angle
  const FirstImpactResult hit = first_impact(system, rigid, 90.0, 1e-6);
  std::printf("first impact at θ = %.4f°: V_X %.4f → %.4f m/s, e = %.4f\n", hit.theta * 180 / M_PI,
              hit.impact.vx_before, hit.impact.vx_after, hit.impact.restitution);

  // 3. A whole pass with the adaptive scheme.
  PassOptions options;  // end at +90°, rtol 1e-9, history every 10 µs
  const PassResult pass = run_pass(system, rigid, options);
  const PassSummary& s = pass.summary;
  std::printf("pass: %d impacts, %d contact episodes, last separation %.3f°, peak F_n %.3f N, %zu history rows\n",
              s.impacts, s.contact_episodes, s.last_separation_deg, s.peak_normal_force_n, pass.history.size());

  // 4. Natural frequencies of the spinning filament.
  const ModalAnalysis modes = modal_analysis(beam);
  std::printf("f1…f3 at 550 rpm: %.2f, %.2f, %.2f Hz\n", modes.frequencies_hz[0], modes.frequencies_hz[1],
              modes.frequencies_hz[2]);

  // 5. The same through a configuration (TOML text or file) with --set style overrides.
  const Config config = load_config_string("[hub]\nspeed_rpm = 3000\n", {"surface.friction=0.1"});
  const PassResult fast = run_case(build_case(config));
  std::printf("3000 rpm, μ = 0.1: %d impacts, last separation %.3f°\n", fast.summary.impacts,
              fast.summary.last_separation_deg);
  return pass.failure || fast.failure ? 1 : 0;
}
