// Wear and frictional heat (docs/wear.md): Archard's law against its closed form on a steady sliding
// contact, the heat against friction's dissipation on three surfaces with the ledger still closed, an
// impact's heat and load–distance against the closed forms of an impact that slides throughout, the
// profile's sums and its place on the surface, the worn filament's surface kept in place, and the
// slow-time loop's totals against its steps.
#include "rotbeam/brush.hpp"
#include "rotbeam/brush_output.hpp"
#include "rotbeam/case.hpp"
#include "rotbeam/kinematics.hpp"
#include "rotbeam/config.hpp"
#include "rotbeam/pass_output.hpp"
#include "rotbeam/wear.hpp"
#include "rotbeam/wear_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace rotbeam;

namespace {

double profile_load(const std::vector<WearBin>& bins) {
  double s = 0;
  for (const WearBin& b : bins) s += b.sliding_load_n_m;
  return s;
}

double profile_heat(const std::vector<WearBin>& bins) {
  double s = 0;
  for (const WearBin& b : bins) s += b.heat_j;
  return s;
}

// A tip held against a concentric casing 0.1 mm inside its reach, started bent clear of it, with
// heavy damping: it settles into a steady slide all the way round at constant force and speed.
Config steady_slide() {
  return load_config_string("", {"surface.shape=casing", "surface.clearance_m=-1e-4", "beam.damping_ratio=0.3",
                                 "simulation.revolutions=30", "simulation.until_steady=true",
                                 "simulation.multipliers=false", "initial.start=flexible",
                                 "initial.modal_displacement=[0.008,0,0,0,0]", "initial.modal_velocity=[0,0,0,0,0]",
                                 "output.interval_s=1e-4", "wear.profile_bins=36"});
}

}  // namespace

// Archard's law on a contact that slides at constant F_n and slip speed: per revolution the
// load–distance is F_n|V_t|T, the worn volumes k S / H, the heat μ F_n |V_t| T. F_n and V_t are read
// from the last history row in contact (x, y, v_x, v_y: |V_t| = |X V_Y − Y V_X| / ρ on the circle),
// not from the ledger. Tolerance 1e-9: the orbit repeats to the steady test's 1e-8 in the section
// state, and the force and speed are constant along it to the integration's tolerance. The ledger
// still closes to 1e-8 of the hub's work.
TEST(Wear, ArchardsLawOnASteadySlideIsItsClosedForm) {
  const Config config = steady_slide();
  const Case c = build_case(config);
  const PassResult r = run_case(c);
  ASSERT_FALSE(r.failure) << r.failure->message;
  ASSERT_TRUE(r.summary.steady_state.reached);
  ASSERT_TRUE(r.summary.last_revolution);
  const RevolutionRecord& rev = *r.summary.last_revolution;
  ASSERT_EQ(rev.impacts, 0);
  const double T = rev.t_end - rev.t_start;
  ASSERT_NEAR(rev.contact_time_s, T, 1e-12 * T) << "the tip slides the whole revolution";
  const HistoryRow* last = nullptr;
  for (const HistoryRow& h : r.history)
    if (h.phase != Phase::free) last = &h;
  ASSERT_NE(last, nullptr);
  const double rho = std::hypot(last->x_tip, last->y_tip);
  const double slip = std::abs(last->x_tip * last->vy - last->y_tip * last->vx) / rho;
  const double S = last->normal_force * slip * T;
  EXPECT_NEAR(rev.ledger[LedgerTerm::sliding_load], S, 1e-9 * S);
  const double mu = config.contact.friction.mu;
  EXPECT_NEAR(rev.ledger[LedgerTerm::frictional_heat], mu * S, 1e-9 * mu * S);
  EXPECT_NEAR(rev.ledger[LedgerTerm::frictional_heat], -rev.ledger[LedgerTerm::friction_work], 1e-12 * mu * S);
  EXPECT_LE(std::abs(rev.ledger.residual()), 1e-8 * std::abs(rev.ledger[LedgerTerm::hub_work]));

  const WearReport w = wear_report(r, config.wear, *c.surface, config.beam.diameter_m, config.simulation.wear_profile_bins);
  ASSERT_EQ(w.revolutions, 1);
  const WearSettings& k = config.wear;
  const double D = config.beam.diameter_m;
  EXPECT_NEAR(w.amounts.sliding_load_n_m, S, 1e-9 * S);
  EXPECT_NEAR(w.amounts.surface_volume_m3, k.surface_coefficient * S / k.surface_hardness_pa,
              1e-9 * k.surface_coefficient * S / k.surface_hardness_pa);
  EXPECT_NEAR(w.amounts.filament_length_m, k.filament_coefficient * S / k.filament_hardness_pa / (M_PI * D * D / 4),
              1e-9 * w.amounts.filament_length_m);
  EXPECT_NEAR(w.amounts.heat_to_filament_j + w.amounts.heat_to_surface_j, w.amounts.heat_j, 1e-15);
  EXPECT_NEAR(w.amounts.heat_to_filament_j, k.heat_to_filament * w.amounts.heat_j, 1e-15);
  // The tip slides round the whole casing at a constant rate: the profile is flat over the 36 bins of
  // 10° and its removed depth is S k/H over the track's area 2πR·D.
  ASSERT_EQ(w.profile.size(), 36u);
  EXPECT_NEAR(w.profile.back().to - w.profile.front().from, 360.0, 1e-9);
  const double R = config.beam.hub_radius_m + config.beam.length_m + config.surface.clearance_m;
  for (const WearBin& b : w.profile) {
    EXPECT_NEAR(b.sliding_load_n_m, S / 36, 1e-6 * S / 36) << "bin from " << b.from;
    EXPECT_NEAR(removed_depth_m(b, k, w.coordinate, w.track_width_m),
                k.surface_coefficient * S / k.surface_hardness_pa / (2 * M_PI * R * D), 1e-6 * 1e-12 + 1e-6 * k.surface_coefficient * S / k.surface_hardness_pa / (2 * M_PI * R * D));
  }
}

