// Streamed output (PassFiles): the files equal those of an in-memory pass; while the pass runs the
// folder holds no summary.json (an older one is removed first), so it never looks complete when it
// is not; a writer that is not committed leaves no temporary behind; memory stays bounded.
#include "rotbeam/case.hpp"
#include "rotbeam/pass_output.hpp"
#include "rotbeam/process_memory.hpp"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <unistd.h>

using namespace rotbeam;
namespace fs = std::filesystem;

namespace {
fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("rotbeam-files-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(d);
  return d;
}
std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
// Forwards to the files and looks at the folder while the pass runs.
struct Watching : PassSink {
  PassFiles& files;
  fs::path dir;
  int rows = 0;
  bool summary_seen = false;
  Watching(PassFiles& f, fs::path d) : files(f), dir(std::move(d)) {}
  void row(const HistoryRow& r) override {
    files.row(r);
    if (++rows % 100 == 0) summary_seen |= fs::exists(dir / "summary.json");
  }
  void event(const PassEvent& e) override { files.event(e); }
};
}  // namespace

TEST(PassFiles, StreamedFilesEqualTheInMemoryOnesAndTheFolderIsNeverCompleteEarly) {
  const Config config = load_config_string("", {"hub.speed_rpm=1000"});
  const Case c = build_case(config);
  const fs::path dir = fresh_dir("equal");
  fs::create_directories(dir);
  std::ofstream(dir / "summary.json") << "{\"an\": \"older run\"}\n";
  const PassResult memory = run_case(c);
  PassResult streamed;
  {
    PassFiles files(dir, config.beam.modes);
    EXPECT_FALSE(fs::exists(dir / "summary.json")) << "an older summary must go before the new run writes";
    Watching watch(files, dir);
    streamed = run_case(c, {&watch, nullptr});
    EXPECT_GT(watch.rows, 100);
    EXPECT_FALSE(watch.summary_seen);
    EXPECT_FALSE(fs::exists(dir / "history.csv"));
    files.commit(streamed, config, *c.surface);
  }
  EXPECT_EQ(slurp(dir / "history.csv"), history_csv(memory, config.beam.modes));
  EXPECT_EQ(slurp(dir / "events.csv"), events_csv(memory));
  const auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  EXPECT_EQ(j["impacts"], memory.summary.impacts);
  EXPECT_EQ(j["surface"]["shape"], "plane");
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  fs::remove_all(dir);
}

TEST(PassFiles, AnUncommittedWriterLeavesNoTemporaries) {
  const fs::path dir = fresh_dir("abandoned");
  {
    PassFiles files(dir, 5);
    HistoryRow row;
    row.q = row.qd = Eigen::VectorXd::Zero(5);
    files.row(row);
  }
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

// A writer that fails after taking the folder's lock (here: an older summary.json that is a
// non-empty folder and cannot be removed) throws with the reason and leaves no lock file behind.
TEST(PassFiles, AWriterThatCannotStartLeavesNoLock) {
  // A folder under a name the run writes (empty or not) made the last rename fail after the whole
  // computation, or was removed as an "older summary": refused before anything is run or touched.
  for (const std::string name : {"history.csv", "events.csv", "revolutions.csv", "summary.json"}) {
    for (const bool empty : {true, false}) {
      const fs::path dir = fresh_dir("cannot-start");
      fs::create_directories(empty ? dir / name : dir / name / "inside");
      try {
        PassFiles files(dir, 5);
        ADD_FAILURE() << "the writer started over a folder named " << name;
      } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(name + ": is a folder"), std::string::npos) << e.what();
      }
      EXPECT_FALSE(fs::exists(dir / ".rotbeam.lock"));
      std::vector<std::string> left;
      for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
      EXPECT_EQ(left, std::vector<std::string>{name});
      EXPECT_TRUE(fs::is_directory(dir / name));
      fs::remove_all(dir);
    }
  }
}

TEST(PassFiles, MemoryStaysBoundedWhileManyRowsStream) {
  // Every accepted step sampled (~34 000 rows of 10 modes, thesis scheme): streaming must not grow the
  // resident set by more than a few MiB (the 1 MiB write buffers), where keeping the rows takes
  // about 8 MiB. The streaming pass runs first, on a fresh heap.
  const Config config =
      load_config_string("", {"simulation.scheme=thesis", "output.interval_s=0", "beam.modes=10"});
  const Case c = build_case(config);
  const fs::path dir = fresh_dir("bounded");
  double streaming_growth = 0.0;
  {
    PassFiles files(dir, config.beam.modes);
    const double before = resident_memory_mib();
    const PassResult r = run_case(c, {&files, nullptr});
    streaming_growth = resident_memory_mib() - before;
    files.commit(r, config, *c.surface);
  }
  const double before = resident_memory_mib();
  const PassResult kept = run_case(c);
  const double memory_growth = resident_memory_mib() - before;
  std::printf("%zu rows: resident growth %.1f MiB streamed, %.1f MiB kept in memory\n", kept.history.size(),
              streaming_growth, memory_growth);
  EXPECT_GT(kept.history.size(), 30000u);
#if !defined(__SANITIZE_ADDRESS__)
  EXPECT_LT(streaming_growth, 4.0);
  EXPECT_GT(memory_growth, 6.0);  // measured 8.0 MiB
#endif
  fs::remove_all(dir);
}

