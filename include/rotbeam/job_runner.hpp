// The one job runner of the studies (sweep, converge, reproduce): independent jobs 0…count−1 on a
// pool of threads, handed out in index order, with progress, a stop token, and a deterministic
// shard i of N (the jobs whose index ≡ i mod N) for spreading a study over processes or machines.
#pragma once

#include "rotbeam/stop_token.hpp"

#include <cstddef>
#include <functional>
#include <vector>

namespace rotbeam {

/// Shard `index` of `count`: the jobs j with j mod count = index (0 ≤ index < count).
struct Shard {
  int index = 0;
  int count = 1;
  bool contains(std::size_t job) const { return static_cast<int>(job % static_cast<std::size_t>(count)) == index; }
};

struct JobProgress {
  std::size_t total = 0;     // jobs in the shard
  std::size_t finished = 0;  // jobs finished so far (this one included)
  std::size_t job = 0;       // the job that just finished
  double elapsed_s = 0;
  double eta_s = 0;          // remaining time at the mean rate so far
};

struct JobRunnerOptions {
  int threads = 0;                 // 0: all cores; never more than the jobs to run
  Shard shard;
  const StopToken* stop = nullptr; // when requested, no further job starts
  std::function<void(const JobProgress&)> on_job_finished;  // called under the runner's lock
};

/// Largest thread count a runner starts (more would only queue on the cores).
inline constexpr int kMaxJobThreads = 256;

/// Runs job(j) for every j < count in the shard, on min(threads, jobs, kMaxJobThreads) threads
/// (the calling thread among them if no thread can be started). Jobs must not throw; if one does,
/// no further job starts and the first exception is rethrown after the running ones finish.
/// Returns the jobs that ran, in index order.
std::vector<std::size_t> run_jobs(std::size_t count, const std::function<void(std::size_t)>& job,
                                  const JobRunnerOptions& options = {});

/// Threads for a `--jobs` value: 0 → the machine's cores.
int default_threads(int requested);

}  // namespace rotbeam