// The heat is where friction's dissipation goes: −friction_work (the slip relative to the surface,
// which on a spinning cylinder is the tip's work through friction less the surface's) on a plane, a
// spinning cylinder (with the hub's sense; and against it, with 1.4 ms of stick and tangential
// impacts) and a lobed casing, plus the heat of the impacts' friction, which the ledger books in impact_loss_j (each
// impact's from events.csv). The ledger closes to 1e-8 of its largest term with the two new terms
// integrated beside it, and the profile's bins sum to the ledger's load–distance and heat. Tolerance
// 1e-9 of the heat (1e-5 with stick, below): the two are integrated as separate components under the
// same error control.
TEST(Wear, TheHeatIsFrictionsDissipationOnThreeSurfaces) {
  const std::vector<std::vector<std::string>> cases = {
      {},
      {"surface.shape=cylinder", "surface.radius_m=0.05", "surface.speed_rpm=300"},
      {"surface.shape=cylinder", "surface.radius_m=0.05", "surface.speed_rpm=-1000"},
      {"surface.shape=cylinder", "surface.radius_m=0.05", "surface.speed_rpm=-3000"},
      {"surface.shape=casing", "surface.clearance_m=1e-4", "surface.lobes=2", "surface.lobe_amplitude_m=3e-4",
       "surface.friction=0.3", "beam.damping_ratio=0.02", "simulation.revolutions=3", "hub.speed_rpm=2000",
       "output.history_revolutions=all"}};
  for (const auto& sets : cases) {
    std::vector<std::string> all = sets;
    all.push_back("output.near_surface_interval_s=5e-7");
    const Config config = load_config_string("", all);
    const Case c = build_case(config);
    const PassResult r = run_case(c);
    ASSERT_FALSE(r.failure) << r.failure->message;
    const Ledger& l = r.summary.ledger;
    const double heat = l[LedgerTerm::frictional_heat];
    SCOPED_TRACE(sets.empty() ? "plane" : sets.front());
    ASSERT_GT(heat, 0.0);
    // The impacts' friction (Coulomb impacts, and the tangential impacts at Painlevé points) makes heat
    // that the ledger books in impact_loss_j: each impact's is in events.csv.
    // Where a slide ends in a stick, the step that ends at V_t = 0 takes its integrals from the dense
    // output, whose stages ran past the root, where F_n|V_t| has a kink: the load–distance, which
    // rides on the steps the motion chooses, is then as accurate as that interpolation (2e-5 at
    // −1000 rpm, 1.4 ms of stick); without stick both agree to 1e-9.
    const double tolerance = r.summary.stick_time_s > 0 ? 1e-4 : 1e-9;
    double impacts_heat = 0, impacts_load = 0;
    for (const PassEvent& e : r.events)
      if (e.kind == EventKind::impact) impacts_heat += e.frictional_heat, impacts_load += e.sliding_load;
    EXPECT_NEAR(heat, -l[LedgerTerm::friction_work] + impacts_heat, 1e-9 * heat);
    // Friction opposes the slip on every row in contact, and ∫|F_t||V_t| dt by the trapezoid rule over
    // the rows (0.5 µs apart near the surface), with V_t the slip relative to the surface computed here
    // from the tip's position and velocity (a cylinder's: V − Ω_s k × (P − c) along the tangent), is the
    // heat of sustained contact to 2e-3 (the rule's error at the episodes' ends).
    if (config.surface.shape != SurfaceShape::casing) {
      const nlohmann::json d = c.surface->describe();
      const bool round = config.surface.shape == SurfaceShape::cylinder;
      const double cx = round ? d["centre_x_m"].get<double>() : 0.0, spin = config.surface.speed_rpm * M_PI / 30.0;
      auto slip = [&](const HistoryRow& h) {
        if (!round) return h.vy;
        const double px = h.x_tip - cx, py = h.y_tip, rho = std::hypot(px, py);
        const double tx = py / rho, ty = -px / rho;  // the normal (c − P)/|c − P| turned +90°
        return (h.vx + spin * py) * tx + (h.vy - spin * px) * ty;
      };
      double rows = 0;
      for (std::size_t i = 1; i < r.history.size(); ++i) {
        const HistoryRow &a = r.history[i - 1], &b = r.history[i];
        if (a.phase == Phase::free || b.phase == Phase::free || !(b.t > a.t)) continue;
        rows += 0.5 * (std::abs(a.friction_force * slip(a)) + std::abs(b.friction_force * slip(b))) * (b.t - a.t);
      }
      // (to 1e-8 of the tip's speed ωr: a stick holds V_t = 0 to the integration's drift between steps)
      const double speed = c.beam->hub_motion().omega * c.beam->tip_radius();
      for (const HistoryRow& h : r.history)
        if (h.phase != Phase::free) EXPECT_LE(h.friction_force * slip(h), 1e-8 * speed * std::abs(h.friction_force)) << "t = " << h.t;
      EXPECT_NEAR(rows, heat - impacts_heat, 2e-3 * heat);
    }
    // In sustained contact the tip slides with |F_t| = μF_n or sticks with V_t = 0, so there the
    // load–distance is the heat over μ, whatever the sign of the slip (against the hub's sense at
    // −3000 rpm the cylinder's surface outruns the tip and the slip is negative).
    EXPECT_NEAR(l[LedgerTerm::sliding_load] - impacts_load, (heat - impacts_heat) / config.contact.friction.mu,
                tolerance * heat / config.contact.friction.mu);
    double largest = 0;
    for (const LedgerTermInfo& t : kLedgerTerms)
      if (t.report == LedgerReport::energy) largest = std::max(largest, std::abs(l[t.term]));
    EXPECT_LE(std::abs(l.residual()), 1e-8 * largest);
    if (config.simulation.revolutions == 0) {
      EXPECT_NEAR(profile_load(r.wear_profile), l[LedgerTerm::sliding_load], 1e-12 * l[LedgerTerm::sliding_load]);
      EXPECT_NEAR(profile_heat(r.wear_profile), heat, 1e-12 * heat);
    } else {
      const RevolutionRecord& rev = *r.summary.last_revolution;
      EXPECT_NEAR(profile_load(r.wear_profile), rev.ledger[LedgerTerm::sliding_load],
                  1e-12 * rev.ledger[LedgerTerm::sliding_load]);
      EXPECT_NEAR(profile_heat(r.wear_profile), rev.ledger[LedgerTerm::frictional_heat],
                  1e-12 * rev.ledger[LedgerTerm::frictional_heat] + 1e-300);
    }
  }
}

