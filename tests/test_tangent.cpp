// The section map's Jacobian from the variational equations with saltation matrices (tangent.hpp,
// docs/model.md "The map's Jacobian from the variational equations") against central differences
// of the map itself at a tight tolerance.
#include "rotbeam/case.hpp"
#include "rotbeam/config.hpp"
#include "rotbeam/steady_state.hpp"
#include "rotbeam/tangent.hpp"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <gtest/gtest.h>

using namespace rotbeam;

namespace {

// ∂P/∂z by central differences with step δ (relative to ‖z‖) on the map of `c`.
Eigen::MatrixXd differences(const SectionMap& map, const Eigen::VectorXd& z, double delta) {
  const Eigen::Index dim = z.size();
  Eigen::MatrixXd J(dim, dim);
  const double h = delta * z.norm();
  for (Eigen::Index j = 0; j < dim; ++j) {
    Eigen::VectorXd zp = z, zm = z;
    zp[j] += h;
    zm[j] -= h;
    const MapEvaluation ep = map(zp, 1), em = map(zm, 1);
    EXPECT_TRUE(ep.complete && em.complete);
    J.col(j) = (ep.z - em.z) / (2.0 * h);
  }
  return J;
}

struct Compared {
  double error = NAN;  // max |J_var − J_fd| / max |J_fd|
  int impacts = 0, episodes = 0;
  std::string lost;
  std::vector<Multiplier> mu_var, mu_fd;
};

Compared compare(const std::vector<std::string>& sets) {
  std::vector<std::string> all = sets;
  all.push_back("simulation.until_steady=true");
  all.push_back("simulation.steady_tolerance=1e-10");
  const Case c = build_case(load_config_string("", all));
  const PassResult r = run_case(c);
  Compared out;
  if (r.failure || !r.summary.steady_state.reached) return out;
  PassOptions tight = c.options;
  tight.rtol = 1e-12;
  tight.atol = 1e-16;
  const System system = c.system();
  const SectionMap map(system, tight, nullptr);
  const Eigen::VectorXd z = section_state(*c.beam, r.final_q, r.final_qd);
  const MapEvaluation e = map(z, 1, true);
  out.impacts = e.impacts;
  out.episodes = e.contact_episodes;
  out.lost = e.tangent_lost;
  if (e.jacobian.size() == 0) return out;
  const Eigen::MatrixXd fd = differences(map, z, 1e-6);
  out.error = (e.jacobian - fd).cwiseAbs().maxCoeff() / fd.cwiseAbs().maxCoeff();
  out.mu_var = floquet_multipliers(e.jacobian);
  out.mu_fd = floquet_multipliers(fd);
  return out;
}

}  // namespace

// The foreshortening beam's free-flight Jacobian in closed form (dynamics.cpp) against central
// differences of q̈ itself, at states of the size a rub reaches (|q| ≈ 0.2 L, |q̇| ≈ ωL), for mode
// counts through the fixed-size kernels (n ≤ 8) and the dynamic ones, with damping and with each
// rotation term switched off. The differences are good to ≈ 1e-9 of the largest entry (steps of 1e-6
// of the scales on a low-degree rational function; measured ≤ 1e-9 up to 8 modes, 3.2e-7 at 10 and
// 12 where the entries span more decades); a term with a wrong factor or index is off by its own
// size, ≥ 1e-4 of the largest here.
TEST(Tangent, FreeFlightJacobianInClosedFormEqualsDifferences) {
  const std::vector<std::vector<std::string>> cases = {
      {"beam.modes=1"},
      {"beam.modes=3", "beam.damping_ratio=0.05"},
      {"beam.modes=5"},
      {"beam.modes=8", "model.coriolis=false"},
      {"beam.modes=10", "model.centrifugal=false"},
      {"beam.modes=12", "beam.damping_ratio=0.02", "hub.speed_rpm=1500"},
  };
  for (const auto& sets : cases) {
    const Case c = build_case(load_config_string("", sets));
    const System system = c.system();
    const int n = c.beam->modes();
    const double L = c.beam->beam_length(), omega = c.beam->hub_motion().omega;
    std::srand(7);
    const Eigen::VectorXd q = 0.2 * L * Eigen::VectorXd::Random(n).cwiseQuotient(Eigen::VectorXd::LinSpaced(n, 1, n));
    const Eigen::VectorXd qd = omega * L * Eigen::VectorXd::Random(n);
    TangentWorkspace closed(*c.beam), differenced(*c.beam);
    differenced.closed_form = false;
    Eigen::MatrixXd jq(n, n), jqd(n, n), fq(n, n), fqd(n, n);
    phase_jacobian(system, Phase::free, {}, 0.0, q, qd, closed, jq, jqd);
    phase_jacobian(system, Phase::free, {}, 0.0, q, qd, differenced, fq, fqd);
    EXPECT_EQ(closed.closed_form_evaluations, 1);
    EXPECT_EQ(differenced.closed_form_evaluations, 0);
    const double eq = (jq - fq).cwiseAbs().maxCoeff() / fq.cwiseAbs().maxCoeff();
    const double eqd = (jqd - fqd).cwiseAbs().maxCoeff() / fqd.cwiseAbs().maxCoeff();
    EXPECT_LT(eq, 1e-6) << sets.front() << " ∂q̈/∂q";
    EXPECT_LT(eqd, 1e-6) << sets.front() << " ∂q̈/∂q̇";
  }
}

