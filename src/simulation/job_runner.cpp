#include "rotbeam/job_runner.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <system_error>
#include <thread>

namespace rotbeam {

int default_threads(int requested) {
  return requested > 0 ? requested : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

std::vector<std::size_t> run_jobs(std::size_t count, const std::function<void(std::size_t)>& job,
                                  const JobRunnerOptions& options) {
  if (options.shard.count < 1 || options.shard.index < 0 || options.shard.index >= options.shard.count)
    throw std::invalid_argument("shard " + std::to_string(options.shard.index) + "/" +
                                std::to_string(options.shard.count) + ": need 0 <= i < N");
  std::vector<std::size_t> mine;
  for (std::size_t j = 0; j < count; ++j)
    if (options.shard.contains(j)) mine.push_back(j);

  std::mutex mutex;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> abort{false};
  std::exception_ptr error;
  std::vector<char> ran(mine.size(), 0);
  JobProgress progress;
  progress.total = mine.size();
  const auto t0 = std::chrono::steady_clock::now();
  auto worker = [&] {
    for (std::size_t k; (k = next.fetch_add(1)) < mine.size();) {
      if (abort.load() || (options.stop && options.stop->stop_requested())) break;
      try {
        job(mine[k]);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        abort.store(true);
        break;
      }
      std::lock_guard<std::mutex> lock(mutex);
      ran[k] = 1;
      ++progress.finished;
      progress.job = mine[k];
      progress.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      progress.eta_s = progress.elapsed_s / static_cast<double>(progress.finished) *
                       static_cast<double>(progress.total - progress.finished);
      if (options.on_job_finished) options.on_job_finished(progress);
    }
  };
  const std::size_t wanted = std::min<std::size_t>(
      {static_cast<std::size_t>(default_threads(options.threads)), mine.size(), static_cast<std::size_t>(kMaxJobThreads)});
  std::vector<std::thread> pool;
  for (std::size_t i = 1; i < wanted; ++i) {
    try {
      pool.emplace_back(worker);
    } catch (const std::system_error&) {
      break;  // the machine will not give more threads: run on those we have
    }
  }
  worker();  // the calling thread works too
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  std::vector<std::size_t> done;
  for (std::size_t k = 0; k < mine.size(); ++k)
    if (ran[k]) done.push_back(mine[k]);
  return done;
}

}  // namespace rotbeam
