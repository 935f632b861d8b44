// Whole-pass timings (base case: 2 %, μ = 0.4, rigid start, Yigit's law with the plastic floor):
// the thesis scheme at its default steps, the adaptive scheme at rtol 1e-8, and the 80-case
// Table 5-2 grid with the adaptive scheme spread over all cores.
#include "rotbeam/case.hpp"
#include "rotbeam/contact_laws.hpp"
#include "rotbeam/job_runner.hpp"
#include "rotbeam/plane.hpp"
#include "table_5_2.hpp"

#include <benchmark/benchmark.h>

using namespace rotbeam;

namespace {

// One pass of the base case at `modes` and `rpm` per iteration, history every 100 µs.
void base_case_passes(benchmark::State& state, PassOptions opt, int modes, double rpm) {
  BeamParameters p;
  p.modes = modes;
  p.speed_rpm = rpm;
  const ForeshorteningBeam model = make_beam(p);
  const Plane plane = plane_at_depth(model, 0.02);
  InitialConditions ic;
  opt.output_interval_s = 1e-4;
  PassSummary s;
  for (auto _ : state) {
    const PassResult r = run_pass({model, plane, default_contact_law()}, ic, opt);
    s = r.summary;
    benchmark::DoNotOptimize(r.history.data());
  }
  state.counters["steps"] = static_cast<double>(s.steps);
  state.counters["rhs_evaluations"] = static_cast<double>(s.rhs_evaluations);
  state.counters["impacts"] = s.impacts;
  state.counters["contact_episodes"] = s.contact_episodes;
}

// One pass of the base case at (modes, rpm) = state.range(0, 1).
void pass_benchmark(benchmark::State& state, PassOptions opt) {
  base_case_passes(state, opt, static_cast<int>(state.range(0)), static_cast<double>(state.range(1)));
}

void BM_ThesisPass(benchmark::State& state) {
  PassOptions opt;
  opt.scheme = Scheme::thesis;
  pass_benchmark(state, opt);
}
BENCHMARK(BM_ThesisPass)->Args({5, 550})->Args({5, 3000})->Args({10, 550})->Args({10, 3000})->Unit(benchmark::kMillisecond);

void BM_AdaptivePass(benchmark::State& state) {
  PassOptions opt;
  opt.rtol = 1e-8;
  pass_benchmark(state, opt);
}
BENCHMARK(BM_AdaptivePass)->Args({5, 550})->Args({5, 3000})->Args({10, 550})->Args({10, 3000})->Unit(benchmark::kMillisecond);

// The base case at the default tolerance (rtol 1e-9) for n = state.range(0) modes, variant
// state.range(1): 0 plain Dormand–Prince on q, q̇; 1 the integrating factor (default); 2 the factor
// with simulation.end_when_clear. History every 100 µs. n = 20 and 30 take seconds to minutes per
// pass: one iteration each (bench/mode_scaling.py gives the whole-process medians and the errors).
void BM_AdaptiveModes(benchmark::State& state) {
  PassOptions opt;
  opt.integrating_factor = state.range(1) >= 1 ? FactorUse::always : FactorUse::never;
  opt.end_when_clear = state.range(1) == 2;
  state.SetLabel(state.range(1) == 0 ? "plain" : state.range(1) == 1 ? "factor" : "factor+clear");
  base_case_passes(state, opt, static_cast<int>(state.range(0)), 550.0);
}
BENCHMARK(BM_AdaptiveModes)
    ->Args({5, 0})->Args({5, 1})->Args({5, 2})
    ->Args({10, 0})->Args({10, 1})->Args({10, 2})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AdaptiveModes)
    ->Args({20, 1})->Args({20, 2})->Args({30, 2})
    ->Unit(benchmark::kSecond)->Iterations(1);

// The 80 Table 5-2 cases (default configuration otherwise: adaptive, rtol 1e-9), on `threads` threads.
void BM_Table52Grid(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  std::vector<Config> cases = table_5_2_cases();
  for (Config& c : cases) c.simulation.output_interval_s = 1e30;
  JobRunnerOptions runner;
  runner.threads = threads;
  for (auto _ : state)
    run_jobs(
        cases.size(), [&](std::size_t i) { benchmark::DoNotOptimize(run_case(build_case(cases[i])).summary.impacts); },
        runner);
  state.counters["cases"] = static_cast<double>(cases.size());
}
BENCHMARK(BM_Table52Grid)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