// Φ at the end of a pass from a flexible start against central differences of the pass's end
// state. The differences use steps of 1e-8 of the scales: the map's gain reaches 1e7 (the high
// modes), and at 1e-6 its curvature already moves the differences by 6 % at 5 modes; at rtol 1e-12
// the integration's noise over such a step is below 1e-9 of the entries.
struct PassCheck {
  double error = NAN;
  int impacts = 0, episodes = 0;
  std::string lost;
};

PassCheck check_pass(const std::vector<std::string>& sets, double end_after_touch_deg, double q_scale,
                     double span_deg = NAN) {
  std::vector<std::string> all = sets;
  if (sets.back().find("thesis") == std::string::npos) {
    all.push_back("simulation.rtol=1e-12");
    all.push_back("simulation.atol=1e-16");
  }
  const Case c = build_case(load_config_string("", all));
  const System system = c.system();
  const int n = c.beam->modes();
  const double L = c.beam->beam_length(), omega = c.beam->hub_motion().omega;
  const double theta0 = c.beam->theta(0.0) * 180.0 / M_PI;
  const double touch = c.surface->first_contact_angle(c.beam->tip_radius(), c.beam->theta(0.0)) * 180.0 / M_PI;
  PassOptions o = c.options;
  o.end_angle_deg = !std::isnan(span_deg) ? theta0 + span_deg : touch + end_after_touch_deg;
  o.output_interval_s = 1e9;
  o.tangent = true;
  InitialConditions ic;
  ic.rigid_start = false;
  ic.q0 = q_scale * L * Eigen::VectorXd::LinSpaced(n, 1.0, 1.0 / n);
  ic.qd0 = q_scale * omega * L * Eigen::VectorXd::LinSpaced(n, -1.0, 1.0);
  const PassResult r = run_pass(system, ic, o, {});
  PassCheck out;
  out.impacts = r.summary.impacts;
  out.episodes = r.summary.contact_episodes;
  out.lost = r.tangent_lost;
  if (r.failure || r.final_tangent.rows() != 2 * n) return out;
  o.tangent = false;
  Eigen::MatrixXd fd(2 * n, 2 * n);
  for (int j = 0; j < 2 * n; ++j) {
    const double h = j < n ? 1e-8 * L : 1e-8 * omega * L;
    InitialConditions p = ic, m = ic;
    if (j < n) p.q0[j] += h, m.q0[j] -= h;
    else p.qd0[j - n] += h, m.qd0[j - n] -= h;
    const PassResult rp = run_pass(system, p, o, {}), rm = run_pass(system, m, o, {});
    EXPECT_EQ(rp.summary.impacts, out.impacts);
    EXPECT_EQ(rm.summary.impacts, out.impacts);
    EXPECT_EQ(rp.summary.contact_episodes, out.episodes);
    EXPECT_EQ(rm.summary.contact_episodes, out.episodes);
    fd.col(j) << (rp.final_q - rm.final_q) / (2 * h), (rp.final_qd - rm.final_qd) / (2 * h);
  }
  out.error = (r.final_tangent - fd).cwiseAbs().maxCoeff() / fd.cwiseAbs().maxCoeff();
  return out;
}

