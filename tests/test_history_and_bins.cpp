// What a pass records beside its events (docs/model.md §7): the rigid turn drawn row by row, rows on the
// near-surface grid taken from the stepper's dense output, and the force on the surface in
// hub-angle bins (force_bins.hpp), each checked against an independent route.
#include "rotbeam/case.hpp"
#include "rotbeam/config.hpp"
#include "rotbeam/force_bins.hpp"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <map>
#include <numeric>

using namespace rotbeam;

namespace {
PassResult run(const std::vector<std::string>& overrides) {
  const Case c = build_case(load_config(std::nullopt, overrides));
  PassResult r = run_case(c, {});
  EXPECT_FALSE(r.failure) << r.failure->message;
  return r;
}
double sum_normal(const std::vector<ForceBin>& bins) {
  return std::accumulate(bins.begin(), bins.end(), 0.0, [](double s, const ForceBin& b) { return s + b.normal_impulse_n_s; });
}
}  // namespace

TEST(ForceBins, SpreadMomentumIsConservedAndSharedByAngle) {
  // 0.5° bins at ω = 10 rad/s: a bin lasts 0.5·π/180/10 s.
  ForceBins bins(0.5, 10.0);
  const double duration = 0.5 * M_PI / 180.0 / 10.0;
  bins.add_spread(-0.25, 1.0, 4.0, -2.0);  // [−0.25°, 0.75°): a quarter, a half, a quarter
  const std::vector<ForceBin> t = bins.table();
  ASSERT_EQ(t.size(), 3u);
  EXPECT_DOUBLE_EQ(t[0].from_deg, -0.5);
  EXPECT_NEAR(t[0].normal_impulse_n_s, 1.0, 1e-14);
  EXPECT_NEAR(t[1].normal_impulse_n_s, 2.0, 1e-14);
  EXPECT_NEAR(t[2].normal_impulse_n_s, 1.0, 1e-14);
  EXPECT_NEAR(t[1].tangential_impulse_n_s, -1.0, 1e-14);
  EXPECT_NEAR(t[1].mean_normal_force_n, 2.0 / duration, 1e-9);
  // Across ±180°: the share beyond 180° lands at −180°, and the table spans the whole turn.
  ForceBins wrap(1.0, 10.0);
  wrap.add_spread(179.5, 1.0, 2.0, 0.0);
  wrap.add_impulse(-0.2, 3.0, 0.5);
  const std::vector<ForceBin> w = wrap.table();
  EXPECT_NEAR(sum_normal(w), 5.0, 1e-14);
  EXPECT_DOUBLE_EQ(w.front().from_deg, -180.0);
  EXPECT_NEAR(w.front().normal_impulse_n_s, 1.0, 1e-14);
  EXPECT_DOUBLE_EQ(w.back().to_deg, 180.0);
  const BinnedForcePeaks p = wrap.peaks();
  EXPECT_NEAR(p.peak_normal_force_n, 3.0 / (M_PI / 180.0 / 10.0), 1e-9);
  EXPECT_DOUBLE_EQ(p.peak_normal_at_deg, -0.5);
  EXPECT_EQ(w[179].impacts, 1);  // [−1°, 0°)
  // A width that does not divide 360°: the last bin is shorter and still receives its share.
  ForceBins odd(0.7, 10.0);
  odd.add_spread(179.9, 0.2, 1.0, 0.0);
  EXPECT_NEAR(sum_normal(odd.table()), 1.0, 1e-14);
  ForceBins last(0.7, 10.0);  // 514 bins of 0.7° and one of 0.2°, [179.8°, 180°)
  last.add_spread(179.85, 0.1, 1.0, 0.0);
  const std::vector<ForceBin> lt = last.table();
  ASSERT_EQ(lt.size(), 1u);
  EXPECT_NEAR(lt[0].to_deg - lt[0].from_deg, 0.2, 1e-9);
  EXPECT_NEAR(lt[0].mean_normal_force_n, 1.0 / (0.2 * M_PI / 180.0 / 10.0), 1e-6);
  EXPECT_NEAR(last.peaks().peak_normal_at_deg, 179.9, 1e-9);
  bins.clear();
  EXPECT_TRUE(bins.table().empty());
  EXPECT_TRUE(std::isnan(bins.peaks().peak_normal_at_deg));
}

