// Long run: N passes in one process over the 80 Table 5-2 cases (cycled), on T threads.
// Reports the resident memory as the passes accumulate and checks that every pass gives exactly
// the summary of the first pass of the same case.
//   long_run [N=1000] [T=2]
#include "rotbeam/case.hpp"
#include "rotbeam/pass_output.hpp"
#include "rotbeam/process_memory.hpp"
#include "table_5_2.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <thread>

using namespace rotbeam;

int main(int argc, char** argv) {
  const int passes = argc > 1 ? std::atoi(argv[1]) : 1000;
  const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
  const std::vector<Config> cases = table_5_2_cases();
  auto fingerprint = [](const PassResult& r, const Config& c, const Surface& surface) {
    nlohmann::json j = summary_json(r, c, surface);
    j.erase("wall_time_s");
    return j.dump() + std::to_string(r.history.size()) + std::to_string(r.history.back().jacobi);
  };
  std::vector<std::string> reference(cases.size());
  std::mutex mutex;
  std::atomic<int> next{0}, done{0}, mismatches{0};
  const double rss_start = resident_memory_mib();
  std::printf("passes  resident_MiB\n%6d  %12.1f\n", 0, rss_start);
  const auto t0 = std::chrono::steady_clock::now();
  auto worker = [&] {
    for (int i; (i = next.fetch_add(1)) < passes;) {
      const std::size_t k = static_cast<std::size_t>(i) % cases.size();
      const Case cs = build_case(cases[k]);
      const PassResult r = run_case(cs);
      const std::string f = fingerprint(r, cases[k], *cs.surface);
      std::lock_guard<std::mutex> lock(mutex);
      if (reference[k].empty())
        reference[k] = f;
      else if (reference[k] != f)
        ++mismatches;
      const int d = ++done;
      if (d == 80 || d % 200 == 0 || d == passes) std::printf("%6d  %12.1f\n", d, resident_memory_mib());
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%d passes on %d threads in %.1f s; results differing from the first pass of their case: %d\n", passes,
              threads, seconds, mismatches.load());
  return mismatches.load() == 0 ? 0 : 1;
}
