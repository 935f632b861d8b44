#include "rotbeam/brush.hpp"

#include "brush_filament.hpp"

#include "rotbeam/case.hpp"
#include "rotbeam/force_bins.hpp"
#include "rotbeam/job_runner.hpp"
#include "rotbeam/units.hpp"
#include "rotbeam/wear.hpp"

#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <cstdio>
#include <map>
#include <mutex>
#include <utility>

namespace rotbeam {

namespace {

// A standard normal draw truncated to ±3 (redrawn beyond), so scattered lengths and diameters stay
// positive for the accepted scatters (≤ 0.3).
template <class Engine>
double truncated_normal(Engine& engine, boost::random::normal_distribution<double>& normal) {
  for (;;) {
    const double x = normal(engine);
    if (std::abs(x) <= 3.0) return x;
  }
}

// The share of the mean normal force the failed filaments are estimated to carry (BrushSummary::
// missing_force_fraction): each failed filament counted as the finished one of the nearest depth
// fraction (the force of a filament follows its reach first).
double missing_force_fraction(const BrushResult& result) {
  // A filament's mean normal force: its own (interpolated, for a population) or its run's.
  const auto force = [&](const BrushFilament& f) {
    return result.estimates.empty() ? result.distinct[f.group].mean_normal_force_n
                                    : result.estimates[f.index].mean_normal_force_n;
  };
  std::vector<std::pair<double, double>> finished;  // (depth fraction, force), sorted by depth
  std::vector<const BrushFilament*> failed;
  for (const BrushFilament& f : result.filaments) {
    const FilamentSteadyState& d = result.distinct[f.group];
    if (!d.reaches || !(f.depth_fraction > 0.0)) continue;
    if (d.ran)
      finished.emplace_back(f.depth_fraction, force(f));
    else
      failed.push_back(&f);
  }
  if (failed.empty()) return 0.0;
  if (finished.empty()) return NAN;
  std::stable_sort(finished.begin(), finished.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  double total = 0, missing = 0;
  for (const auto& [depth, f] : finished) total += f;
  for (const BrushFilament* f : failed) {
    // The finished filament of the nearest depth fraction (the first of equals).
    auto it = std::lower_bound(finished.begin(), finished.end(), f->depth_fraction,
                               [](const auto& a, double v) { return a.first < v; });
    if (it == finished.end() ||
        (it != finished.begin() && f->depth_fraction - std::prev(it)->first <= it->first - f->depth_fraction)) {
      --it;
      while (it != finished.begin() && std::prev(it)->first == it->first) --it;
    }
    missing += it->second;
  }
  return missing + total > 0 ? missing / (missing + total) : 0.0;
}

// The nominal filament's configuration without [brush]: what the surface's coordinate is built from.
Config config_for_coordinate(const Config& config) {
  Config c = config;
  c.brush.reset();
  return c;
}

}  // namespace

std::vector<BrushFilament> brush_filaments(const Config& config) {
  if (!config.brush) throw ConfigError("brush: the configuration has no [brush] section");
  const BrushSettings& b = *config.brush;
  boost::random::mt19937_64 engine(b.seed);
  boost::random::normal_distribution<double> normal(0.0, 1.0);
  const double l0 = config.beam.length_m, d0 = config.beam.diameter_m, p0 = config.surface.depth_fraction;
  std::vector<BrushFilament> out;
  out.reserve(static_cast<std::size_t>(b.filaments) * b.rows);
  std::map<std::pair<double, double>, int> groups;
  for (int r = 0; r < b.rows; ++r)
    for (int k = 0; k < b.filaments; ++k) {
      BrushFilament f;
      f.index = static_cast<int>(out.size());
      f.row = r;
      f.position = k;
      const double jitter = truncated_normal(engine, normal);
      const double dl = truncated_normal(engine, normal);
      const double dd = truncated_normal(engine, normal);
      f.phase_deg = 360.0 * k / b.filaments + r * b.row_phase_deg + b.phase_jitter_deg * jitter;
      f.length_m = b.length_scatter > 0.0 ? l0 * (1.0 + b.length_scatter * dl) : l0;
      f.diameter_m = b.diameter_scatter > 0.0 ? d0 * (1.0 + b.diameter_scatter * dd) : d0;
      f.depth_fraction = f.length_m == l0 ? p0 : (f.length_m - l0 + p0 * l0) / f.length_m;
      const auto key = std::make_pair(f.length_m, f.diameter_m);
      const auto it = groups.find(key);
      f.group = it != groups.end() ? it->second : static_cast<int>(groups.size());
      if (it == groups.end()) groups.emplace(key, f.group);
      out.push_back(f);
    }
  return out;
}

std::vector<Config> brush_filament_configs(const Config& config, const std::vector<BrushFilament>& filaments) {
  int group_count = 0;
  for (const BrushFilament& f : filaments) group_count = std::max(group_count, f.group + 1);
  std::vector<Config> configs(group_count);
  std::vector<char> done(group_count, 0);
  for (const BrushFilament& f : filaments) {
    if (done[f.group] || !(f.depth_fraction > 0.0)) continue;
    done[f.group] = 1;
    try {
      configs[f.group] = detail::filament_config(config, f);
    } catch (const ConfigError& e) {
      char what[200];
      std::snprintf(what, sizeof what,
                    "brush: filament %d (L = %.6g m, D = %.6g m, depth fraction %.6g) drawn from the scatter: ",
                    f.index + 1, f.length_m, f.diameter_m, f.depth_fraction);
      throw ConfigError(what + std::string(e.what()));
    }
  }
  return configs;
}

BrushResult run_brush(const Config& config, const BrushOptions& options) {
  if (config.brush && config.brush->method == BrushMethod::population) return detail::run_brush_population(config, options);
  const double start = detail::clock_s();
  BrushResult result;
  result.filaments = brush_filaments(config);
  int group_count = 0;
  for (const BrushFilament& f : result.filaments) group_count = std::max(group_count, f.group + 1);
  std::vector<const BrushFilament*> representative(group_count, nullptr);
  std::vector<std::vector<const BrushFilament*>> copies(group_count);
  for (const BrushFilament& f : result.filaments) {
    if (!representative[f.group]) representative[f.group] = &f;
    copies[f.group].push_back(&f);
  }
  result.distinct.resize(group_count);
  result.run.resize(group_count);
  std::vector<int> todo;  // groups whose tip reaches the surface
  for (int g = 0; g < group_count; ++g) {
    const BrushFilament& f = *representative[g];
    const double n = static_cast<double>(copies[g].size());
    result.run[g] = RunFilament{f.length_m, f.diameter_m, f.depth_fraction, n, static_cast<int>(copies[g].size())};
    if (f.depth_fraction > 0.0)
      todo.push_back(g);
    else
      result.distinct[g].reaches = false;
  }
  const std::vector<Config> configs = brush_filament_configs(config, result.filaments);
  const double omega = rad_per_s_from_rpm(config.beam.speed_rpm);
  ForceBins total(config.simulation.bin_deg, omega), profile(config.simulation.bin_deg, omega);
  // Each group's bins are summed into the total in group order, whatever order the groups finish
  // in, so the result does not depend on the thread count.
  std::mutex mutex;
  std::map<int, std::pair<ForceBins, ForceBins>> finished_bins;
  std::size_t next_to_merge = 0;
  BrushProgress progress;
  progress.total = static_cast<int>(todo.size());
  JobRunnerOptions runner;
  runner.threads = options.threads;
  runner.stop = options.stop;
  run_jobs(
      todo.size(),
      [&](std::size_t j) {
        const int g = todo[j];
        ForceBins bins(config.simulation.bin_deg, omega), own(config.simulation.bin_deg, omega);
        detail::FilamentOrbit orbit = detail::run_filament_orbit(configs[g], options.stop);
        // Its deliveries over the orbit go into the workpiece's bins once per copy, shifted by the
        // copy's phase and weighted 1/m, and into the profile at the filament's own angle, weighted
        // (copies)/m.
        for (const BrushFilament* f : copies[g])
          for (const MomentumDelivery& d : orbit.deliveries) bins.add(d, f->phase_deg, orbit.weight);
        for (const MomentumDelivery& d : orbit.deliveries)
          own.add(d, 0.0, orbit.weight * static_cast<double>(copies[g].size()));
        std::lock_guard<std::mutex> lock(mutex);
        result.distinct[g] = std::move(orbit.state);
        finished_bins.emplace(static_cast<int>(j), std::make_pair(std::move(bins), std::move(own)));
        while (next_to_merge < todo.size()) {
          const auto it = finished_bins.find(static_cast<int>(next_to_merge));
          if (it == finished_bins.end()) break;
          total.merge(it->second.first);
          profile.merge(it->second.second);
          finished_bins.erase(it);
          ++next_to_merge;
        }
        ++progress.finished;
        progress.elapsed_s = detail::clock_s() - start;
        progress.eta_s = progress.elapsed_s / progress.finished * (progress.total - progress.finished);
        if (options.on_progress) options.on_progress(progress);
      },
      runner);
  detail::finish_brush(result, config, total, profile, start);
  return result;
}

namespace detail {

void finish_brush(BrushResult& result, const Config& config, const ForceBins& total, const ForceBins& profile,
                  double start_s) {
  const double omega = rad_per_s_from_rpm(config.beam.speed_rpm);
  {
    const SurfaceCoordinate k = build_case(config_for_coordinate(config)).surface->coordinate();
    result.wear_coordinate = k.name;
    result.wear_coordinate_unit = k.unit;
    result.wear_metres_per_unit = k.metres_per_unit;
    result.wear_period = k.period;
  }
  result.workpiece = total.full_table();
  result.profile = profile.full_table();
  // The mean filament: the sum at the filaments' own angles over their number.
  const double per = 1.0 / static_cast<double>(std::max<std::size_t>(1, result.filaments.size()));
  for (ForceBin& b : result.profile) {
    b.normal_impulse_n_s *= per;
    b.tangential_impulse_n_s *= per;
    b.mean_normal_force_n *= per;
    b.mean_tangential_force_n *= per;
    b.hub_angular_impulse_n_m_s *= per;
    b.mean_hub_torque_n_m *= per;
  }

  BrushSummary& s = result.summary;
  s.method = config.brush ? config.brush->method : BrushMethod::filaments;
  s.filaments = static_cast<int>(result.filaments.size());
  s.distinct_filaments = static_cast<int>(result.distinct.size());
  s.bin_deg = config.simulation.bin_deg;
  s.revolution_period_s = 2.0 * M_PI / omega;
  // Counts by filament (each as its distinct filament, or its nearest representative) …
  for (const BrushFilament& f : result.filaments) {
    const FilamentSteadyState& d = result.distinct[f.group];
    if (!d.reaches) continue;
    ++s.reaching;
    if (!d.ran) {
      ++s.failed;
      s.failed_indices.push_back(f.index);
      if (s.failed_filament < 0) {
        s.failed_filament = f.index;
        if (d.failure)
          s.failure = d.failure;
        else if (d.error.empty())  // never started: the stop came first
          s.failure = NumericalFailure{FailureKind::interrupted, 0.0, 0.0, "not run (interrupted)"};
      }
      if (!d.error.empty() && s.error.empty()) s.error = "filament " + std::to_string(f.index + 1) + ": " + d.error;
      continue;
    }
    (d.steady ? s.steady : s.not_steady) += 1;
  }
  // … and sums by the filaments run, each weighted by the filaments it stands for.
  std::vector<std::vector<WearBin>> wear_profiles;
  std::vector<double> wear_weights;
  for (std::size_t g = 0; g < result.distinct.size(); ++g) {
    const FilamentSteadyState& d = result.distinct[g];
    const double w = result.run[g].weight;
    if (!d.reaches || !d.ran || !(w > 0.0)) continue;
    s.max_tip_deflection_ratio = std::max(s.max_tip_deflection_ratio, d.max_tip_deflection_ratio);
    if (static_cast<int>(d.validity) > static_cast<int>(s.validity)) s.validity = d.validity;
    s.mean_normal_force_n += w * d.mean_normal_force_n;
    s.mean_tangential_force_n += w * d.mean_tangential_force_n;
    s.mean_hub_torque_n_m += w * d.mean_hub_torque_n_m;
    for (std::size_t k = 0; k < kLedgerTermCount; ++k) s.ledger.value[k] += w * d.ledger.value[k];
    s.ledger.energy_change_j += w * d.ledger.energy_change_j;
    s.ledger_residual_max_j += w * d.ledger_residual_max_j;
    if (!d.wear_profile.empty()) {
      wear_profiles.push_back(d.wear_profile);
      wear_weights.push_back(w);
    }
    if (std::isfinite(d.first_contact_deg)) {
      s.contact_zone_from_deg = std::isnan(s.contact_zone_from_deg) ? d.first_contact_deg
                                                                     : std::min(s.contact_zone_from_deg, d.first_contact_deg);
      s.contact_zone_to_deg = std::isnan(s.contact_zone_to_deg) ? d.last_contact_deg
                                                                 : std::max(s.contact_zone_to_deg, d.last_contact_deg);
    }
  }
  s.mean_hub_power_w = s.mean_hub_torque_n_m * omega;
  s.missing_force_fraction = missing_force_fraction(result);
  // The spread between seeds and the roll-up, filament by filament (the population's interpolated values).
  {
    const bool estimated = !result.estimates.empty();
    double sum_n = 0, sum_nn = 0, sum_t = 0, sum_tt = 0;
    int counted = 0;
    const double barely = 0.25 * config.surface.depth_fraction;
    for (const BrushFilament& f : result.filaments) {
      const FilamentSteadyState& d = result.distinct[f.group];
      if (d.reaches && !d.ran) continue;  // failed: neither value nor spread
      const bool reaches = f.depth_fraction > 0.0;
      const double n = !reaches ? 0.0 : estimated ? result.estimates[f.index].mean_normal_force_n : d.mean_normal_force_n;
      const double t = !reaches ? 0.0 : estimated ? result.estimates[f.index].mean_hub_torque_n_m : d.mean_hub_torque_n_m;
      sum_n += n, sum_nn += n * n, sum_t += t, sum_tt += t * t;
      ++counted;
      if (!reaches) continue;
      s.at_edge_of_model += d.validity == Validity::edge;
      s.outside_model += d.validity == Validity::outside;
      s.barely_reaching += f.depth_fraction < barely;
    }
    if (counted > 1) {
      const double k = counted;
      const double var_n = std::max(0.0, (sum_nn - sum_n * sum_n / k) / (k - 1));
      const double var_t = std::max(0.0, (sum_tt - sum_t * sum_t / k) / (k - 1));
      s.seed_spread_normal_force = sum_n != 0.0 ? std::sqrt(k * var_n) / std::abs(sum_n) : 0.0;
      s.seed_spread_hub_torque = sum_t != 0.0 ? std::sqrt(k * var_t) / std::abs(sum_t) : 0.0;
    }
  }
  // The wear along the surface: every finished filament's profile, summed (docs/wear.md).
  result.wear_profile = rebin(wear_profiles, wear_weights, config.simulation.wear_profile_bins, result.wear_period);
  if (std::isfinite(s.contact_zone_from_deg)) s.contact_zone_deg = s.contact_zone_to_deg - s.contact_zone_from_deg;
  double along_min = INFINITY, along_max = -INFINITY;
  for (std::size_t g = 0; g < result.distinct.size(); ++g) {
    const FilamentSteadyState& d = result.distinct[g];
    if (d.ran && result.run[g].weight > 0.0 && std::isfinite(d.along_min_m)) {
      along_min = std::min(along_min, d.along_min_m);
      along_max = std::max(along_max, d.along_max_m);
    }
  }
  if (along_max >= along_min) s.contact_zone_width_m = along_max - along_min;
  const BinnedForcePeaks peaks = total.peaks();
  s.peak_normal_force_n = peaks.peak_normal_force_n;
  s.peak_tangential_force_n = peaks.peak_tangential_force_n;
  s.peak_normal_at_deg = peaks.peak_normal_at_deg;

  const BeamParameters& beam = config.beam;
  const double area = M_PI * beam.diameter_m * beam.diameter_m / 4.0;
  const double ei = beam.youngs_modulus_pa * M_PI * std::pow(beam.diameter_m, 4) / 64.0;
  const double l = beam.length_m;
  const double omega1 = 1.8751040687119611 * 1.8751040687119611 * std::sqrt(ei / (beam.density_kg_m3 * area * std::pow(l, 4)));
  s.depth_ratio = config.surface.depth_fraction;
  s.speed_ratio = omega / omega1;
  const double static_force = 3.0 * ei * config.surface.depth_fraction * l / (l * l * l);
  s.force_ratio = s.filaments > 0 ? s.mean_normal_force_n / s.filaments / static_force : 0.0;
  if (s.reaching > 0 && s.steady + s.not_steady == 0) {
    // Every filament that reaches the surface failed or was not run: the brush has no force, torque,
    // power or contact zone to report (NaN, null in summary.json, empty in sweep.csv), not zeros.
    for (double* v : {&s.mean_normal_force_n, &s.mean_tangential_force_n, &s.peak_normal_force_n,
                      &s.peak_tangential_force_n, &s.peak_normal_at_deg, &s.mean_hub_torque_n_m, &s.mean_hub_power_w,
                      &s.contact_zone_deg, &s.contact_zone_width_m, &s.force_ratio, &s.ledger_residual_max_j})
      *v = NAN;
    s.ledger.value.fill(NAN);
    s.ledger.energy_change_j = NAN;
  }
  if (s.not_steady > 0)
    s.warnings.push_back(std::to_string(s.not_steady) + " of " + std::to_string(s.reaching) +
                         " filaments did not reach their steady state within simulation.revolutions = " +
                         std::to_string(config.simulation.revolutions) +
                         ": their last revolution is used (add beam.damping_ratio, or raise simulation.revolutions)");
  if (s.validity != Validity::within) {
    int beyond = 0;
    for (const BrushFilament& f : result.filaments) {
      const FilamentSteadyState& d = result.distinct[f.group];
      beyond += d.ran && d.validity != Validity::within;
    }
    std::ostringstream w;
    w.precision(3);
    w << beyond << " of " << s.steady + s.not_steady << " filaments bend past simulation.deflection_warning_ratio = "
      << config.simulation.deflection_warning_ratio << " of their length (max |y_t|/L = " << s.max_tip_deflection_ratio
      << ")"
      << (s.validity == Validity::outside ? ", some outside the model (their results are not physical)"
                                          : ", at the edge of the quadratic foreshortening")
      << " (docs/model.md §10): run the brush with beam.theory = \"elastica\" to see the difference";
    s.warnings.push_back(w.str());
  }
  if (s.reaching < s.filaments)
    s.warnings.push_back(std::to_string(s.filaments - s.reaching) +
                         " filaments are too short to reach the surface and deliver nothing");
  s.wall_time_s = clock_s() - start_s;
}

}  // namespace detail

}  // namespace rotbeam
