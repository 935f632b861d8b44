// The rotbeam binary as a user runs it: outputs, JSON field names (docs/model.md §7), exit codes.
#include "rotbeam/config.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "process_support.hpp"

namespace fs = std::filesystem;

namespace {
struct CliRun {
  int status;
  std::string out;
  std::string err;
};

CliRun run(const std::string& args, const std::string& environment = "") {
  // One file per process and call: ctest runs the cases of this file in parallel processes.
  static int calls = 0;
  const std::string err_file = ::testing::TempDir() + "rotbeam_cli_stderr_" + std::to_string(getpid()) + "_" +
                               std::to_string(++calls) + ".txt";
  const std::string cmd = environment + " " + std::string(ROTBEAM_CLI) + " " + args + " 2>" + err_file;
  CliRun r{};
  FILE* pipe = popen(cmd.c_str(), "r");
  std::array<char, 4096> buf{};
  while (std::size_t got = fread(buf.data(), 1, buf.size(), pipe)) r.out.append(buf.data(), got);
  const int st = pclose(pipe);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  if (FILE* f = fopen(err_file.c_str(), "r")) {
    while (std::size_t got = fread(buf.data(), 1, buf.size(), f)) r.err.append(buf.data(), got);
    fclose(f);
  }
  r.err = rotbeam::test::without_progress_lines(r.err);
  std::remove(err_file.c_str());
  return r;
}
}  // namespace

TEST(Cli, ImpactPrintsTheBaseCaseTableRow) {
  const CliRun r = run("impact");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("550 | 1.0319 | -0.5129 | 1.5448"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("-8.1096"), std::string::npos);
}