// A Coulomb impact's heat −∫V_t dP_t and load–distance ∫|V_t| dp against an independent integration
// of its impulse process (Darboux–Keller, in 2·10⁵ small steps of the normal impulse with Coulomb's
// slide/stick rule and the energetic restitution's end), from the mobility of the state before it:
// the library sums exact linear segments, this is first order in the step. Tolerance 1e-4. Cases:
// the flexible 3000 rpm start at μ = 0.05 (the slip reverses through a stick) and 0.4 (it sticks).
TEST(Wear, AnImpactsHeatAndLoadDistanceAreItsImpulseProcessIntegrals) {
  for (const char* mu : {"surface.friction=0.05", "surface.friction=0.4"}) {
    const Config config = load_config_string("", {"impact.friction=coulomb", mu, "hub.speed_rpm=3000",
                                                  "initial.modal_velocity=[2,0,0,0,0]"});
    const Case c = build_case(config);
    const FirstImpactResult f = run_first_impact(c);
    ASSERT_TRUE(f.found);
    const ImpactResult& r = f.impact;
    // The mobility a = [∇C g_t]ᵀ M⁻¹ [∇C g_t] at the impact.
    const BeamModel& beam = *c.beam;
    auto ws = beam.make_workspace();
    TipKinematics tip(beam.modes());
    tip_kinematics(beam, *c.surface, f.t, f.q, f.qd_before, tip);
    beam.evaluate_mass(f.q, *ws);
    const Eigen::MatrixXd M = ws->mass;
    const Eigen::VectorXd mg = M.ldlt().solve(tip.grad_gap), mt = M.ldlt().solve(tip.grad_tangent);
    const double ann = tip.grad_gap.dot(mg), ant = tip.grad_gap.dot(mt), att = tip.grad_tangent.dot(mt);
    const double m = config.contact.friction.mu, e = r.restitution;
    double vn = tip.gap_rate, vt = tip.slip_speed, wc = 0, wr = 0, heat = 0, load = 0, pt = 0;
    const double dp = std::abs(r.impulse) / 2e5;
    bool compressing = true;
    for (int k = 0; k < 10000000; ++k) {
      double dvn, dvt, dpt;
      if (std::abs(vt) > 1e-9) {
        const double s = vt > 0 ? 1.0 : -1.0;
        dvn = -(ann + m * s * ant), dvt = -(ant + m * s * att), dpt = -m * s;
      } else if (std::abs(ant) <= m * att) {
        dvn = -(ann - ant * ant / att), dvt = 0, dpt = ant / att, vt = 0;
      } else {
        const double s = ant > 0 ? -1.0 : 1.0;
        dvn = -(ann + m * s * ant), dvt = -(ant + m * s * att), dpt = -m * s;
      }
      const double vn_mid = vn + 0.5 * dvn * dp;
      // A step that carries the slip through zero counts its slip up to the zero only (O(dp)).
      double f1 = 1.0;
      if (vt != 0 && (vt + dvt * dp) * vt < 0) f1 = -vt / (dvt * dp);
      heat += -dpt * dp * f1 * (vt + 0.5 * dvt * f1 * dp);
      load += dp * (f1 * std::abs(vt + 0.5 * dvt * f1 * dp));
      pt += dpt * dp;
      (compressing ? wc : wr) += vn_mid * dp;
      vn += dvn * dp;
      vt = f1 < 1.0 ? 0.0 : vt + dvt * dp;
      if (compressing && vn <= 0) compressing = false;
      if (!compressing && (e == 0.0 || wr <= -e * e * wc)) break;
    }
    SCOPED_TRACE(mu);
    EXPECT_NEAR(r.frictional_heat, heat, 1e-4 * heat);
    EXPECT_NEAR(r.sliding_load, load, 1e-4 * load);
    EXPECT_NEAR(r.tangential_impulse, pt, 1e-4 * std::abs(pt));
    EXPECT_GT(r.frictional_heat, 0.0);
  }
  // Without friction the slip still changes linearly with P, through zero here: ∫|v| dp = P(v0² + v1²)/(2(|v0| + |v1|)).
  EXPECT_DOUBLE_EQ(linear_sliding_load(2.0, 3.0, -1.0), 2.0 * (9.0 + 1.0) / (2.0 * 4.0));
  EXPECT_DOUBLE_EQ(linear_sliding_load(2.0, 3.0, 1.0), 4.0);
}

