#include "rotbeam/force_bins.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rotbeam {

ForceBins::ForceBins(double bin_deg, double omega) : bin_deg_(bin_deg), omega_(omega) {
  if (!(bin_deg > 0.0) || !(omega > 0.0)) throw std::invalid_argument("ForceBins: bin_deg and ω must be positive");
  count_ = static_cast<int>(std::ceil(360.0 / bin_deg - 1e-9));
  normal_.assign(count_, 0.0);
  tangential_.assign(count_, 0.0);
  hub_.assign(count_, 0.0);
  impacts_.assign(count_, 0.0);
  touched_.assign(count_, 0);
}

void ForceBins::clear() {
  std::fill(normal_.begin(), normal_.end(), 0.0);
  std::fill(tangential_.begin(), tangential_.end(), 0.0);
  std::fill(hub_.begin(), hub_.end(), 0.0);
  std::fill(impacts_.begin(), impacts_.end(), 0.0);
  std::fill(touched_.begin(), touched_.end(), 0);
}

int ForceBins::index(double angle_deg) const {
  // Bin k covers [−180° + k·w, −180° + (k + 1)·w); angles are taken mod 360°.
  double a = std::fmod(angle_deg + 180.0, 360.0);
  if (a < 0.0) a += 360.0;
  return std::min(static_cast<int>(a / bin_deg_), count_ - 1);
}

double ForceBins::bin_width_deg(int k) const { return k == count_ - 1 ? 360.0 - k * bin_deg_ : bin_deg_; }

double ForceBins::bin_duration_s(int k) const { return bin_width_deg(k) * M_PI / 180.0 / omega_; }

void ForceBins::add_impulse(double angle_deg, double normal_n_s, double tangential_n_s) {
  const int k = index(angle_deg);
  normal_[k] += normal_n_s;
  tangential_[k] += tangential_n_s;
  ++impacts_[k];
  touched_[k] = 1;
}

void ForceBins::add_impacts(double angle_deg, double count) {
  if (!(count > 0.0)) return;
  const int k = index(angle_deg);
  impacts_[k] += count;
  touched_[k] = 1;
}

void ForceBins::add_spread(double from_deg, double span_deg, double normal_n_s, double tangential_n_s,
                           double hub_angular_n_m_s) {
  if (!(span_deg > 0.0)) {
    const int k = index(from_deg);
    normal_[k] += normal_n_s;
    tangential_[k] += tangential_n_s;
    hub_[k] += hub_angular_n_m_s;
    touched_[k] = 1;
    return;
  }
  // Walk the bins the span crosses, giving each its share of the angle (the last bin what is left,
  // so that the momentum is kept to the last bit).
  double a = from_deg, normal_left = normal_n_s, tangential_left = tangential_n_s, hub_left = hub_angular_n_m_s;
  const double end = from_deg + span_deg;
  while (a < end) {
    double wrapped = std::fmod(a + 180.0, 360.0);  // a's place in [0°, 360°) from −180°
    if (wrapped < 0.0) wrapped += 360.0;
    const int k = index(a);
    const double upper = k == count_ - 1 ? 360.0 : (k + 1) * bin_deg_;  // the bin's end, same origin
    const double b = std::min(end, std::max(a + (upper - wrapped), std::nextafter(a, INFINITY)));
    const double share = (b - a) / span_deg;
    const double normal = b < end ? share * normal_n_s : normal_left;
    const double tangential = b < end ? share * tangential_n_s : tangential_left;
    const double hub = b < end ? share * hub_angular_n_m_s : hub_left;
    normal_[k] += normal;
    tangential_[k] += tangential;
    hub_[k] += hub;
    normal_left -= normal;
    tangential_left -= tangential;
    hub_left -= hub;
    touched_[k] = 1;
    a = b;
  }
}

void ForceBins::add(const MomentumDelivery& d, double shift_deg, double weight) {
  const double at = d.from_deg - shift_deg;
  if (d.impact) {
    const int k = index(at);
    normal_[k] += weight * d.normal_n_s;
    tangential_[k] += weight * d.tangential_n_s;
    hub_[k] += weight * d.hub_angular_impulse_n_m_s;
    impacts_[k] += weight;
    touched_[k] = 1;
    return;
  }
  add_spread(at, d.span_deg, weight * d.normal_n_s, weight * d.tangential_n_s, weight * d.hub_angular_impulse_n_m_s);
}

void ForceBins::merge(const ForceBins& other) {
  if (other.count_ != count_ || other.bin_deg_ != bin_deg_ || other.omega_ != omega_)
    throw std::invalid_argument("ForceBins::merge: the bins differ");
  for (int k = 0; k < count_; ++k) {
    normal_[k] += other.normal_[k];
    tangential_[k] += other.tangential_[k];
    hub_[k] += other.hub_[k];
    impacts_[k] += other.impacts_[k];
    touched_[k] |= other.touched_[k];
  }
}

ForceBin ForceBins::bin(int k) const {
  const double duration = bin_duration_s(k);
  ForceBin b;
  b.from_deg = -180.0 + k * bin_deg_;
  b.to_deg = b.from_deg + bin_width_deg(k);
  b.normal_impulse_n_s = normal_[k];
  b.tangential_impulse_n_s = tangential_[k];
  b.mean_normal_force_n = normal_[k] / duration;
  b.mean_tangential_force_n = tangential_[k] / duration;
  b.impacts = static_cast<int>(std::lround(impacts_[k]));
  b.hub_angular_impulse_n_m_s = hub_[k];
  b.mean_hub_torque_n_m = hub_[k] / duration;
  return b;
}

std::vector<ForceBin> ForceBins::full_table() const {
  std::vector<ForceBin> out;
  out.reserve(count_);
  for (int k = 0; k < count_; ++k) out.push_back(bin(k));
  return out;
}

std::vector<ForceBin> ForceBins::table() const {
  std::vector<ForceBin> out;
  int first = -1, last = -1;
  for (int k = 0; k < count_; ++k)
    if (touched_[k]) {
      if (first < 0) first = k;
      last = k;
    }
  if (first < 0) return out;
  out.reserve(last - first + 1);
  for (int k = first; k <= last; ++k) out.push_back(bin(k));
  return out;
}

BinnedForcePeaks ForceBins::peaks() const {
  BinnedForcePeaks p;
  p.bin_deg = bin_deg_;
  p.peak_normal_at_deg = NAN;
  double best = -1.0;
  for (int k = 0; k < count_; ++k) {
    if (!touched_[k]) continue;
    const double duration = bin_duration_s(k);
    if (normal_[k] / duration > best) {
      best = normal_[k] / duration;
      p.peak_normal_at_deg = -180.0 + k * bin_deg_ + 0.5 * bin_width_deg(k);
    }
    p.peak_tangential_force_n = std::max(p.peak_tangential_force_n, std::abs(tangential_[k]) / duration);
  }
  if (best >= 0.0) p.peak_normal_force_n = best;
  return p;
}

}  // namespace rotbeam