TEST(Cli, ImpactJsonHasTheStableFieldNames) {
  const CliRun r = run("impact --set hub.speed_rpm=3000 --set initial.modal_velocity=[2,0,0,0,0] --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* k : {"t_s", "theta_deg", "y_tip_m", "vx_before_m_s", "vx_after_m_s", "delta_vx_m_s", "restitution"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_NEAR(j["vx_before_m_s"].get<double>(), 5.0358, 0.5e-4);
  EXPECT_NEAR(j["vx_after_m_s"].get<double>(), -1.6842, 0.5e-4);
  EXPECT_EQ(j["config"]["initial"]["start"], "flexible");
}

TEST(Cli, ModesJsonIsOneRowPerSpeedAscending) {
  const CliRun r = run("modes --speeds-rpm 0:3000:4 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["speeds_rpm"].size(), 4u);
  EXPECT_EQ(j["speeds_rpm"][1].get<double>(), 1000.0);
  ASSERT_EQ(j["frequencies_hz"].size(), 4u);
  EXPECT_EQ(j["frequencies_hz"][0].size(), 5u);
  EXPECT_NEAR(j["frequencies_hz"][0][0].get<double>(), 93.603, 1e-3);
  EXPECT_LT(j["frequencies_hz"][0][0].get<double>(), j["frequencies_hz"][3][0].get<double>());
}

TEST(Cli, ModesDefaultTableAndCsv) {
  const CliRun r = run("modes");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("f5_hz"), std::string::npos);
  EXPECT_NE(r.out.find("3000.0"), std::string::npos);
  const std::string csv = ::testing::TempDir() + "rotbeam_modes_" + std::to_string(getpid()) + ".csv";
  ASSERT_EQ(run("modes --speeds-rpm 550 --csv " + csv).status, 0);
  FILE* f = fopen(csv.c_str(), "r");
  ASSERT_NE(f, nullptr);
  char line[256];
  ASSERT_NE(fgets(line, sizeof line, f), nullptr);
  fclose(f);
  EXPECT_EQ(std::string(line), "speed_rpm,f1_hz,f2_hz,f3_hz,f4_hz,f5_hz\n");
}

TEST(Cli, HelpOnEachCommand) {
  for (const char* c : {"--help", "modes --help", "impact --help"}) {
    const CliRun r = run(c);
    EXPECT_EQ(r.status, 0) << c;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << c;
  }
}

TEST(Cli, BadInputIsOneLineNamingTheKeyWithExitCode2) {
  struct Bad {
    const char* args;
    const char* names;
  };
  for (const Bad& b : {Bad{"impact --set surface.depth_fraction=-1", "surface.depth_fraction"},
                       Bad{"impact --set hub.sped_rpm=3", "hub.speed_rpm"},
                       Bad{"impact /nonexistent.toml", "/nonexistent.toml"},
                       Bad{"modes --speeds-rpm 0:x:3", "--speeds-rpm"},
                       Bad{"modes --csv /nonexistent-dir/x.csv", "/nonexistent-dir/x.csv"},
                       Bad{"frobnicate", "frobnicate"}}) {
    const CliRun r = run(b.args);
    EXPECT_NE(r.status, 0) << b.args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << b.args << ": " << r.err;
    EXPECT_NE(r.err.find(b.names), std::string::npos) << b.args << ": " << r.err;
  }
  EXPECT_EQ(run("impact --set beam.modes=0").status, 2);
}

TEST(Cli, NoImpactBeforeTheEndAngleIsReported) {
  const CliRun r = run("impact --set initial.modal_velocity=[0.1,0,0,0,0] --set simulation.end_angle_deg=-20");
  EXPECT_EQ(r.status, 3);
  EXPECT_NE(r.err.find("no impact"), std::string::npos) << r.err;
}

namespace {
std::string slurp(const std::string& path) {
  std::string s;
  if (FILE* f = fopen(path.c_str(), "r")) {
    std::array<char, 4096> buf{};
    while (std::size_t got = fread(buf.data(), 1, buf.size(), f)) s.append(buf.data(), got);
    fclose(f);
  }
  return s;
}
}  // namespace

TEST(Cli, RunWritesHistoryEventsAndSummary) {
  const std::string dir = ::testing::TempDir() + "rotbeam_run_base_" + std::to_string(getpid());
  const CliRun r = run("run -o " + dir);
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* line : {"impacts", "contact episodes", "contact span", "peak normal force", "normal impulse"})
    EXPECT_NE(r.out.find(line), std::string::npos) << line;
  const auto j = nlohmann::json::parse(slurp(dir + "/summary.json"));
  for (const char* k : {"impacts", "contact_episodes", "first_impact_deg", "last_separation_deg", "contact_time_s",
                        "peak_normal_force_n", "normal_impulse_n_s", "friction_work_j", "max_tip_deflection_ratio",
                        "energy_audit_residual", "steps", "rhs_evaluations", "wall_time_s", "scheme", "warnings",
                        "config", "contact_intervals", "failure"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["scheme"], "adaptive");
  EXPECT_TRUE(j["failure"].is_null());
  EXPECT_NEAR(j["first_impact_deg"].get<double>(), -8.1096, 1e-4);
  EXPECT_GT(j["impacts"].get<int>(), 1);
  EXPECT_GT(j["max_tip_deflection_ratio"].get<double>(), 0.1);
  EXPECT_FALSE(j["warnings"].empty());  // the validity warning of docs/model.md §10
  const std::string history = slurp(dir + "/history.csv");
  EXPECT_EQ(history.rfind("t_s,theta_deg,phase,x_tip_m,y_tip_m,gap_m,vx_m_s,vy_m_s,normal_force_n,friction_force_n,"
                          "lambda_n,q1_m,",
                          0),
            0u);
  EXPECT_NE(history.find(",contact,"), std::string::npos);
  const std::string events = slurp(dir + "/events.csv");
  EXPECT_NE(events.find(",impact,"), std::string::npos);
  EXPECT_NE(events.find(",contact_start,"), std::string::npos);
  EXPECT_NE(events.find(",end,"), std::string::npos);
}

TEST(Cli, RunHistoryIntervalIsConfigurable) {
  const std::string a = ::testing::TempDir() + "rotbeam_run_i1_" + std::to_string(getpid()),
                    b = ::testing::TempDir() + "rotbeam_run_i2_" + std::to_string(getpid());
  // Near-surface rows off, so that the interval alone sets the sampling.
  ASSERT_EQ(run("run --set output.interval_s=1e-4 --set output.near_surface_gap_m=0 -o " + a).status, 0);
  ASSERT_EQ(run("run --set output.interval_s=1e-5 --set output.near_surface_gap_m=0 -o " + b).status, 0);
  const auto lines = [](const std::string& s) { return std::count(s.begin(), s.end(), '\n'); };
  EXPECT_LT(lines(slurp(a + "/history.csv")) * 3, lines(slurp(b + "/history.csv")));
  EXPECT_EQ(slurp(a + "/events.csv"), slurp(b + "/events.csv"));  // events do not depend on sampling
}

TEST(Cli, RunReportsANumericalFailureAndKeepsThePartialResult) {
  // One corrector iteration cannot meet the tolerance: a diagnosed stop with t and θ, exit code 6.
  const std::string dir = ::testing::TempDir() + "rotbeam_run_fail_" + std::to_string(getpid());
  const CliRun r = run("run --set simulation.scheme=thesis --set simulation.corrector_max_iterations=1 "
                       "--set impact.plastic_below_m_s=10 -o " + dir);
  EXPECT_EQ(r.status, 6) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("corrector"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("θ = "), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(slurp(dir + "/summary.json"));
  EXPECT_EQ(j["failure"]["kind"], "corrector");
  EXPECT_GT(j["steps"].get<long>(), 0);
}

TEST(Cli, RunRejectsAnUnwritableOutputFolder) {
  const CliRun r = run("run -o /proc/rotbeam-cannot-write-here");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("/proc/rotbeam-cannot-write-here"), std::string::npos) << r.err;
}

TEST(Cli, ConvergePrintsItsTableAndJson) {
  const std::string args = "converge --set simulation.end_angle_deg=-5 --rtols 1e-8,1e-10 --steps 1e-6 --modes 3";
  const CliRun r = run(args);
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* s : {"adaptive rtol=1e-10 (reference)", "adaptive rtol=1e-08", "thesis h=1e-06/1e-07", "modes=3",
                        "sep_deg", "impulse_mNs"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s << "\n" << r.out;
  const CliRun j = run(args + " --json");
  ASSERT_EQ(j.status, 0) << j.err;
  const auto doc = nlohmann::json::parse(j.out);
  ASSERT_EQ(doc["runs"].size(), 4u);
  EXPECT_TRUE(doc["runs"][0]["reference"].get<bool>());
  EXPECT_EQ(doc["runs"][0]["difference"]["normal_impulse_rel"].get<double>(), 0.0);
  EXPECT_TRUE(doc["runs"][2]["metrics"].contains("normal_impulse_n_s"));
  EXPECT_NE(run("converge --rtols 1e-8,abc").status, 0);
}

TEST(Cli, WarningsAreEventsToo) {
  // docs/model.md §7: warnings are events; the base case passes the validity threshold (|y_t|/L > 0.1).
  const std::string dir = ::testing::TempDir() + "rotbeam_run_warn_" + std::to_string(getpid());
  ASSERT_EQ(run("run --set output.interval_s=1e-3 -o " + dir).status, 0);
  const std::string events = slurp(dir + "/events.csv");
  EXPECT_NE(events.find(",warning,"), std::string::npos) << events.substr(0, 500);
  EXPECT_NE(events.find("tip deflection exceeds 0.1"), std::string::npos);
}

// Results that cannot be written to standard output (a full disk) are a failure with a one-line
// reason, never a silent success.
TEST(Cli, AnUnwritableStandardOutputIsAFailure) {
  for (const char* args : {"impact >/dev/full", "modes --json >/dev/full", "--help >/dev/full", "run --help >/dev/full", "--version >/dev/full"}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.status, 1) << args;
    EXPECT_NE(r.err.find("standard output: the results could not be written"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

// The plotting module cannot start (no such interpreter) or lacks its libraries: exit 1 with one
// line that says which, never a traceback or the shell's 127.
TEST(Cli, APlottingModuleThatCannotStartSaysWhyInOneLine) {
  const std::string png = ::testing::TempDir() + "rotbeam_cli_noplot_" + std::to_string(getpid()) + ".png";
  const CliRun none = run("modes --plot " + png, "ROTBEAM_PYTHON=/nonexistent/python3");
  EXPECT_EQ(none.status, 1);
  EXPECT_EQ(std::count(none.err.begin(), none.err.end(), '\n'), 1) << none.err;
  EXPECT_NE(none.err.find("cannot run the plotting module: /nonexistent/python3"), std::string::npos) << none.err;
  // A matplotlib that fails to import, ahead of the real one on the path (needs the package built
  // beside the binary: the sanitizer build has none).
  const fs::path package = fs::path(ROTBEAM_CLI).parent_path() / "python";
  if (!fs::exists(package / "rotbeam" / "plots.py")) GTEST_SKIP() << "built without the Python package";
  const fs::path fake = fs::path(::testing::TempDir()) / ("rotbeam_cli_fake_mpl_" + std::to_string(getpid()));
  fs::create_directories(fake / "matplotlib");
  std::ofstream(fake / "matplotlib" / "__init__.py") << "raise ImportError(\"No module named 'matplotlib'\")\n";
  const CliRun missing =
      run("modes --plot " + png, "ROTBEAM_PYTHONPATH=" + fake.string() + ":" + package.string());
  EXPECT_EQ(missing.status, 1);
  EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << missing.err;
  EXPECT_NE(missing.err.find("needs numpy and matplotlib"), std::string::npos) << missing.err;
  EXPECT_FALSE(fs::exists(png));
  fs::remove_all(fake);
}

// A file named with --csv that is a symbolic link is written through (the link stays, its target
// gets the table); a node that is not a regular file is written into, never replaced by a file
// (it replaced the link, and /dev/stdout, by a regular file).
TEST(Cli, AnOutputFileThatIsALinkOrADeviceIsWrittenThrough) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("rotbeam_cli_link_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "real.csv") << "target\n";
  fs::create_symlink("real.csv", dir / "link.csv");
  const CliRun linked = run("modes --csv " + (dir / "link.csv").string());
  EXPECT_EQ(linked.status, 0) << linked.err;
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "link.csv")));
  EXPECT_EQ(slurp((dir / "real.csv").string()).rfind("speed_rpm,f1_hz", 0), 0u);
  fs::create_symlink("new.csv", dir / "dangling.csv");
  EXPECT_EQ(run("modes --csv " + (dir / "dangling.csv").string()).status, 0);
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "dangling.csv")));
  EXPECT_EQ(slurp((dir / "new.csv").string()).rfind("speed_rpm,f1_hz", 0), 0u);
  // A link to the process's standard output, as /dev/stdout is: the table arrives on the pipe, and
  // the link stays.
  fs::create_symlink("/proc/self/fd/1", dir / "stdout");
  const CliRun out = run("modes --csv " + (dir / "stdout").string());
  EXPECT_EQ(out.status, 0) << out.err;
  EXPECT_NE(out.out.find("speed_rpm,f1_hz"), std::string::npos) << out.out;
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "stdout")));
  // The same with standard output sent to a file: the table is in that file, written in place.
  const CliRun to_file = run("modes --csv " + (dir / "stdout").string() + " > " + (dir / "shell.txt").string());
  EXPECT_EQ(to_file.status, 0) << to_file.err;
  EXPECT_EQ(slurp((dir / "shell.txt").string()).rfind("speed_rpm,f1_hz", 0), 0u);
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "stdout")));
  fs::remove_all(dir);
}

