// Whole-pass timings (base case: 2 %, μ = 0.4, rigid start, Yigit's law with the plastic floor):
// the thesis scheme at its default steps, the adaptive scheme at rtol 1e-8, and the 80-case
// Table 5-2 grid with the adaptive scheme spread over all cores.
#include "rotbeam/config.hpp"
#include "rotbeam/pass.hpp"
#include "table_5_2.hpp"

#include <atomic>
#include <benchmark/benchmark.h>
#include <thread>

using namespace rotbeam;

namespace {

// One pass of the base case at (modes, rpm) = state.range(0, 1), history every 100 µs.
template <class RunPass>
void pass_benchmark(benchmark::State& state, PassOptions opt, RunPass run_pass) {
  PhysicalParameters p;
  p.modes = static_cast<int>(state.range(0));
  p.speed_rpm = static_cast<double>(state.range(1));
  const Model model = make_model(p);
  InitialConditions ic;
  opt.output_interval_s = 1e-4;
  PassSummary s;
  for (auto _ : state) {
    const PassResult r = run_pass(model, ImpactLaw{}, FrictionModel{p.friction, false}, ic, opt);
    s = r.summary;
    benchmark::DoNotOptimize(r.history.data());
  }
  state.counters["steps"] = static_cast<double>(s.steps);
  state.counters["rhs_evaluations"] = static_cast<double>(s.rhs_evaluations);
  state.counters["impacts"] = s.impacts;
  state.counters["contact_episodes"] = s.contact_episodes;
}

void BM_ThesisPass(benchmark::State& state) { pass_benchmark(state, PassOptions{}, run_thesis_pass); }
BENCHMARK(BM_ThesisPass)->Args({5, 550})->Args({5, 3000})->Args({10, 550})->Args({10, 3000})->Unit(benchmark::kMillisecond);

void BM_AdaptivePass(benchmark::State& state) {
  PassOptions opt;
  opt.rtol = 1e-8;
  pass_benchmark(state, opt, run_adaptive_pass);
}
BENCHMARK(BM_AdaptivePass)->Args({5, 550})->Args({5, 3000})->Args({10, 550})->Args({10, 3000})->Unit(benchmark::kMillisecond);

// The 80 Table 5-2 cases (default configuration otherwise: adaptive, rtol 1e-9), on `threads` threads.
void BM_Table52Grid(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  std::vector<Config> cases = table_5_2_cases();
  for (Config& c : cases) c.output_interval_s = 1e30;
  for (auto _ : state) {
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
      for (std::size_t i; (i = next.fetch_add(1)) < cases.size();) benchmark::DoNotOptimize(cases[i].run_pass().summary.impacts);
    };
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
    for (std::thread& t : pool) t.join();
  }
  state.counters["cases"] = static_cast<double>(cases.size());
}
BENCHMARK(BM_Table52Grid)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