TEST(ForceBins, APassesBinsHoldItsImpulseAndTheMeanForceOfItsRows) {
  // Over passes with sustained contact, with impacts only, with Coulomb impacts and over the last
  // revolution of a run: the bins' momentum sums to the summary's normal impulse (the two are
  // accumulated separately) and their impacts to its impacts. Inside a sustained-contact episode a
  // bin's mean force equals ∫F_n dt / its duration from a history sampled at every step (trapezoid;
  // the steps are ~1e-3 of a bin, so 1e-3 relative); its tangential force is μ F_n against the
  // tip's slip, as −∫F_t dt of the rows says.
  const std::vector<std::vector<std::string>> cases = {
      {"output.interval_s=0"},
      {"hub.speed_rpm=3000", "output.interval_s=0"},
      {"hub.speed_rpm=1000", "surface.friction=0.1", "impact.restitution=0.3", "output.interval_s=0"},
      {"hub.speed_rpm=800", "impact.friction=\"coulomb\"", "output.interval_s=0", "output.bin_deg=0.25"},
  };
  for (const auto& overrides : cases) {
    SCOPED_TRACE(overrides.front());
    const Config config = load_config(std::nullopt, overrides);
    const Case c = build_case(config);
    const PassResult r = run_case(c, {});
    ASSERT_FALSE(r.failure) << r.failure->message;
    const PassSummary& s = r.summary;
    ASSERT_FALSE(r.force_bins.empty());
    EXPECT_NEAR(sum_normal(r.force_bins), s.ledger[LedgerTerm::normal_impulse], 1e-12 * s.ledger[LedgerTerm::normal_impulse]);
    int impacts = 0;
    for (const ForceBin& b : r.force_bins) impacts += b.impacts;
    EXPECT_EQ(impacts, s.impacts);
    EXPECT_DOUBLE_EQ(s.binned_force.bin_deg, config.simulation.bin_deg);
    double peak = 0;
    for (const ForceBin& b : r.force_bins) peak = std::max(peak, b.mean_normal_force_n);
    EXPECT_DOUBLE_EQ(s.binned_force.peak_normal_force_n, peak);
    // Bins wholly inside one sustained-contact episode and holding no impact, against the rows.
    const double omega = c.beam->hub_motion().omega;
    const double bin_s = config.simulation.bin_deg * M_PI / 180.0 / omega;
    int checked = 0;
    for (const ForceBin& b : r.force_bins) {
      if (b.impacts > 0) continue;
      const double t0 = (b.from_deg + 90.0) * M_PI / 180.0 / omega, t1 = t0 + bin_s;  // θ0 = −90°
      bool inside = false;
      for (const ContactInterval& e : s.contact_intervals) inside = inside || (e.t_start < t0 && t1 < e.t_end);
      if (!inside) continue;
      double fn = 0, ft = 0;
      for (std::size_t i = 1; i < r.history.size(); ++i) {
        const HistoryRow &a = r.history[i - 1], &z = r.history[i];
        const double lo = std::max(a.t, t0), hi = std::min(z.t, t1);
        if (!(hi > lo)) continue;
        // Linear between rows, integrated over the part inside the bin.
        const auto at = [&](double t, double va, double vz) { return va + (vz - va) * (t - a.t) / (z.t - a.t); };
        fn += 0.5 * (at(lo, a.normal_force, z.normal_force) + at(hi, a.normal_force, z.normal_force)) * (hi - lo);
        ft += 0.5 * (at(lo, a.friction_force, z.friction_force) + at(hi, a.friction_force, z.friction_force)) * (hi - lo);
      }
      EXPECT_NEAR(b.normal_impulse_n_s, fn, 1e-3 * fn) << "bin from " << b.from_deg << "°";
      EXPECT_NEAR(b.mean_normal_force_n, fn / bin_s, 1e-3 * fn / bin_s) << "bin from " << b.from_deg << "°";
      EXPECT_NEAR(b.tangential_impulse_n_s, -ft, 1e-3 * std::abs(ft) + 1e-15) << "bin from " << b.from_deg << "°";
      ++checked;
    }
    if (s.contact_time_s > 2 * bin_s) EXPECT_GT(checked, 0);
  }
  // Many revolutions: the bins are the last complete revolution's, summing to its impulse.
  const PassResult many = run({"hub.speed_rpm=300", "beam.modes=3", "simulation.revolutions=3", "beam.damping_ratio=0.02"});
  ASSERT_EQ(many.revolutions.size(), 3u);
  EXPECT_NEAR(sum_normal(many.force_bins), many.revolutions.back().ledger[LedgerTerm::normal_impulse],
              1e-12 * many.revolutions.back().ledger[LedgerTerm::normal_impulse]);
}