TEST(PassFiles, OneRunAtATimeInAFolderAndLeftoversOfAKilledRunAreRemoved) {
  // Two writers on one folder: the second stops at once (two runs into one -o could mix their files).
  // A killed run's temporaries are removed by the next writer (it holds the lock, so they are stale).
  const fs::path dir = fresh_dir("lock");
  fs::create_directories(dir);
  std::ofstream(dir / "history.csv.tmp.999999") << "partial\n";
  std::ofstream(dir / "events.csv.tmp.999999.3") << "partial\n";
  // A user's files that only look alike are not the writer's: kept.
  const std::vector<std::string> users = {"history.csv.tmp.backup", "history.csv.tmp.", "events.csv.tmp.12.x",
                                          "summary.json.tmp.1 2"};
  for (const std::string& name : users) std::ofstream(dir / name) << "mine\n";
  // The pictures an older run's `plot` and `animate` drew here (beside its summary.json) describe
  // that run: removed. Other pictures (a Campbell diagram, a user's) stay; in a folder that held no
  // run, even those of the drawn names stay (Reliability.AFolderThatHeldNoRunKeepsTheUsersPictures).
  // (A run's summary: its config and files; a user's {} would not count, Reliability.
  // AFolderThatHeldNoRunKeepsTheUsersPictures.)
  std::ofstream(dir / "summary.json") << "{\"config\": {}, \"files\": {}}\n";
  const std::vector<std::string> drawn = {"tip_path.png", "energy.png", "animation.gif", "animation.mp4"};
  for (const std::string& name : drawn) std::ofstream(dir / name) << "old run\n";
  std::ofstream(dir / "campbell.png") << "mine\n";
  {
    PassFiles first(dir, 5);
    EXPECT_FALSE(fs::exists(dir / "history.csv.tmp.999999"));
    EXPECT_FALSE(fs::exists(dir / "events.csv.tmp.999999.3"));
    for (const std::string& name : users) EXPECT_TRUE(fs::exists(dir / name)) << name;
    for (const std::string& name : drawn) EXPECT_FALSE(fs::exists(dir / name)) << name;
    EXPECT_TRUE(fs::exists(dir / "campbell.png"));
    EXPECT_THROW(PassFiles(dir, 5), std::runtime_error);
  }
  PassFiles again(dir, 5);  // the lock went with the first writer
  fs::remove_all(dir);
}