// The profile lies where the tip touched: on the plane its coordinate is the tip's Y, and every bin
// that holds load–distance lies within the span of the contact's rows and impacts (one bin of slack),
// which in turn lies inside the profile.
TEST(Wear, TheProfileLiesWhereTheTipTouched) {
  const Config config = load_config_string("", {"output.interval_s=1e-6"});
  const PassResult r = run_case(build_case(config));
  ASSERT_FALSE(r.failure);
  double lo = INFINITY, hi = -INFINITY;
  for (const HistoryRow& h : r.history)
    if (h.phase != Phase::free) lo = std::min(lo, h.y_tip), hi = std::max(hi, h.y_tip);
  for (const PassEvent& e : r.events)
    if (e.kind == EventKind::impact) lo = std::min(lo, e.y_tip), hi = std::max(hi, e.y_tip);
  ASSERT_LT(lo, hi);
  ASSERT_FALSE(r.wear_profile.empty());
  const double h = r.wear_profile.front().to - r.wear_profile.front().from;
  EXPECT_LE(r.wear_profile.front().from, lo + 1e-12);
  EXPECT_GE(r.wear_profile.back().to, hi - 1e-12);
  for (const WearBin& b : r.wear_profile)
    if (b.sliding_load_n_m > 0) {
      EXPECT_GE(b.to, lo - h);
      EXPECT_LE(b.from, hi + h);
    }
  EXPECT_GT(r.wear_profile.front().sliding_load_n_m + r.wear_profile.back().sliding_load_n_m, 0.0)
      << "the profile spans what was touched, no more";
}