TEST(Tangent, FreeFlightPhiEqualsDifferencesOfThePass) {
  for (const char* sets : {"beam.damping_ratio=0", "beam.damping_ratio=0.03"}) {
    const PassCheck k = check_pass({sets}, 0.0, 0.05, 15.0);
    EXPECT_EQ(k.impacts, 0);
    EXPECT_LT(k.error, 1e-6) << sets << " " << k.lost;
  }
}

// Through impacts (frictionless, Coulomb, several at once), sustained sliding contact (the rigid
// law's constraint phase, entered after a plastic impact and left at λ = 0) and frictionless
// compliant contact (the damping set from the approach speed at each touch): Φ equals the
// differences to 1e-5 of its largest entry (measured 5e-8 to 8e-6; the differences' own error is
// near 1e-7). Over longer sequences (8° after the touch: 11 to 33 impacts) the two differ by 2e-5 to
// 4e-4 (docs/model.md). Dropping the saltation's time-shift term, or the damping's sensitivity, makes these
// errors O(1) (tried once each).
TEST(Tangent, ThroughImpactsAndContacts) {
  const std::vector<std::vector<std::string>> cases = {
      {"beam.modes=3", "impact.restitution=0.6", "surface.friction=0"},
      {"beam.modes=5", "impact.restitution=0.6", "surface.friction=0.3"},
      {"beam.modes=3", "surface.friction=0.1"},
      {"beam.modes=5"},
      {"beam.modes=3", "contact.model=\"hertz\"", "surface.friction=0"},
  };
  int episodes = 0;
  for (double after : {0.5, 3.0})
    for (const auto& sets : cases) {
      const PassCheck k = check_pass(sets, after, 0.0);
      std::string name;
      for (const auto& x : sets) name += x + " ";
      EXPECT_TRUE(k.lost.empty()) << name << k.lost;
      EXPECT_GE(k.impacts + k.episodes, 1) << name;
      EXPECT_LT(k.error, 1e-5) << name << "to " << after << "° after the touch: " << k.impacts << " impacts, "
                               << k.episodes << " episodes";
      episodes += k.episodes;
    }
  EXPECT_GT(episodes, 3);
}

// Where the variational equations are not carried, the run says why and the map's Jacobian is
// differenced (SectionMap falls back): the compliant law's regularised friction, the thesis scheme.
TEST(Tangent, WhereItIsNotCarriedTheRunSaysWhy) {
  EXPECT_NE(check_pass({"beam.modes=3", "contact.model=\"hertz\""}, 0.5, 0.0).lost.find("regularised friction"),
            std::string::npos);
  EXPECT_NE(check_pass({"beam.modes=3", "simulation.scheme=\"thesis\""}, 0.5, 0.0).lost.find("thesis scheme"),
            std::string::npos);
}

// On steady orbits (simulation.until_steady) the Jacobian of the revolution map from one variational
// run equals central differences of the map at rtol 1e-12 with δ = 1e-6 ‖z‖ (their error ≈ 1e-5 here:
// the map's curvature over δ), and so do the Floquet multipliers, to 1e-4.
TEST(Tangent, SteadyOrbitJacobianEqualsDifferencesOfTheMap) {
  const std::vector<std::vector<std::string>> cases = {
      {"beam.modes=3", "beam.damping_ratio=0.02", "surface.friction=0.1", "hub.speed_rpm=800", "impact.restitution=0.6"},
  };
  for (const auto& sets : cases) {
    const Compared k = compare(sets);
    ASSERT_TRUE(k.lost.empty()) << k.lost;
    ASSERT_FALSE(std::isnan(k.error));
    EXPECT_GE(k.impacts + k.episodes, 1);
    EXPECT_LT(k.error, 1e-4) << sets.back();
    ASSERT_EQ(k.mu_var.size(), k.mu_fd.size());
    for (std::size_t i = 0; i < k.mu_var.size(); ++i) {
      EXPECT_NEAR(k.mu_var[i].re, k.mu_fd[i].re, 1e-4) << sets.back() << " multiplier " << i;
      EXPECT_NEAR(k.mu_var[i].im, k.mu_fd[i].im, 1e-4) << sets.back() << " multiplier " << i;
    }
  }
}
