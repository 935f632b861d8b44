// The one job runner (sweep, converge, reproduce): every job of a shard runs once, shards partition
// the jobs deterministically, threads are bounded, a stop ends it early, a job's exception surfaces.
#include "rotbeam/job_runner.hpp"

#include <atomic>
#include <gtest/gtest.h>
#include <mutex>
#include <set>
#include <stdexcept>

using namespace rotbeam;

TEST(JobRunner, EveryJobRunsOnceAndShardsPartitionTheJobs) {
  const std::size_t count = 103;
  std::set<std::size_t> all;
  for (int shards : {1, 3, 7}) {
    std::set<std::size_t> seen;
    for (int i = 0; i < shards; ++i) {
      std::mutex m;
      std::vector<std::size_t> ran_here;
      JobRunnerOptions o;
      o.threads = 3;
      o.shard = {i, shards};
      const std::vector<std::size_t> done = run_jobs(
          count,
          [&](std::size_t j) {
            std::lock_guard<std::mutex> lock(m);
            ran_here.push_back(j);
          },
          o);
      EXPECT_EQ(done.size(), ran_here.size());
      for (std::size_t j : done) {
        EXPECT_EQ(static_cast<int>(j % shards), i) << "job " << j << " in shard " << i << "/" << shards;
        EXPECT_TRUE(seen.insert(j).second) << "job " << j << " ran twice";
      }
      EXPECT_TRUE(std::is_sorted(done.begin(), done.end()));
    }
    EXPECT_EQ(seen.size(), count) << shards << " shards";
  }
}

TEST(JobRunner, ManyRequestedThreadsAreBoundedAndProgressIsComplete) {
  // More threads than jobs (the --jobs 40000 of a user) must neither abort nor start idle threads.
  std::atomic<int> calls{0};
  std::size_t last_finished = 0, total = 0;
  JobRunnerOptions o;
  o.threads = 40000;
  o.on_job_finished = [&](const JobProgress& p) {
    EXPECT_EQ(p.finished, last_finished + 1);
    last_finished = p.finished;
    total = p.total;
  };
  run_jobs(5, [&](std::size_t) { ++calls; }, o);
  EXPECT_EQ(calls.load(), 5);
  EXPECT_EQ(last_finished, 5u);
  EXPECT_EQ(total, 5u);
}

TEST(JobRunner, AStopRequestStartsNoFurtherJob) {
  StopToken stop;
  std::atomic<int> calls{0};
  JobRunnerOptions o;
  o.threads = 1;
  o.stop = &stop;
  const auto done = run_jobs(
      50,
      [&](std::size_t j) {
        ++calls;
        if (j == 9) stop.request_stop();
      },
      o);
  EXPECT_EQ(calls.load(), 10);
  EXPECT_EQ(done.size(), 10u);
}

TEST(JobRunner, AJobsExceptionSurfacesAfterTheOthersFinish) {
  JobRunnerOptions o;
  o.threads = 2;
  EXPECT_THROW(run_jobs(
                   20,
                   [](std::size_t j) {
                     if (j == 4) throw std::runtime_error("job 4 failed");
                   },
                   o),
               std::runtime_error);
  o.shard = {3, 3};
  EXPECT_THROW(run_jobs(3, [](std::size_t) {}, o), std::invalid_argument);
}