// The plotting module announces that it started and the code it ends with on a pipe: a program
// that is not the module (ROTBEAM_PYTHON=/bin/true exited 0 silently, /bin/false 1 with nothing
// said, /bin/sh 2, read as "damaged folder") and a module that dies (a signal) are named, exit 1.
TEST(Cli, AChildThatDidNotRunThePlottingModuleIsNamed) {
  const std::string png = ::testing::TempDir() + "rotbeam_cli_child_" + std::to_string(getpid()) + ".png";
  for (const char* python : {"/bin/true", "/bin/false", "/bin/sh"}) {
    const CliRun r = run("modes --plot " + png, std::string("ROTBEAM_PYTHON=") + python);
    EXPECT_EQ(r.status, 1) << python;
    EXPECT_NE(r.err.find(std::string("cannot run the plotting module: ") + python + " -m rotbeam.plots did not start it"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find(std::string("ROTBEAM_PYTHON=") + python), std::string::npos) << r.err;
  }
  const fs::path fake = fs::path(::testing::TempDir()) / ("rotbeam_cli_dies_" + std::to_string(getpid()));
  for (const auto& [body, expected] : std::vector<std::pair<std::string, std::string>>{
           {"kill -9 $$", "stopped before it finished (killed by signal 9 (SIGKILL))"},
           {"exit 2", "stopped before it finished (exit 2)"}}) {
    std::ofstream(fake) << "#!/bin/sh\necho started >&$ROTBEAM_RESULT_FD\n" << body << "\n";
    fs::permissions(fake, fs::perms::owner_all);
    const CliRun r = run("modes --plot " + png, "ROTBEAM_PYTHON=" + fake.string());
    EXPECT_EQ(r.status, 1) << body;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("the plotting module rotbeam.plots " + expected), std::string::npos) << r.err;
  }
  fs::remove(fake);
  EXPECT_FALSE(fs::exists(png));
}

