// The right-hand side, the kinematics and the impact law allocate nothing on the heap.
// The test is linked with -Wl,--wrap=malloc, so every malloc made by the (static) library's code
// goes through __wrap_malloc below and is counted while `counting` is set.
#include "rotbeam/dynamics.hpp"
#include "rotbeam/elastica_beam.hpp"
#include "rotbeam/impact.hpp"
#include "rotbeam/kinematics.hpp"
#include "rotbeam/rk5.hpp"
#include "rotbeam/plane.hpp"
#include "rotbeam/casing.hpp"
#include "rotbeam/cylinder.hpp"
#include "rotbeam/case.hpp"
#include "rotbeam/config.hpp"
#include "rotbeam/stepper.hpp"

#include <atomic>
#include <cstdlib>
#include <gtest/gtest.h>

extern "C" void* __real_malloc(std::size_t);
namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
}  // namespace
extern "C" void* __wrap_malloc(std::size_t size) {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1);
  return __real_malloc(size);
}

using namespace rotbeam;

TEST(NoAllocation, RightHandSideKinematicsImpactAndRk5Step) {
  for (int n : {1, 5, 10, 20}) {
    BeamParameters p;
    p.modes = n;
    const ForeshorteningBeam model = make_beam(p);
    const Plane plane = plane_at_depth(model, 0.02);
    ForeshorteningWorkspace ws(n);
    TipKinematics tip(n);
    Rk5Stepper stepper(n);
    Eigen::VectorXd q = Eigen::VectorXd::Constant(n, 1e-3), v = Eigen::VectorXd::Constant(n, 0.3),
                    a(n), q2(n), v2(n);
    auto accel = [&](double, const Eigen::VectorXd& qq, const Eigen::VectorXd& vv, Eigen::VectorXd& out) {
      acceleration(model, qq, vv, nullptr, ws, out);
    };
    const double t = model.time_at(-0.2);
    acceleration(model, q, v, nullptr, ws, a);  // warm-up (first-touch of any lazily built data)
    Eigen::VectorXd qd = v;
    qd[0] += 5.0;  // make sure the tip approaches
    allocations = 0;
    counting = true;
    acceleration(model, q, v, nullptr, ws, a);
    tip_kinematics(model, plane, t, q, v, tip);
    stepper.step(accel, t, q, v, 1e-6, q2, v2);
    tip_kinematics(model, plane, t, q, qd, tip);
    if (tip.gap_rate > 0) apply_impact(model, plane, ImpactLaw{}, t, q, qd, ws, tip);
    counting = false;
    EXPECT_EQ(allocations.load(), 0) << "n = " << n;
    EXPECT_TRUE(a.allFinite());
  }
}

TEST(NoAllocation, CurvedSurfacesContactGeometry) {
  // A spinning cylinder's and a lobed casing's contact geometry (gap field, chain rule) and an impact
  // on each: nothing on the heap either.
  for (int n : {3, 12}) {
    BeamParameters p;
    p.modes = n;
    const ForeshorteningBeam model = make_beam(p);
    const Cylinder cylinder(model.tip_radius() - 0.02 * model.length, 0.05, 100.0);
    const Casing casing(model.tip_radius(), 1e-4, 3, 5e-4, LobeLaw::cosine);
    const Casing benchmark(model.tip_radius(), 1e-4, 2, 1e-4, LobeLaw::benchmark);
    ForeshorteningWorkspace ws(n);
    TipKinematics tip(n);
    Eigen::VectorXd q = Eigen::VectorXd::Constant(n, 1e-3), v = Eigen::VectorXd::Constant(n, 0.3);
    const double t = model.time_at(-0.2);
    for (const Surface* s : {static_cast<const Surface*>(&cylinder), static_cast<const Surface*>(&casing),
                             static_cast<const Surface*>(&benchmark)}) {
      tip_kinematics(model, *s, t, q, v, tip);  // warm-up
      Eigen::VectorXd qd = v;
      allocations = 0;
      counting = true;
      tip_kinematics(model, *s, t, q, qd, tip);
      if (tip.gap_rate <= 0) qd = -qd;
      tip_kinematics(model, *s, t, q, qd, tip);
      if (tip.gap_rate > 0) apply_impact(model, *s, ImpactLaw{}, t, q, qd, ws, tip);
      counting = false;
      EXPECT_EQ(allocations.load(), 0) << "n = " << n << " " << s->describe().dump();
    }
  }
}