TEST(History, TheRigidTurnIsDrawnRowByRow) {
  // A rigid start turns the undeformed filament (q = q̇ = 0) from θ0 to the first impact: rows at
  // max(interval, 0.1°) far from the surface and at the near-surface interval within its gap,
  // all with q = 0, in order, the last before the impact; before, only the row at θ0 was written.
  for (const double rpm : {550.0, 3000.0}) {
    const Config config = load_config(std::nullopt, {"hub.speed_rpm=" + std::to_string(rpm)});
    const Case c = build_case(config);
    const PassResult r = run_case(c, {});
    ASSERT_FALSE(r.failure);
    const double omega = c.beam->hub_motion().omega;
    const double t_star = c.beam->time_at(r.summary.first_impact_deg * M_PI / 180.0);
    const double far = std::max(config.simulation.output_interval_s, 0.1 * M_PI / 180.0 / omega);
    const double near = config.simulation.near_surface_interval_s, band = config.simulation.near_surface_gap_m;
    int rigid = 0, near_rows = 0;
    const HistoryRow* previous = nullptr;
    for (const HistoryRow& row : r.history) {
      if (row.t >= t_star) break;
      EXPECT_EQ(row.q.norm() + row.qd.norm(), 0.0) << row.t;
      if (previous) {
        const double spacing = row.t - previous->t;
        EXPECT_GT(spacing, 0.0);
        EXPECT_LE(spacing, (previous->gap > -band ? near : far) * (1 + 1e-9)) << "at θ = " << row.theta * 180 / M_PI;
        if (previous->gap > -band) ++near_rows;
      }
      previous = &row;
      ++rigid;
    }
    EXPECT_GT(rigid, t_star / far * 0.9) << rpm;
    EXPECT_GT(near_rows, 5) << rpm;
    ASSERT_NE(previous, nullptr);
    EXPECT_LT(t_star - previous->t, near * (1 + 1e-9));
  }
}

TEST(History, NearSurfaceRowsLieOnTheTrajectory) {
  // Rows between accepted steps come from the dense output. The reference records every accepted
  // step of a run whose steps are at most 1e-8 s (to θ = −7.5°, past the first bounce); the row
  // nearest in time, moved by its tip velocity to the coarse row's time (an error ≈ ½a·(5e-9 s)²,
  // below 1e-11 m), must agree with every near-surface row of the first bounce (first impact to
  // second, 120 µs) to 1e-9 m: the tip moves at 7 m/s, so a row drawn 0.1 % of h off its time
  // would be 1.4e-8 m off.
  const PassResult coarse = run({}),
                   fine = run({"output.interval_s=0", "output.near_surface_interval_s=0", "simulation.max_step_s=1e-8",
                               "simulation.end_angle_deg=-7.5"});
  std::vector<double> impacts;
  for (const PassEvent& e : coarse.events)
    if (e.kind == EventKind::impact) impacts.push_back(e.t);
  ASSERT_GE(impacts.size(), 2u);
  const double t1 = impacts[0], t2 = impacts[1];
  std::map<double, const HistoryRow*> reference;
  for (const HistoryRow& row : fine.history) reference[row.t] = &row;
  int compared = 0;
  double largest = 0;
  for (const HistoryRow& row : coarse.history) {
    if (!(row.t > t1 && row.t < t2)) continue;
    auto it = reference.lower_bound(row.t);
    if (it == reference.end()) continue;
    if (it != reference.begin() && row.t - std::prev(it)->first < it->first - row.t) --it;
    const HistoryRow& f = *it->second;
    const double dt = row.t - f.t;
    ASSERT_LT(std::abs(dt), 1e-8);
    const double dx = row.x_tip - (f.x_tip + f.vx * dt), dy = row.y_tip - (f.y_tip + f.vy * dt);
    EXPECT_NEAR(dx, 0.0, 1e-9) << row.t;
    EXPECT_NEAR(dy, 0.0, 1e-9) << row.t;
    largest = std::max({largest, std::abs(dx), std::abs(dy)});
    ++compared;
  }
  // 120 µs at 2 µs: about 60 rows.
  EXPECT_GT(compared, 40);
  std::printf("near-surface rows compared: %d, largest tip difference %.3g m\n", compared, largest);
}

TEST(History, RowsOffEventsAreNeverNearDuplicates) {
  // A row written at k·h can leave t/h a hair below k; the next grid time must then be (k + 1)·h,
  // not t again. Over three revolutions (rows at 1e-5 s, and at 2e-6 s near the surface) two rows
  // closer than 1e-8 s must share an event's time (an impact's before/after rows, a separation);
  // before, rows 4.4e-10 s apart appeared where 0.4492/1e-5 rounds to 44919.99999999999.
  const PassResult r = run({"hub.speed_rpm=300", "beam.modes=3", "simulation.revolutions=3", "beam.damping_ratio=0.02",
                            "output.history_revolutions=\"all\""});
  std::vector<double> event_times;
  for (const PassEvent& e : r.events) event_times.push_back(e.t);
  const auto at_event = [&](double t) {
    return std::any_of(event_times.begin(), event_times.end(), [&](double te) { return std::abs(te - t) < 1e-12; });
  };
  int close = 0;
  for (std::size_t i = 1; i < r.history.size(); ++i) {
    const double a = r.history[i - 1].t, b = r.history[i].t;
    EXPECT_GE(b, a) << i;
    if (b - a < 1e-8 && !at_event(a) && !at_event(b)) {
      ++close;
      ADD_FAILURE() << "rows " << i - 1 << " and " << i << " at t = " << a << ", " << b << " s";
      if (close > 5) break;
    }
  }
}