// A reader that leaves early (`| head -1`) is not an error: exit 0 and nothing on stderr (it died
// by SIGPIPE, 141, once the table outgrew the pipe's buffer; 20 000 rows are 1.4 MB, more than a
// pipe holds, 1 MiB at most).
TEST(Cli, AReaderThatLeavesEarlyIsNotAnError) {
  const std::string base = ::testing::TempDir() + "rotbeam_cli_head_" + std::to_string(getpid());
  const std::string cmd = "sh -c '{ " + std::string(ROTBEAM_CLI) + " modes --speeds-rpm 0:1000:20000 2>" + base +
                          ".err; echo $? >" + base + ".status; } | head -1 >/dev/null'";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(slurp(base + ".status"), "0\n");
  EXPECT_EQ(slurp(base + ".err"), "");
  std::remove((base + ".err").c_str());
  std::remove((base + ".status").c_str());
}

// `modes --plot` killed with SIGKILL cannot remove its scratch table from TMPDIR: the next one
// removes the tables of processes that are gone, and nothing else.
TEST(Cli, AKilledPlotsScratchIsRemovedByTheNext) {
  const fs::path tmp = fs::path(::testing::TempDir()) / ("rotbeam_cli_scratch_" + std::to_string(getpid()));
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  // A pid above the kernel's largest (4194304) is never alive.
  std::ofstream(tmp / "rotbeam-modes-9999999-a1B2c3.csv") << "a killed run's\n";
  for (const char* mine : {"rotbeam-modes-notes.csv", "rotbeam-modes-9999999-a1B2c3.csv.bak", "rotbeam-modes-1-abc.csv"})
    std::ofstream(tmp / mine) << "mine\n";
  const CliRun r = run("modes --plot " + (tmp / "c.png").string(), "TMPDIR=" + tmp.string() + " ROTBEAM_PYTHON=/bin/true");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_FALSE(fs::exists(tmp / "rotbeam-modes-9999999-a1B2c3.csv"));
  for (const char* mine : {"rotbeam-modes-notes.csv", "rotbeam-modes-9999999-a1B2c3.csv.bak", "rotbeam-modes-1-abc.csv"})
    EXPECT_TRUE(fs::exists(tmp / mine)) << mine;
  EXPECT_EQ(std::distance(fs::directory_iterator(tmp), fs::directory_iterator()), 3);
  fs::remove_all(tmp);
}

