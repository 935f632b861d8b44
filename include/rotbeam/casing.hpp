// A casing around the hub (issue "Beyond the flat plane"; docs/model.md §11): the closed curve
// ρ = R(φ) = r_h + L + c(φ) in polar coordinates (ρ, φ) about the hub centre, at rest, the tip inside.
// The clearance c(φ) is one of
//   concentric:  c(φ) = c0                                                     (lobes = 0)
//   cosine:      c(φ) = c0 − A cos(kφ)                 (k lobes, deepest at φ = 0, 360°/k, …)
//   benchmark:   c(φ) = c0 − 2A exp(−((mod(φ + π/2, π)/π − 0.5)/0.15)²)   (two lobes, deepest at 0°, 180°)
// with c0 = surface.clearance_m (negative: interference), A = surface.lobe_amplitude_m. The
// benchmark law is the two-lobe distortion of the NASA Rotor 37 rub case (Piollet, Nyssen & Batailly
// 2019): with A = c0 = g0 it is their g(θ) = g0(1 − 2exp(−((mod(θ, π)/π − 0.5)/0.15)²)) with their
// θ = φ + 90°, so that the lobes sit at φ = 0° and 180° (0° is the deepest point of every surface, and
// the filament starts at −90°, between the lobes). Its derivative jumps from +4.2e-4·A to −4.2e-4·A
// per radian (each side 2A·2u·e^(−u²)/(0.15π), u = 0.5/0.15) at φ = 90° + m·180°, where mod wraps: the
// law is only C⁰ there (the benchmark's own property).
//
// The gap is g = (ρ − R(φ)) w, w = ρ/√(ρ² + R'(φ)²), so that |∇g| = 1 on the casing (the multiplier is
// the physical normal force) and g has the sign of ρ − R(φ); without lobes it is the signed distance
// ρ − R. ∇g and the Hessian follow from the polar derivatives (casing.cpp).
#pragma once

#include "rotbeam/gap_field.hpp"
#include "rotbeam/surface.hpp"

#include <string>

namespace rotbeam {

enum class LobeLaw { cosine, benchmark };

class Casing final : public Surface {
public:
  /// Nominal radius `nominal_radius_m` = r_h + L [m]; the clearance law's c0, k, A [m, -, m].
  Casing(double nominal_radius_m, double clearance_m, int lobes, double lobe_amplitude_m, LobeLaw law);

  /// The clearance c(φ) [m] and its first three derivatives in φ [m/rad^k] at the polar angle φ [rad].
  struct Clearance {
    double value = 0, d1 = 0, d2 = 0, d3 = 0;
  };
  Clearance clearance(double phi) const;
  /// g, ∇g and H at the global point P [m] (P ≠ 0).
  GapField field(const Eigen::Vector2d& position) const;

  double gap(const Eigen::Vector2d& position, double t) const override;
  void contact_geometry(TipKinematics& tip) const override;
  /// The first φ ≥ θ_from where r − R(φ) rises through 0 (a scan at 1/64 of a lobe, then bisection
  /// to the last bit); NaN when the point at distance r never crosses the casing inward.
  double first_contact_angle(double radius, double theta_from) const override;
  /// An upper bound on g over the points within `excursion` of the point at distance r on the arc:
  /// ρ ≤ r + δ and φ within asin(δ/r) of the arc bound ρ − R(φ); w ≥ w_min turns a negative bound on
  /// ρ − R into one on g.
  double max_gap_on_arc(double radius, double theta_from, double theta_to, double excursion) const override;
  /// Where the clearance is smallest: φ = 0 (every law).
  double deepest_angle() const override { return 0.0; }
  /// The polar angle φ of P about the hub centre [deg], in (−180°, 180°] (the casing is at rest).
  double material_coordinate(const Eigen::Vector2d& position, double t) const override;
  SurfaceCoordinate coordinate() const override;
  nlohmann::json describe() const override;

private:
  /// The smallest clearance over the angles [a, b] (b ≥ a) [m].
  double min_clearance(double a, double b) const;
  double nominal_, c0_, amplitude_;
  int lobes_;
  LobeLaw law_;
  double max_slope_;  // max |c'(φ)| [m/rad]
};

const char* lobe_law_name(LobeLaw law);

}  // namespace rotbeam
