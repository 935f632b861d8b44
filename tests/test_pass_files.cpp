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
  {
    PassFiles first(dir, 5);
    EXPECT_FALSE(fs::exists(dir / "history.csv.tmp.999999"));
    EXPECT_THROW(PassFiles(dir, 5), std::runtime_error);
  }
  PassFiles again(dir, 5);  // the lock went with the first writer
  fs::remove_all(dir);
}