// A key with a NUL or a line break in a file: shown escaped on one whole line (the NUL cut the
// message to "hub.speed", and a line break read as a space).
TEST(Cli, AKeyWithControlCharactersIsShownEscaped) {
  const fs::path toml = fs::path(::testing::TempDir()) / ("rotbeam_cli_nul_key_" + std::to_string(getpid()) + ".toml");
  for (const auto& [escape, shown] : std::vector<std::pair<std::string, std::string>>{{"\\u0000", "\\u0000"}, {"\\n", "\\u000a"}}) {
    std::ofstream(toml) << "[hub]\n\"speed" << escape << "rpm\" = 550\n";
    const CliRun r = run("impact " + toml.string());
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("hub.speed" + shown + "rpm = 550: unknown key"), std::string::npos) << r.err;
  }
  fs::remove(toml);
}

// The depth in a summary line tells 0.999999999 from 1 (it read "100.00 %") and keeps two decimals
// where they say it all.
TEST(Cli, TheDepthIsShownWithTheDigitsThatTellIt) {
  EXPECT_NE(run("impact --set surface.depth_fraction=0.999999999").out.find("depth 99.9999999 %"), std::string::npos);
  EXPECT_NE(run("impact").out.find("depth 2.00 %"), std::string::npos);
}

// A speed below the smallest normal double is a number (read as its nearest double, as TOML reads
// it; it was "not a number"); one beyond the largest double is refused, as such.
TEST(Cli, ASubnormalNumberIsANumber) {
  const CliRun tiny = run("modes --speeds-rpm 1e-320 --json");
  EXPECT_EQ(tiny.status, 0) << tiny.err;
  const CliRun huge = run("modes --speeds-rpm 1e999");
  EXPECT_EQ(huge.status, 2);
  EXPECT_NE(huge.err.find("'1e999' is beyond the largest number"), std::string::npos) << huge.err;
}

// An empty list is refused (it was taken as "not given" and the defaults ran, exit 0).
TEST(Cli, AnEmptyListIsRefused) {
  for (const char* args : {"modes --speeds-rpm ''", "converge --rtols ''", "converge --steps ' '", "converge --modes ''"}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(": an empty list; give values, e.g. "), std::string::npos) << args << ": " << r.err;
  }
}

// The speed column has the digits that tell its rows apart (0:1:100000 printed rows reading 0.0 …
// 1.0, one decimal for steps of 1e-5 rpm), and keeps one decimal where that says it all.
TEST(Cli, ModesSpeedsAreShownWithTheDigitsThatTellThemApart) {
  const CliRun fine = run("modes --speeds-rpm 1:1.0001:3");
  ASSERT_EQ(fine.status, 0) << fine.err;
  for (const char* row : {"\n    1.00000 ", "\n    1.00005 ", "\n    1.00010 "})
    EXPECT_NE(fine.out.find(row), std::string::npos) << row << "\n" << fine.out;
  const CliRun coarse = run("modes --speeds-rpm 0:3000:4");
  ASSERT_EQ(coarse.status, 0) << coarse.err;
  EXPECT_NE(coarse.out.find("\n     1000.0 "), std::string::npos) << coarse.out;
}

