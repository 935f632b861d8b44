// Micro-benchmarks of the model core: q̈(q, q̇) for several mode counts, the modal integrals, and
// one whole free pass (θ0 → +90°) with the thesis's fixed-step RK5.
#include "rotbeam/dynamics.hpp"
#include "rotbeam/contact_laws.hpp"
#include "rotbeam/elastica_beam.hpp"
#include "rotbeam/modal_integrals.hpp"
#include "rotbeam/plane.hpp"
#include "rotbeam/stepper.hpp"

#include <benchmark/benchmark.h>

using namespace rotbeam;

namespace {

// Floating-point operations of one acceleration() call, counted from the loops of dynamics.cpp
// (a multiply-add counts 2): Z (n²·P), M (n·n(n+1)/2), the two Z contractions (2n·P), the
// gyroscopic term (2n³), the centrifugal GEMVs (2n²), the bending contraction (P² + n²), the
// Cholesky factorisation (n³/3) and the two triangular solves (2n²); P = n(n+1)/2.
double flops_per_acceleration(int n) {
  const double p = n * (n + 1) / 2.0, nn = n;
  const double fma = nn * nn * p + nn * nn * (nn + 1) / 2 + 2 * nn * p + 2 * nn * nn * nn + 2 * nn * nn + p * p + nn * nn;
  return 2 * fma + nn * nn * nn / 3 + 2 * nn * nn;
}

ForeshorteningBeam model_with(int n, double rpm = 550.0) {
  BeamParameters p;
  p.modes = n;
  p.speed_rpm = rpm;
  return make_beam(p);
}

void BM_Acceleration(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const ForeshorteningBeam model = model_with(n);
  ForeshorteningWorkspace ws(n);
  Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(n, 1e-2, 1e-4), v = Eigen::VectorXd::LinSpaced(n, 2.0, 0.1), a(n);
  for (auto _ : state) {
    acceleration(model, q, v, nullptr, ws, a);
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  state.counters["flops_per_call"] = flops_per_acceleration(n);
  state.counters["flop_rate"] =
      benchmark::Counter(flops_per_acceleration(n), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Acceleration)->Arg(5)->Arg(10)->Arg(20)->Arg(30);

void BM_ElasticaAcceleration(benchmark::State& state) {
  // The elastica's q̈ (its quadrature at every call: (n + 2)·16 nodes) at the same state as
  // BM_Acceleration, for the cost of the exact geometry against the thesis model's.
  const int n = static_cast<int>(state.range(0));
  BeamParameters p;
  p.modes = n;
  const ElasticaBeam model = make_elastica(p);
  auto ws = model.make_workspace();
  Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(n, 1e-2, 1e-4), v = Eigen::VectorXd::LinSpaced(n, 2.0, 0.1), a(n);
  for (auto _ : state) {
    acceleration(model, q, v, nullptr, *ws, a);
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  state.counters["nodes"] = model.nodes();
}
BENCHMARK(BM_ElasticaAcceleration)->Arg(5)->Arg(10)->Arg(20)->Arg(30);

void BM_ModalIntegrals(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  for (auto _ : state) {
    ModalIntegrals mi = compute_modal_integrals(n, default_quadrature_panels(n), 20);
    benchmark::DoNotOptimize(mi.isp_isp.data());
  }
  state.SetLabel("computed once per mode count and cached");
}
BENCHMARK(BM_ModalIntegrals)->Arg(5)->Arg(10)->Arg(30)->Unit(benchmark::kMillisecond);

void BM_FreePass(benchmark::State& state) {
  // θ0 = −90° → +90° with q̇(0) = (2, 0, …) m/s, h = 1e-6 s, surface ignored.
  const int n = static_cast<int>(state.range(0));
  const double rpm = static_cast<double>(state.range(1));
  const ForeshorteningBeam model = model_with(n, rpm);
  const Plane far(1.0);  // out of reach
  PassOptions opt;
  opt.scheme = Scheme::thesis;
  opt.free_step_s = 1e-6;
  const double t_end = model.time_at(M_PI / 2);
  long steps = 0, rhs = 0;
  for (auto _ : state) {
    const auto stepper = make_thesis_stepper({model, far, default_contact_law()}, opt);
    FilamentState s(n);
    s.qd[0] = 2.0;
    stepper->begin_free(s, FreeStart::pass_start);
    while (s.t < t_end) stepper->step(s, t_end);
    steps = stepper->statistics().steps;
    rhs = stepper->statistics().rhs_evaluations;
    benchmark::DoNotOptimize(s.q.data());
  }
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["rhs_evaluations"] = static_cast<double>(rhs);
}
BENCHMARK(BM_FreePass)->Args({5, 550})->Args({5, 3000})->Args({10, 550})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