TEST(PassFiles, TheHistoryEstimateMatchesWhatARunWrites) {
  // estimate_history predicts the rows and bytes of history.csv before a run (the disk check and
  // the size note depend on it), over one pass (rigid and flexible starts, another speed and
  // interval) and many revolutions keeping two. Far from the surface rows come at the interval and
  // the rigid turn's are counted exactly; near the surface they come at near_surface_interval_s
  // over a stretch that the bounce and rub set and the estimate takes from the undeformed tip, so
  // it is within −15 % … +25 % of the rows and bytes written. min_rows, which refuses a run that
  // cannot fit, must never exceed what is written. (Where the steps are longer than the interval
  // there are fewer rows: the estimate is then an upper bound. The adaptive scheme's steps at
  // 3000 rpm are ~10 µs with the integrating factor, so that case samples every 20 µs.) With
  // simulation.end_when_clear the pass may end early: the estimate says it is an upper bound.
  const std::vector<std::vector<std::string>> cases = {
      {},
      {"hub.speed_rpm=3000", "output.interval_s=2e-5"},
      {"initial.modal_velocity=[0.1,0,0,0,0]", "simulation.end_angle_deg=30"},
      {"hub.speed_rpm=300", "beam.modes=3", "simulation.revolutions=3", "output.history_revolutions=2",
       "beam.damping_ratio=0.02", "output.interval_s=5e-5"},
  };
  int k = 0;
  for (const auto& overrides : cases) {
    const Config config = load_config(std::nullopt, overrides);
    const Case c = build_case(config);
    const HistoryEstimate e = estimate_history(c);
    ASSERT_TRUE(e.known);
    const fs::path dir = fresh_dir("estimate" + std::to_string(++k));
    {
      PassFiles files(dir, config.beam.modes, config.simulation.history_revolutions);
      const PassResult r = run_case(c, {&files, nullptr, {}});
      ASSERT_FALSE(r.failure) << r.failure->message;
      files.commit(r, config, *c.surface);
    }
    std::ifstream in(dir / "history.csv");
    const double rows = std::count(std::istreambuf_iterator<char>(in), {}, '\n') - 1.0;
    const double bytes = static_cast<double>(fs::file_size(dir / "history.csv"));
    EXPECT_GT(e.rows / rows, 0.85) << k << ": estimated " << e.rows << " rows, wrote " << rows;
    EXPECT_LT(e.rows / rows, 1.25) << k << ": estimated " << e.rows << " rows, wrote " << rows;
    EXPECT_GT(e.csv_bytes / bytes, 0.85) << k << ": estimated " << e.csv_bytes << " bytes, wrote " << bytes;
    EXPECT_LT(e.csv_bytes / bytes, 1.25) << k << ": estimated " << e.csv_bytes << " bytes, wrote " << bytes;
    EXPECT_LE(e.min_rows, rows) << k;
    fs::remove_all(dir);
  }
  EXPECT_FALSE(estimate_history(build_case(load_config(std::nullopt, {}))).upper_bound);
  EXPECT_TRUE(estimate_history(build_case(load_config(std::nullopt, {"simulation.end_when_clear=true"}))).upper_bound);
  // The key named for the sampling is the one that gives most rows (the near-surface one here: the
  // note named output.interval_s, left at its default).
  EXPECT_EQ(estimate_history(build_case(load_config(std::nullopt, {}))).sampling_key, "output.interval_s");
  EXPECT_EQ(estimate_history(build_case(load_config(std::nullopt, {"output.near_surface_gap_m=0.9", "output.near_surface_interval_s=2e-9",
                                                                   "hub.speed_rpm=400"})))
                .sampling_key,
            "output.near_surface_interval_s");
  // Unknown with every step sampled; refused (naming the key) where it cannot fit.
  EXPECT_FALSE(estimate_history(build_case(load_config(std::nullopt, {"output.interval_s=0"}))).known);
  EXPECT_FALSE(estimate_history(build_case(load_config(std::nullopt, {"output.near_surface_interval_s=0"}))).known);
  const Case slow = build_case(load_config(std::nullopt, {"hub.speed_rpm=0.5"}));
  try {
    check_history_fits(slow, 1e8, false);
    ADD_FAILURE() << "a 2.4 GB history was let onto 100 MB";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("output.interval_s = 1e-05: the history would hold about", 0), 0u) << e.what();
  }
  EXPECT_NO_THROW(check_history_fits(slow, 1e10, false));
  EXPECT_NO_THROW(check_history_fits(slow, 0.0, true));  // unknown: no check
}

TEST(PassFiles, TheStepEstimateBoundsTheStepsARunTakes) {
  // estimate_steps announces a long pass before it runs (the step keys' ranges cannot bound the
  // cost). The adaptive scheme's steps are at most simulation.max_step_s, so span / max_step_s is a
  // lower bound; with the maximum step short enough to set the steps (1 µs, the base case's free
  // flight takes longer ones) it is within 20 % of them. The thesis scheme's is an estimate from
  // above (its contact stretch counted whole, at the fine step when that is shorter): never below
  // the steps taken, and within 100× of them on the base case (the fine step serves only where
  // |λ| < fine_below_n). Without it a run of 3e9 steps started with nothing said but an ETA in seconds.
  {
    const Config config = load_config(std::nullopt, {"simulation.max_step_s=1e-6"});
    const Case c = build_case(config);
    const StepEstimate e = estimate_steps(c);
    EXPECT_TRUE(e.at_least);
    EXPECT_EQ(e.key, "simulation.max_step_s");
    const PassResult r = run_case(c);
    ASSERT_FALSE(r.failure);
    EXPECT_LE(e.steps, r.summary.steps);
    EXPECT_GT(e.steps, r.summary.steps / 1.2);
  }
  for (const std::vector<std::string>& overrides :
       {std::vector<std::string>{"simulation.scheme=\"thesis\""},
        std::vector<std::string>{"simulation.scheme=\"thesis\"", "simulation.fine_below_n=0"},
        std::vector<std::string>{"simulation.scheme=\"thesis\"", "hub.speed_rpm=3000"}}) {
    const Config config = load_config(std::nullopt, overrides);
    const Case c = build_case(config);
    const StepEstimate e = estimate_steps(c);
    EXPECT_FALSE(e.at_least);
    const PassResult r = run_case(c);
    ASSERT_FALSE(r.failure) << overrides.back();
    EXPECT_GE(e.steps, r.summary.steps) << overrides.back();
    EXPECT_LT(e.steps, 100.0 * r.summary.steps) << overrides.back();
  }
}
