// Whole-pass timings of the thesis scheme (base case: 2 %, μ = 0.4, rigid start, Yigit's law).
#include "rotbeam/pass.hpp"

#include <benchmark/benchmark.h>

using namespace rotbeam;

namespace {

void BM_ThesisPass(benchmark::State& state) {
  PhysicalParameters p;
  p.modes = static_cast<int>(state.range(0));
  p.speed_rpm = static_cast<double>(state.range(1));
  const Model model = make_model(p);
  InitialConditions ic;
  PassOptions opt;
  opt.output_interval_s = 1e-4;
  PassSummary s;
  for (auto _ : state) {
    const PassResult r = run_thesis_pass(model, ImpactLaw{}, FrictionModel{p.friction, false}, ic, opt);
    s = r.summary;
    benchmark::DoNotOptimize(r.history.data());
  }
  state.counters["steps"] = static_cast<double>(s.steps);
  state.counters["rhs_evaluations"] = static_cast<double>(s.rhs_evaluations);
  state.counters["impacts"] = s.impacts;
  state.counters["contact_episodes"] = s.contact_episodes;
}
BENCHMARK(BM_ThesisPass)->Args({5, 550})->Args({5, 3000})->Args({10, 550})->Args({10, 3000})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