// rotbeam `args`, sent SIGINT once the pass is under way (its interrupt handler installed): the
// exit code (128 + the signal if it killed the process) and standard error.
CliRun run_interrupted(const std::string& args) {
  const std::string err_file = ::testing::TempDir() + "rotbeam_cli_interrupted_" + std::to_string(getpid()) + ".txt";
  const pid_t pid = rotbeam::test::start_in_background(std::string(ROTBEAM_CLI) + " " + args + " >/dev/null 2>" + err_file);
  const bool under_way = rotbeam::test::wait_until([&] {
    return rotbeam::test::ended(pid) || rotbeam::test::runs_and_catches(pid, ROTBEAM_CLI, SIGINT);
  }) && !rotbeam::test::ended(pid);
  ::kill(pid, under_way ? SIGINT : SIGKILL);
  CliRun r{rotbeam::test::exit_code(pid), "", slurp(err_file)};
  if (!under_way) r.err += "(not under way: killed)";
  std::remove(err_file.c_str());
  return r;
}

// A pass of billions of steps is announced before it starts, naming the step key (max_step_s =
// 1e-11 s ran for hours with only its progress line, in bare seconds). SIGINT ends it.
TEST(Cli, APassOfBillionsOfStepsIsAnnounced) {
  const std::string out = ::testing::TempDir() + "rotbeam_cli_long_" + std::to_string(getpid());
  const CliRun r = run_interrupted("run --set simulation.max_step_s=1e-11 -o " + out);
  EXPECT_EQ(r.status, 130) << r.err;
  EXPECT_NE(r.err.find("rotbeam: note: simulation.max_step_s = 1e-11: the pass takes at least 2.97e+09 steps (0.0297 s of motion"), std::string::npos)
      << r.err;
  const CliRun thesis = run_interrupted("run --set simulation.scheme=\"thesis\" --set simulation.contact_step_s=1e-12 -o " + out);
  EXPECT_NE(thesis.err.find("rotbeam: note: simulation.contact_step_s = 1e-12: the pass may take up to about 4.91e+09 steps (0.00491 s of contact"), std::string::npos)
      << thesis.err;
  const CliRun base = run("run -o " + out);
  EXPECT_EQ(base.status, 0) << base.err;
  EXPECT_EQ(base.err.find("note"), std::string::npos) << base.err;
  fs::remove_all(out);
}

// Paths that are not there, said as they are: a loop of symbolic links in the system's words (it
// was "no such configuration file"), the empty path as "" (it was nothing before the colon), and a
// folder to draw that does not exist as such (it was "neither a run folder nor a sweep folder").
TEST(Cli, PathsThatAreNotThereAreNamedForWhatTheyAre) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("rotbeam_cli_paths_" + std::to_string(getpid()));
  fs::create_directories(dir);
  fs::create_symlink("loop2", dir / "loop1");
  fs::create_symlink("loop1", dir / "loop2");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"impact " + (dir / "loop1").string(), "loop1: cannot read the configuration file (Too many levels of symbolic links)"},
      {"impact ''", "error: \"\": no such configuration file"},
      {"plot " + (dir / "nothere").string(), "nothere: no such folder"},
      {"animate " + (dir / "nothere").string(), "nothere: no such folder"},
      {"plot " + (dir / "loop1").string(), "loop1: Too many levels of symbolic links"},
      {"plot ''", "error: \"\": no such folder"}};
  for (const auto& [args, message] : cases) {
    const CliRun r = run(args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
  }
  fs::remove_all(dir);
}