// A track's bins and a rebinning keep the pieces' sums to round-off, on an open coordinate and around
// a period (pieces across the seam at ±180°).
TEST(Wear, TrackBinsKeepTheirSums) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-170, 170), len(0, 30), amount(0, 1);
  for (double period : {0.0, 360.0}) {
    WearTrack track(period);
    double load = 0, heat = 0;
    for (int k = 0; k < 500; ++k) {
      const double s0 = u(rng), l = amount(rng), q = amount(rng);
      track.add(s0, k % 7 == 0 ? s0 : s0 + len(rng), l, q);
      load += l, heat += q;
    }
    for (int count : {1, 10, 97}) {
      const std::vector<WearBin> b = track.bins(count, 0.1);
      EXPECT_NEAR(profile_load(b), load, 1e-12 * load);
      EXPECT_NEAR(profile_heat(b), heat, 1e-12 * heat);
      if (period > 0) EXPECT_NEAR(b.back().to - b.front().from, 360.0, 1e-9) << "the pieces go round";
      const std::vector<WearBin> two = rebin({b, b}, {0.5, 2.0}, 13);
      EXPECT_NEAR(profile_load(two), 2.5 * load, 1e-12 * load);
    }
  }
  // A piece across the seam at ±180° lands at both ends of a track that goes all the way round.
  WearTrack seam(360.0);
  seam.add(170.0, 190.0, 1.0, 0.0);
  for (int k = 0; k < 34; ++k) seam.add(-170.0 + 10.0 * k, -160.0 + 10.0 * k, 0.5, 0.0);
  const std::vector<WearBin> round = seam.bins(36, 0.0);
  ASSERT_EQ(round.size(), 36u);
  EXPECT_NEAR(round.back().to - round.front().from, 360.0, 1e-9);
  double at_seam = 0;
  for (const WearBin& bin : round)
    if (std::abs(std::remainder(0.5 * (bin.from + bin.to) - 180.0, 360.0)) < 10.0) at_seam += bin.sliding_load_n_m;
  EXPECT_NEAR(at_seam, 1.0, 1e-9) << "the two 10° bins about the seam hold the piece that crosses it, and only it";
  // A single point is spread over the minimum span, centred on it.
  WearTrack point;
  point.add(1.0, 1.0, 2.0, 0.0);
  const std::vector<WearBin> b = point.bins(4, 0.5);
  EXPECT_DOUBLE_EQ(b.front().from, 0.75);
  EXPECT_DOUBLE_EQ(profile_load(b), 2.0);
}

