#include "rotbeam/casing.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rotbeam {

namespace {
constexpr double kBenchmarkWidth = 0.15;  // the benchmark law's lobe width (fraction of π)
}  // namespace

const char* lobe_law_name(LobeLaw law) { return law == LobeLaw::benchmark ? "benchmark" : "cosine"; }

Casing::Casing(double nominal_radius_m, double clearance_m, int lobes, double lobe_amplitude_m, LobeLaw law)
    : nominal_(nominal_radius_m), c0_(clearance_m), amplitude_(lobes > 0 ? lobe_amplitude_m : 0.0), lobes_(lobes),
      law_(law) {
  if (law_ == LobeLaw::benchmark && lobes_ != 2)
    throw std::invalid_argument("the benchmark lobe law has two lobes, got " + std::to_string(lobes_));
  const double beta = 1.0 / (kBenchmarkWidth * M_PI);
  max_slope_ = law_ == LobeLaw::benchmark ? 2.0 * std::abs(amplitude_) * beta * std::sqrt(2.0 / std::exp(1.0))
                                          : std::abs(amplitude_) * lobes_;
}

Casing::Clearance Casing::clearance(double phi) const {
  Clearance c;
  c.value = c0_;
  if (amplitude_ == 0.0) return c;
  if (law_ == LobeLaw::cosine) {
    const double k = lobes_, s = std::sin(k * phi), co = std::cos(k * phi);
    c.value -= amplitude_ * co;
    c.d1 = amplitude_ * k * s;
    c.d2 = amplitude_ * k * k * co;
    c.d3 = -amplitude_ * k * k * k * s;
    return c;
  }
  // Hermite's derivatives of e^(−u²): −2u e, (4u² − 2) e, (12u − 8u³) e; du/dφ = β.
  const double shifted = phi + 0.5 * M_PI;
  const double m = shifted - M_PI * std::floor(shifted / M_PI);
  const double beta = 1.0 / (kBenchmarkWidth * M_PI);
  const double u = (m / M_PI - 0.5) / kBenchmarkWidth, e = std::exp(-u * u), a2 = 2.0 * amplitude_;
  c.value -= a2 * e;
  c.d1 = -a2 * beta * (-2.0 * u) * e;
  c.d2 = -a2 * beta * beta * (4.0 * u * u - 2.0) * e;
  c.d3 = -a2 * beta * beta * beta * (12.0 * u - 8.0 * u * u * u) * e;
  return c;
}

GapField Casing::field(const Eigen::Vector2d& p) const {
  const double rho = p.norm(), phi = std::atan2(p.y(), p.x());
  const Clearance c = clearance(phi);
  const double r1 = c.d1, r2 = c.d2, r3 = c.d3;  // R' = c', R'' = c'', R''' = c'''
  const double h = rho - (nominal_ + c.value);
  const double s2 = rho * rho + r1 * r1, s = std::sqrt(s2), s3 = s2 * s, s5 = s3 * s2;
  const double w = rho / s;
  const double w_r = r1 * r1 / s3, w_p = -rho * r1 * r2 / s3;
  const double w_rr = -3.0 * r1 * r1 * rho / s5;
  const double w_rp = 2.0 * r1 * r2 / s3 - 3.0 * r1 * r1 * r1 * r2 / s5;
  const double w_pp = -rho * (r2 * r2 + r1 * r3) / s3 + 3.0 * rho * r1 * r1 * r2 * r2 / s5;
  const double g_r = w + h * w_r, g_p = -r1 * w + h * w_p;
  const double g_rr = 2.0 * w_r + h * w_rr;
  const double g_rp = w_p - r1 * w_r + h * w_rp;
  const double g_pp = -r2 * w - 2.0 * r1 * w_p + h * w_pp;
  const Eigen::Vector2d er = p / rho, ep(-er.y(), er.x());
  GapField f;
  f.value = h * w;
  f.gradient = g_r * er + (g_p / rho) * ep;
  const double mixed = g_rp / rho - g_p / (rho * rho);
  f.hessian = g_rr * er * er.transpose() + mixed * (er * ep.transpose() + ep * er.transpose()) +
              (g_pp / (rho * rho) + g_r / rho) * ep * ep.transpose();
  return f;
}

double Casing::material_coordinate(const Eigen::Vector2d& p, double) const {
  return std::atan2(p.y(), p.x()) * 180.0 / M_PI;
}

SurfaceCoordinate Casing::coordinate() const {
  return {"angle around the casing", "deg", (nominal_ + c0_) * M_PI / 180.0, 360.0};
}

double Casing::gap(const Eigen::Vector2d& position, double) const { return field(position).value; }

void Casing::contact_geometry(TipKinematics& k) const { fill_contact_geometry(field({k.X, k.Y}), SurfaceMotion{}, k); }

double Casing::first_contact_angle(double r, double theta_from) const {
  const double offset = r - nominal_;
  const auto f = [&](double phi) { return offset - clearance(phi).value; };
  if (amplitude_ == 0.0) return NAN;  // r − R is constant: never crossed
  // The deepest angles are on the grid, so a lobe that reaches r shows a non-negative sample.
  const int k = lobes_;
  const double lobe = 2.0 * M_PI / k, step = lobe / 64.0;  // lobes of the benchmark law: every 180°
  const double first_deepest = deepest_angle() + lobe * std::ceil((theta_from - deepest_angle()) / lobe);
  double a = theta_from, fa = f(a);
  for (int i = 1; i <= 64 * k + 1; ++i) {
    double b = theta_from + i * step;
    // Put the deepest angle between a and b on the grid.
    const double deepest = first_deepest + lobe * std::floor((b - first_deepest) / lobe);
    if (deepest > a && deepest < b) b = deepest, --i;
    const double fb = f(b);
    if (fa < 0.0 && fb >= 0.0) {
      for (int j = 0; j < 200; ++j) {
        const double mid = 0.5 * (a + b);
        if (!(mid > a && mid < b)) break;
        (f(mid) >= 0.0 ? b : a) = mid;
      }
      return b;
    }
    a = b, fa = fb;
  }
  return NAN;
}

double Casing::min_clearance(double a, double b) const {
  if (amplitude_ == 0.0) return c0_;
  const double lobe = 2.0 * M_PI / lobes_;
  const double first_deepest = deepest_angle() + lobe * std::ceil((a - deepest_angle()) / lobe);
  double smallest = std::min(clearance(a).value, clearance(b).value);
  if (first_deepest <= b) smallest = std::min(smallest, clearance(first_deepest).value);
  return smallest;
}

double Casing::max_gap_on_arc(double r, double theta_from, double theta_to, double excursion) const {
  const double widen = excursion < r ? std::asin(excursion / r) : M_PI;
  const double cmin = min_clearance(theta_from - widen, theta_to + widen);
  const double bound = r + excursion - (nominal_ + cmin);
  if (bound >= 0.0) return bound;  // g ≤ ρ − R where that is ≥ 0 (w ≤ 1)
  const double rho_min = r - excursion;
  if (!(rho_min > 0.0)) return 0.0;
  return bound * rho_min / std::hypot(rho_min, max_slope_);  // g = (ρ − R) w ≤ (ρ − R) w_min
}

nlohmann::json Casing::describe() const {
  nlohmann::json j = {{"shape", "casing"}, {"radius_m", nominal_ + c0_}, {"nominal_radius_m", nominal_},
                      {"clearance_m", c0_},  {"lobes", lobes_},          {"lobe_amplitude_m", amplitude_}};
  if (lobes_ > 0) j["lobe_law"] = lobe_law_name(law_);
  return j;
}

}  // namespace rotbeam