// A pass whose tip goes farther from its clamp than the filament's length (a soft, heavy filament)
// is a result outside the model, not a failure: exit 0, summary.json's validity "outside" and the
// printed summary saying so in plain words (it was exit 0 with only a warning line). A surface 6 %
// deep bends the filament past 0.35 L, where the foreshortening's tip is 1e-2 L from the exact one:
// "outside" too, with that reason. The base case is at the "edge" (its warning says so and what to
// run instead), a surface 0.01 % deep "within".
TEST(Cli, APassOutsideTheModelSaysSoAndExitsZero) {
  const std::string out = ::testing::TempDir() + "rotbeam_cli_outside_" + std::to_string(getpid());
  const CliRun soft = run("run --set beam.youngs_modulus_pa=1e3 --set beam.density_kg_m3=1e6 -o " + out);
  EXPECT_EQ(soft.status, 0) << soft.err;
  EXPECT_NE(soft.out.find("validity              OUTSIDE THE MODEL: the tip went farther from its clamp than the "
                          "filament's length; these results are not physical"),
            std::string::npos)
      << soft.out;
  std::ifstream summary(out + "/summary.json");
  EXPECT_EQ(nlohmann::json::parse(summary)["validity"], "outside");
  const CliRun deep = run("run --set surface.depth_fraction=0.06 -o " + out);
  EXPECT_EQ(deep.status, 0) << deep.err;
  EXPECT_NE(deep.out.find("validity              OUTSIDE THE MODEL: max |y_t|/L above 0.35, where the foreshortening's "
                          "tip is 0.01 L or more from the exact one"),
            std::string::npos)
      << deep.out;
  std::ifstream deep_summary(out + "/summary.json");
  const auto dj = nlohmann::json::parse(deep_summary);
  EXPECT_EQ(dj["validity"], "outside");
  EXPECT_GT(dj["max_tip_deflection_ratio"].get<double>(), 0.35);
  const CliRun base = run("run -o " + out);
  EXPECT_EQ(base.status, 0) << base.err;
  EXPECT_EQ(base.out.find("OUTSIDE THE MODEL"), std::string::npos) << base.out;
  EXPECT_NE((base.out + base.err).find("beam.theory = \"elastica\" is exact at any deflection"), std::string::npos) << base.out;
  std::ifstream base_summary(out + "/summary.json");
  EXPECT_EQ(nlohmann::json::parse(base_summary)["validity"], "edge");  // max |y_t|/L 0.25 in its bounces
  const CliRun shallow = run("run --set surface.depth_fraction=0.0001 -o " + out);
  EXPECT_EQ(shallow.status, 0) << shallow.err;
  std::ifstream shallow_summary(out + "/summary.json");
  EXPECT_EQ(nlohmann::json::parse(shallow_summary)["validity"], "within");  // max |y_t|/L 0.09
  fs::remove_all(out);
}

TEST(Cli, ASweepNamesTheCaseFoldersOfAnEarlierGrid) {
  // A sweep over fewer cases left an earlier grid's case folders beside its sweep.csv without a
  // word; they are kept (the user's data) and counted in the sweep's output.
  const std::string dir = ::testing::TempDir() + "rotbeam_cli_earlier_grid_" + std::to_string(getpid());
  fs::remove_all(dir);
  const std::string base = "sweep --quiet --set hub.speed_rpm=3000 --set simulation.end_angle_deg=0 -o " + dir;
  ASSERT_EQ(run(base + " --vary surface.friction=0.1,0.2,0.3").status, 0);
  const CliRun r = run(base + " --vary surface.friction=0.2");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("2 case folders in " + dir + " are not in this grid"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir + "/case-0003/summary.json"));
  const CliRun again = run(base + " --vary surface.friction=0.1,0.2,0.3");
  EXPECT_EQ(again.out.find("not in this grid"), std::string::npos) << again.out;
  fs::remove_all(dir);
}