TEST(NoAllocation, TheElasticasEvaluationsAndAStepOfAPass) {
  // The elastica's dynamics, energies, tip, momentum rate and excursion bound, the contact
  // kinematics and an impact, at 5 modes (fixed-size kernels of small products) and 40 (Eigen's
  // products at sizes that would use its blocking buffers): nothing on the heap.
  for (int n : {5, 40}) {
    BeamParameters p;
    p.modes = n;
    const ElasticaBeam model = make_elastica(p);
    const Plane plane = plane_at_depth(model, 0.02);
    auto ws = model.make_workspace();
    TipKinematics tip(n);
    HubFrameTip hub_tip(n);
    Eigen::VectorXd q = Eigen::VectorXd::Constant(n, 1e-3), v = Eigen::VectorXd::Constant(n, 0.3), a(n);
    const double t = model.time_at(-0.2);
    acceleration(model, q, v, nullptr, *ws, a);  // warm-up
    Eigen::VectorXd qd = v;
    qd[0] += 5.0;
    allocations = 0;
    counting = true;
    acceleration(model, q, v, nullptr, *ws, a);
    const EnergyTerms e = model.energy(q, v, *ws);
    const double rate = model.angular_momentum_rate(q, v, a, *ws);
    const double bound = model.tip_excursion_bound(q, v, *ws);
    model.tip(q, v, hub_tip);
    tip_kinematics(model, plane, t, q, qd, tip);
    if (tip.gap_rate > 0) apply_impact(model, plane, ImpactLaw{}, t, q, qd, *ws, tip);
    counting = false;
    EXPECT_EQ(allocations.load(), 0) << "n = " << n;
    EXPECT_TRUE(a.allFinite() && std::isfinite(e.jacobi) && std::isfinite(rate) && std::isfinite(bound));
  }
}

TEST(NoAllocation, CounterSeesAllocations) {
  // The wrap is live: an allocation inside the library is counted (guards against a test that
  // cannot fail because the wrapping silently stopped working).
  allocations = 0;
  counting = true;
  ForeshorteningWorkspace ws(7);
  counting = false;
  EXPECT_GT(allocations.load(), 0);
}

TEST(NoAllocation, CompliantContactSteps) {
  // The adaptive scheme's steps inside a compliant (Hertz) contact: the right-hand side (kinematics,
  // Hertz force, regularised friction, contact load, q̈), the dense output's samples, the gap root
  // and the peak's refinement allocate nothing once the stepper is warm.
  for (int n : {1, 5, 12}) {
    const Case c = build_case(load_config_string("", {"contact.model=hertz", "beam.modes=" + std::to_string(n)}));
    const System sys = c.system();
    const std::unique_ptr<Stepper> stepper = make_adaptive_stepper(sys, c.options);
    FilamentState s(n);
    s.t = c.beam->time_at(sys.surface.first_contact_angle(c.beam->tip_radius(), c.beam->theta(0.0)));
    s.phase = Phase::contact;
    s.episode.parameter[0] = 0.5;  // the compliant law's Hunt–Crossley c [s/m]
    stepper->begin_contact(s);
    stepper->step(s, 1.0);  // warm-up: odeint sizes its internal states at the first step
    int steps = 0;
    allocations = 0;
    counting = true;
    for (; steps < 50; ++steps)
      if (stepper->step(s, 1.0).status != StepStatus::advanced) break;
    counting = false;
    EXPECT_EQ(allocations.load(), 0) << "n = " << n << " over " << steps << " steps";
    EXPECT_GT(steps, 5) << "n = " << n;
  }
}
