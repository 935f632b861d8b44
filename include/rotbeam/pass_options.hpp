// Settings of a pass (docs/model.md §6, §9 [simulation] and [output]): the scheme, its steps or tolerances,
// and the recording. Every default is defined here once; the configuration reads into this struct.
#pragma once

namespace rotbeam {

/// The integration scheme under the pass driver (docs/model.md §6).
enum class Scheme {
  adaptive,  // error-controlled Dormand–Prince 5(4) with dense output and located events (default)
  thesis,    // the thesis's fixed-step RK5 and predictor–corrector (thesis §4.6–4.7)
};
const char* scheme_name(Scheme s);

/// Whether the adaptive scheme integrates through the integrating factor (integrating_factor.hpp).
enum class FactorUse {
  automatic,  // for an undamped filament; not with damping (docs/model.md: the factor makes the damped
              // modes' forced, slowly varying response oscillate in its variables and costs steps)
  always,
  never,
};
const char* factor_use_name(FactorUse u);

/// How a run looks for the periodic steady state (docs/model.md §11).
enum class SteadyMethod {
  brute_force,  // revolution after revolution until the section state stops changing
  shooting,     // Newton on the one-revolution map at the section (studies layer, steady_state.hpp)
};
const char* steady_method_name(SteadyMethod m);

/// How the section map's Jacobian is computed (Newton's steps, the Floquet multipliers, continuation).
enum class JacobianMethod {
  variational,  // the variational equations with a saltation matrix at every event (tangent.hpp): one run
  differences,  // central differences of the map: 4n runs, accurate to ≈ 1e-4 at rtol 1e-9
};
const char* jacobian_method_name(JacobianMethod m);

/// simulation.revolutions when simulation.until_steady is set without it: the cap on the search.
inline constexpr int kDefaultSteadyRevolutionCap = 1000;

/// The longest period [revolutions] of a steady state the searches recognise.
inline constexpr int kMaxSteadyPeriod = 4;

struct PassOptions {
  Scheme scheme = Scheme::adaptive;   // simulation.scheme
  double end_angle_deg = 90.0;        // simulation.end_angle_deg: stop angle θ [deg] (one pass)
  // simulation.end_when_clear: end one pass early, in free flight, once the tip provably cannot
  // reach the surface before end_angle_deg (BeamModel::tip_excursion_bound, Surface::max_gap_on_arc).
  bool end_when_clear = false;
  // Revolutions (docs/model.md §11): with revolutions > 0 the run ends after that many whole turns from θ0
  // (end_angle_deg is then θ0 + 360·revolutions) and the section θ = θ0 (mod 360°) closes each one.
  int revolutions = 0;                // simulation.revolutions: 0 = one pass to end_angle_deg
  bool until_steady = false;          // simulation.until_steady: stop once the section state repeats
  double steady_tolerance = 1e-8;     // simulation.steady_tolerance: relative section distance
  SteadyMethod steady_method = SteadyMethod::brute_force;  // simulation.steady_method
  bool multipliers = true;            // simulation.multipliers: the steady state's Floquet multipliers
  JacobianMethod jacobian = JacobianMethod::differences;  // simulation.jacobian
  // Thesis scheme (thesis §4.6–4.7).
  double free_step_s = 1e-6;          // simulation.free_step_s: RK5 step in free flight [s]
  double contact_step_s = 1e-7;       // simulation.contact_step_s: predictor–corrector step [s]
  double fine_contact_step_s = 1e-8;  // simulation.fine_contact_step_s: … while 0 < |λ| < fine_below_n [s]
  double fine_below_n = 1e-4;         // simulation.fine_below_n [N]
  double corrector_tolerance = 1e-5;  // simulation.corrector_tolerance: relative change of λ between iterates
  int corrector_max_iterations = 50;  // simulation.corrector_max_iterations
  bool thesis_dcdt = false;           // compat.thesis_dcdt: ∂C/∂t forced to −∇Cᵀu^p (thesis §6.3)
  // Adaptive scheme (docs/model.md §6).
  double rtol = 1e-9;                 // simulation.rtol
  double atol = 1e-12;                // simulation.atol
  double max_step_s = 2e-5;           // simulation.max_step_s: upper bound on the adaptive step [s]
  double event_tolerance_s = 1e-13;   // events located to this bracket width [s]
  // simulation.integrating_factor: propagate the linear modal oscillation about q = 0 exactly and
  // integrate only the remainder (Lawson's method, integrating_factor.hpp); never: plain DP5 on q, q̇.
  FactorUse integrating_factor = FactorUse::automatic;
  // The adaptive scheme integrates the variational equations beside the motion and applies the
  // saltation matrix at every event (tangent.hpp), so that the run's end holds ∂x/∂x₀ (PassResult::
  // final_tangent). Set by the studies (the section map's Jacobian); not a configuration key.
  bool tangent = false;
  // Both schemes.
  int max_impacts = 10000;                 // simulation.max_impacts
  double deflection_warning_ratio = 0.1;   // simulation.deflection_warning_ratio: warn past max |y_t|/L
  bool deflection_limit_is_error = false;  // simulation.deflection_limit_is_error: stop with `validity`
  // Recording.
  double output_interval_s = 1e-5;    // output.interval_s: history sampling (events always recorded exactly)
  int history_revolutions = 1;        // output.history_revolutions: history and events of the last K revolutions (0: all)
  // While the tip is within near_surface_gap_m of the surface (C > −gap), rows every
  // near_surface_interval_s (free flight: on the stepper's dense output where it has one; 0: every
  // accepted step) so that impacts, bounces and separations are drawn from many points (docs/model.md §7).
  double near_surface_interval_s = 2e-6;  // output.near_surface_interval_s [s]
  double near_surface_gap_m = 5e-4;       // output.near_surface_gap_m [m] (0: off)
  double bin_deg = 0.5;                   // output.bin_deg: hub-angle bins of the force on the surface [°]
  int wear_profile_bins = 100;            // wear.profile_bins: bins of the wear profile over the span touched
  // The span [m] over which a profile whose contact touched one point only (a single impact) is spread:
  // the contact's own width, the filament's diameter (build_case sets it).
  double wear_point_span_m = 5.08e-4;
};

}  // namespace rotbeam