TEST(Cli, AnEmptyPathIsRefusedByEveryCommand) {
  // `modes --csv ''` and `--plot ''` wrote nothing and exited 0; `sweep -o ''` said "Invalid
  // argument", `plot -o ''` meant the default: one message for every option that names a file.
  for (const std::string& args :
       {"modes --csv ''", "modes --plot ''", "run -o ''", "sweep --vary hub.speed_rpm=600 -o ''", "plot . -o ''",
        "animate . -o ''", "reproduce -o ''"}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(": an empty path; give a name"), std::string::npos) << args << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

TEST(Cli, TheHeaderShowsAGivenValueThatReadsBack) {
  // μ = 999.9999 was printed "μ = 1000", the upper bound of its range.
  const std::string dir = ::testing::TempDir() + "rotbeam_cli_header_" + std::to_string(getpid());
  const CliRun r = run("run --set surface.friction=999.9999 --set hub.speed_rpm=999999.9 --set simulation.end_angle_deg=0 -o " + dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("Pass: 999999.9 rpm, depth 2.00 %, μ = 999.9999,"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

TEST(Cli, ALinkToNowhereAndNoImpactInJson) {
  // -o naming a dangling link said "cannot create the output folder (File exists)"; impact --json
  // with no impact printed nothing, so a script read empty input.
  const std::string link = ::testing::TempDir() + "rotbeam_cli_dangling_" + std::to_string(getpid());
  fs::remove(link);
  fs::create_symlink(link + "-nowhere", link);
  const CliRun r = run("run --set simulation.end_angle_deg=0 -o " + link);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find(link + ": a link to " + link + "-nowhere, which does not exist; give a folder"), std::string::npos)
      << r.err;
  fs::remove(link);
  const CliRun none = run("impact --set initial.modal_velocity=[0.1,0,0,0,0] --set simulation.end_angle_deg=-20 --json");
  EXPECT_EQ(none.status, 3) << none.err;
  EXPECT_EQ(none.out, "null\n");
}

TEST(Cli, ARangeWithSpacesAboutItsNumbersIsRead) {
  // ' 3 : 4 :2' read "' 3 ' is not a number"; --set and --vary's keys are trimmed, so are the ends.
  const std::string dir = ::testing::TempDir() + "rotbeam_cli_spaced_range_" + std::to_string(getpid());
  fs::remove_all(dir);
  const CliRun r = run("sweep --quiet --set hub.speed_rpm=3000 --set simulation.end_angle_deg=0 --vary 'beam.modes= 3 : 4 :2' -o " + dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir + "/case-0002/summary.json"));
  fs::remove_all(dir);
}

TEST(Cli, KeysListsEveryKeyWithTheStructsDefault) {
  const CliRun json = run("keys --json");
  ASSERT_EQ(json.status, 0) << json.err;
  const auto keys = nlohmann::json::parse(json.out);
  ASSERT_TRUE(keys.is_array());
  std::map<std::string, nlohmann::json> by_name;
  for (const auto& k : keys) {
    for (const char* field : {"name", "type", "unit", "default", "unset", "allowed", "doc"})
      EXPECT_TRUE(k.contains(field)) << k.dump() << " has no " << field;
    by_name[k["name"].get<std::string>()] = k;
  }
  const std::vector<std::string>& names = rotbeam::config_keys();
  EXPECT_EQ(by_name.size(), names.size());
  // The defaults are the structs': every key the default configuration writes, a brush's, and those
  // of the other shapes and the compliant law from their structs.
  rotbeam::Config with_brush;
  with_brush.brush.emplace();
  nlohmann::json expected = with_brush.to_json();
  const rotbeam::SurfaceParameters surface;
  const rotbeam::HertzContact hertz;
  const rotbeam::BeamParameters beam;
  expected["beam"]["theory"] = "foreshortening";
  expected["beam"]["axial"] = "inextensible";
  expected["beam"]["poisson"] = hertz.wire_poisson;
  expected["model"] = {{"centrifugal", beam.centrifugal}, {"coriolis", beam.coriolis}};
  expected["surface"].update({{"shape", "plane"}, {"radius_m", surface.radius_m}, {"speed_rpm", surface.speed_rpm},
                              {"clearance_m", surface.clearance_m}, {"lobes", surface.lobes},
                              {"lobe_amplitude_m", surface.lobe_amplitude_m}, {"lobe_law", surface.lobe_law},
                              {"youngs_modulus_pa", hertz.surface_youngs_modulus_pa}, {"poisson", hertz.surface_poisson}});
  expected["contact"] = {{"model", "rigid"}, {"tip_radius_m", hertz.tip_radius_m},
                         {"friction_regularization_m_s", hertz.friction_regularization_m_s},
                         {"stiffness_factor", hertz.stiffness_factor}};
  expected["simulation"]["revolutions"] = 0;
  for (const std::string& name : names) {
    ASSERT_TRUE(by_name.count(name)) << name << " is not listed";
    const auto dot = name.find('.');
    const nlohmann::json& want = expected[name.substr(0, dot)][name.substr(dot + 1)];
    EXPECT_EQ(by_name[name]["default"], want) << name;
  }
  EXPECT_EQ(by_name["beam.length_m"]["unit"], "m");
  EXPECT_EQ(by_name["beam.length_m"]["allowed"], "(0, 100]");
  EXPECT_EQ(by_name["simulation.revolutions"]["unset"], "none (one pass)");
  const CliRun table = run("keys");
  ASSERT_EQ(table.status, 0) << table.err;
  EXPECT_EQ(table.out.rfind("KEY", 0), 0u) << table.out;
  for (const std::string& name : names) EXPECT_NE(table.out.find("\n" + name + " "), std::string::npos) << name;
  EXPECT_NE(table.out.find("    the filament's length L\n"), std::string::npos);
}