// A worn filament's surface stays where it was in space: the plane's and cylinder's nearest distance,
// the casing's radius.
TEST(Wear, AWornFilamentsSurfaceStaysInPlace) {
  for (const auto& sets : std::vector<std::vector<std::string>>{
           {}, {"surface.shape=cylinder", "surface.radius_m=0.05"}, {"surface.shape=casing", "surface.clearance_m=1e-4",
                                                                     "surface.lobes=2", "surface.lobe_amplitude_m=3e-4"}}) {
    const Config base = load_config_string("", sets);
    const Config worn = worn_config(base, base.beam.length_m - 5e-5);
    const nlohmann::json a = build_case(base).surface->describe(), b = build_case(worn).surface->describe();
    const char* key = base.surface.shape == SurfaceShape::casing ? "radius_m" : "distance_m";
    EXPECT_NEAR(b[key].get<double>(), a[key].get<double>(), 1e-15) << a.dump();
  }
  // Worn past its reach, a plane's depth is refused.
  const Config base = load_config_string("", {});
  EXPECT_THROW(worn_config(base, base.beam.length_m * (1 - 1.01 * base.surface.depth_fraction)), ConfigError);
}

// The slow-time loop: every step's steady state reached (its section distance under the tolerance),
// the lengths chained by the steps' rates (L_{k+1} = L_k − rate_k Δt), each rate k_f S/(H_f πD²/4)
// times the revolutions per hour, and the run's totals the sums of its steps.
TEST(Wear, TheSlowTimeTotalsAreTheSumsOfItsSteps) {
  const Config config = load_config_string("", {"beam.damping_ratio=0.05", "wear.filament_coefficient=1e-3"});
  WearRunOptions o;
  o.hours = 4;
  o.steps = 2;
  const WearRun run = run_wear(config, o);
  ASSERT_FALSE(run.failure);
  ASSERT_EQ(run.steps.size(), 3u);
  double lost = 0, volume = 0;
  const double rev_per_h = 60 * config.beam.speed_rpm, D = config.beam.diameter_m;
  for (std::size_t k = 0; k < run.steps.size(); ++k) {
    const WearStep& s = run.steps[k];
    EXPECT_TRUE(s.steady);
    EXPECT_LE(s.section_distance, config.simulation.steady_tolerance);
    EXPECT_NEAR(s.length_m, config.beam.length_m - lost, 1e-15);
    EXPECT_NEAR(s.length_rate_m_h,
                config.wear.filament_coefficient * s.per_revolution.sliding_load_n_m / config.wear.filament_hardness_pa /
                    (M_PI * D * D / 4) * rev_per_h,
                1e-12 * s.length_rate_m_h);
    EXPECT_NEAR(s.length_lost_m, s.length_rate_m_h * s.duration_h, 1e-18);
    EXPECT_NEAR(profile_load(s.profile), s.per_revolution.sliding_load_n_m, 1e-12 * s.per_revolution.sliding_load_n_m);
    lost += s.length_lost_m;
    volume += s.volume_removed_m3;
  }
  EXPECT_GT(run.steps[1].length_m, 0.0);
  EXPECT_LT(run.steps[1].length_m, config.beam.length_m);
  EXPECT_EQ(run.length_lost_m, lost);
  EXPECT_NEAR(run.volume_removed_m3, volume, 1e-15 * volume);
  // The surface's profile over the run holds the volume removed.
  const double removed = config.wear.surface_coefficient * profile_load(run.removed_profile) / config.wear.surface_hardness_pa;
  EXPECT_NEAR(removed, run.volume_removed_m3, 1e-12 * run.volume_removed_m3);
}

// Bad options name themselves.
TEST(Wear, BadOptionsAreRefusedByName) {
  const Config config = load_config_string("", {});
  WearRunOptions o;
  o.hours = -1;
  try {
    run_wear(config, o);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--hours"), std::string::npos);
  }
  o.hours = 1;
  o.steps = 0;
  EXPECT_THROW(run_wear(config, o), ConfigError);
}

// A brush's wear profile: its bins sum to the filaments' load–distance per revolution (so its removed
// volume integrates to the worn volume), and its shape is the single filament's wear law applied
// independently to that filament's history rows (F_n|V_Y| by the trapezoid rule between contact
// rows 0.5 µs apart, at the rows' mean Y) and to its impacts (each event's load–distance over the
// filament's diameter about its Y),
// three times over for three identical filaments. Tolerances: 2e-3 on the total and 1e-3 of the
// touched span on the centroid (the rows' trapezoid rule against the steps' integrals); a
// correlation above 0.99 bin by bin.
TEST(Wear, ABrushsProfileIsItsFilamentsWearAlongTheSurface) {
  const std::vector<std::string> filament = {"beam.damping_ratio=0.05"};
  std::vector<std::string> brush_sets = filament;
  brush_sets.push_back("brush.filaments=3");
  const Config bc = load_config_string("", brush_sets);
  BrushOptions bo;
  bo.threads = 1;
  const BrushResult b = run_brush(bc, bo);
  ASSERT_EQ(b.summary.steady, 3);
  ASSERT_FALSE(b.wear_profile.empty());
  const double total = profile_load(b.wear_profile);
  EXPECT_NEAR(total, b.summary.ledger[LedgerTerm::sliding_load], 1e-12 * total);
  const WearReport w = brush_wear_report(b, bc);
  double volume = 0;
  for (const WearBin& bin : w.profile)
    volume += removed_depth_m(bin, bc.wear, w.coordinate, w.track_width_m) * w.track_width_m * (bin.to - bin.from);
  EXPECT_NEAR(volume, w.amounts.surface_volume_m3, 1e-9 * w.amounts.surface_volume_m3);

  std::vector<std::string> run_sets = filament;
  for (const char* s : {"simulation.until_steady=true", "simulation.revolutions=200", "simulation.multipliers=false",
                        "output.interval_s=1e-6", "output.near_surface_interval_s=5e-7"})
    run_sets.push_back(s);
  const PassResult r = run_case(build_case(load_config_string("", run_sets)));
  ASSERT_TRUE(r.summary.steady_state.reached);
  ASSERT_EQ(r.summary.steady_state.period_revolutions, 1);
  const double t0 = r.summary.last_revolution->t_start;
  std::vector<WearBin> rows = b.wear_profile;
  for (WearBin& bin : rows) bin.sliding_load_n_m = 0;
  const double lo = rows.front().from, h = rows.front().to - rows.front().from;
  auto add = [&](double y, double s) {
    const int k = std::clamp(static_cast<int>(std::floor((y - lo) / h)), 0, static_cast<int>(rows.size()) - 1);
    rows[k].sliding_load_n_m += 3 * s;
  };
  // An impact's load–distance over the filament's diameter about its point (docs/wear.md), in 100 parts.
  const double D = bc.beam.diameter_m;
  auto add_impact = [&](double y, double s) {
    for (int i = 0; i < 100; ++i) add(y - 0.5 * D + (i + 0.5) * D / 100, s / 100);
  };
  for (std::size_t i = 1; i < r.history.size(); ++i) {
    const HistoryRow &a = r.history[i - 1], &c = r.history[i];
    if (a.t < t0 || a.phase == Phase::free || c.phase == Phase::free || !(c.t > a.t)) continue;
    add(0.5 * (a.y_tip + c.y_tip), 0.5 * (a.normal_force * std::abs(a.vy) + c.normal_force * std::abs(c.vy)) * (c.t - a.t));
  }
  for (const PassEvent& e : r.events)
    if (e.kind == EventKind::impact && e.t >= t0) add_impact(e.y_tip, e.sliding_load);
  const double from_rows = profile_load(rows);
  EXPECT_NEAR(from_rows, total, 2e-3 * total);
  double ca = 0, cb = 0, sab = 0, saa = 0, sbb = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const double y = 0.5 * (rows[k].from + rows[k].to);
    ca += y * b.wear_profile[k].sliding_load_n_m / total;
    cb += y * rows[k].sliding_load_n_m / from_rows;
  }
  const double span = rows.back().to - rows.front().from;
  EXPECT_NEAR(ca, cb, 1e-3 * span);
  const double ma = total / rows.size(), mb = from_rows / rows.size();
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const double da = b.wear_profile[k].sliding_load_n_m - ma, db = rows[k].sliding_load_n_m - mb;
    sab += da * db, saa += da * da, sbb += db * db;
  }
  EXPECT_GT(sab / std::sqrt(saa * sbb), 0.99);
}
