// docs/reliability.md is the test data: every row of its tables is run against the binary.
// Plus the failure kinds no configuration reaches (stick, non-finite) and interruption.
#include "rotbeam/rigid_contact.hpp"
#include "rotbeam/pass.hpp"
#include "rotbeam/dynamics.hpp"
#include "rotbeam/first_impact.hpp"
#include "rotbeam/plane.hpp"
#include "rotbeam/stop_token.hpp"

#include <array>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include "process_support.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

using namespace rotbeam;
namespace fs = std::filesystem;

namespace {

struct Row {
  std::string section, label, args, message;
  int exit_code = 0;
};

std::vector<std::string> cells(std::string line) {
  const std::string escaped_bar = "\x01";
  for (std::size_t p; (p = line.find("\\|")) != std::string::npos;) line.replace(p, 2, escaped_bar);
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, '|');) {
    for (std::size_t p; (p = cell.find(escaped_bar)) != std::string::npos;) cell.replace(p, 1, "|");
    const auto b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
    out.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  return out;
}

std::string unquote(const std::string& s) {
  if (s.size() >= 2 && s.front() == '`' && s.back() == '`') return s.substr(1, s.size() - 2);
  return s;
}

std::vector<Row> rows() {
  std::ifstream in(std::string(ROTBEAM_SOURCE_DIR) + "/docs/reliability.md");
  std::vector<Row> out;
  std::string section;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("## ", 0) == 0) section = line.substr(3);
    if (line.rfind("| ", 0) != 0 || line.find('`') == std::string::npos) continue;
    const std::vector<std::string> c = cells(line);
    // "", #/kind, input/configuration, arguments, exit, message
    if (c.size() < 6) continue;
    Row r;
    r.section = section;
    r.label = c[1] + " " + c[2];
    r.args = unquote(c[3]);
    r.exit_code = std::stoi(c[4]);
    r.message = unquote(c[5]);
    out.push_back(r);
  }
  return out;
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

struct Outcome {
  int status = -1;
  std::string err;
};

Outcome run(const std::string& args, const std::string& out_dir) {
  std::string cmd = ROTBEAM_CLI;
  std::stringstream ss(args);
  for (std::string a; ss >> a;) {
    if (a == "OUT") a = out_dir;
    if (a.rfind("DATA/", 0) == 0) a = std::string(ROTBEAM_SOURCE_DIR) + "/tests/data/" + a.substr(5);
    cmd += " " + quote(a);
  }
  const std::string err_file = out_dir + ".stderr";
  cmd += " > /dev/null 2> " + quote(err_file);
  Outcome o;
  const int st = std::system(cmd.c_str());
  o.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  std::ifstream e(err_file);
  o.err = rotbeam::test::without_progress_lines(std::string(std::istreambuf_iterator<char>(e), {}));
  fs::remove(err_file);
  return o;
}

std::string fresh_dir(const std::string& name) {
  const fs::path p = fs::path(::testing::TempDir()) / ("rotbeam_rel_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(p);
  return p.string();
}

}  // namespace

TEST(Reliability, EveryBadInputRowOfTheDocument) {
  int count = 0;
  for (const Row& r : rows()) {
    if (r.section.rfind("Bad input", 0) != 0) continue;
    ++count;
    const std::string out = fresh_dir("bad" + std::to_string(count));
    const Outcome o = run(r.args, out);
    EXPECT_EQ(o.status, r.exit_code) << r.label << ": " << r.args << "\n" << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << r.label << ": " << o.err;
    EXPECT_NE(o.err.find(r.message), std::string::npos) << r.label << "\n  expected: " << r.message << "\n  got:      " << o.err;
    EXPECT_FALSE(fs::exists(out)) << r.label << ": left " << out << " behind";
  }
  EXPECT_GE(count, 30);
}

TEST(Reliability, EveryNumericalFailureRowOfTheDocument) {
  int count = 0;
  for (const Row& r : rows()) {
    if (r.section.rfind("Numerical failures", 0) != 0) continue;
    ++count;
    const std::string out = fresh_dir("num" + std::to_string(count));
    const Outcome o = run(r.args, out);
    EXPECT_EQ(o.status, r.exit_code) << r.label << "\n" << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
    EXPECT_NE(o.err.find(r.message), std::string::npos) << r.label << "\n  expected: " << r.message << "\n  got: " << o.err;
    EXPECT_NE(o.err.find(" at t = "), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("θ = "), std::string::npos) << o.err;
    std::ifstream summary(out + "/summary.json");
    ASSERT_TRUE(summary) << r.label;
    const auto j = nlohmann::json::parse(summary);
    EXPECT_EQ(j["failure"]["kind"], cells("| " + r.label + " |")[1].substr(0, j["failure"]["kind"].get<std::string>().size()));
    std::ifstream history(out + "/history.csv");
    const std::string h((std::istreambuf_iterator<char>(history)), {});
    EXPECT_GT(std::count(h.begin(), h.end(), '\n'), 2) << "the partial history is kept";
    fs::remove_all(out);
  }
  EXPECT_EQ(count, 8);  // the rows of the table (non_finite, shooting's orbit and an early cap added; the stick row went when the adaptive scheme began to hold sticks)
}

TEST(Reliability, StickIsDiagnosedByTheLockedTipAnalysis) {
  // A beam held statically against the surface (no spin, q̇ = 0): with the tip locked, the
  // tangential force needed is within μF_n, so the decision is `stick`; with μ = 0 it slides.
  BeamParameters p;
  p.speed_rpm = 0.0;
  const ForeshorteningBeam model = make_beam(p);
  const Plane plane(-1e-3);
  const ModalIntegrals& mi = *model.integrals;
  const Eigen::VectorXd kinv_s = mi.s_tip.cwiseQuotient(mi.r4);
  const Eigen::VectorXd q = -1e-3 * kinv_s / mi.s_tip.dot(kinv_s);
  const Eigen::VectorXd qd = Eigen::VectorXd::Zero(model.n);
  ForeshorteningWorkspace ws(model.n);
  TipKinematics tip(model.n);
  evaluate_dynamics(model, q, qd, ws);
  tip_kinematics(model, plane, 0.0, q, qd, tip);
  const SlipDecision held = decide_slip(model, FrictionModel{0.4, false}, tip, ws);
  EXPECT_EQ(held.kind, SlipDecision::Kind::stick);
  EXPECT_LT(held.stick_normal, 0.0);
  EXPECT_LE(std::abs(held.stick_tangential), 0.4 * std::abs(held.stick_normal));
  EXPECT_FALSE(held.from_velocity);
}

TEST(Reliability, NonFiniteStateIsDiagnosed) {
  // A NaN in the state (no input produces one: every input is range-checked) stops both schemes
  // with a `non_finite` failure instead of looping or writing NaN results as if valid.
  BeamParameters p;
  const ForeshorteningBeam model = make_beam(p);
  const Plane plane = plane_at_depth(model, 0.02);
  InitialConditions ic;
  ic.rigid_start = false;
  ic.q0 = Eigen::VectorXd::Zero(model.n);
  ic.qd0 = Eigen::VectorXd::Zero(model.n);
  ic.qd0[2] = std::numeric_limits<double>::quiet_NaN();
  PassOptions thesis, adaptive;
  thesis.scheme = Scheme::thesis;
  for (const PassResult& r : {run_pass({model, plane, default_contact_law()}, ic, thesis), run_pass({model, plane, default_contact_law()}, ic, adaptive)}) {
    ASSERT_TRUE(r.failure.has_value()) << scheme_name(r.summary.scheme);
    EXPECT_TRUE(r.failure->kind == FailureKind::non_finite || r.failure->kind == FailureKind::step_underflow)
        << scheme_name(r.summary.scheme) << ": " << failure_name(r.failure->kind) << " " << r.failure->message;
  }
}

TEST(Reliability, InterruptKeepsACompleteRecord) {
  // SIGINT into a run of several seconds (12 modes, thesis scheme, 0.5 µs free steps), once the run
  // is under way (its files open and its interrupt handler installed): exit 130, three complete
  // files, failure.kind = "interrupted".
  const std::string out = fresh_dir("interrupt");
  const pid_t pid = test::start_in_background(
      std::string(ROTBEAM_CLI) + " run --set beam.modes=12 --set simulation.scheme=thesis --set simulation.free_step_s=5e-7 -o " +
      out + " >/dev/null 2>&1");
  const bool under_way =
      test::wait_until([&] { return test::ended(pid) || test::runs_and_catches(pid, ROTBEAM_CLI, SIGINT); }) && !test::ended(pid);
  ::kill(pid, under_way ? SIGINT : SIGKILL);
  const int code = test::exit_code(pid);
  ASSERT_TRUE(under_way) << "the run did not get under way";
  EXPECT_EQ(code, 130);
  std::ifstream summary(out + "/summary.json");
  ASSERT_TRUE(summary);
  const auto j = nlohmann::json::parse(summary);
  EXPECT_EQ(j["failure"]["kind"], "interrupted");
  EXPECT_LT(j["failure"]["theta_deg"].get<double>(), 90.0);
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  fs::remove_all(out);
}

TEST(Reliability, ProgressCountsFromTheFlexibleStart) {
  // A rigid start turns the undeformed filament from θ0 to the first impact at no cost: the
  // progress fraction and its ETA count from there, so they start near 0 % instead of at the
  // fraction of the rigid turn (≈ 92 % of −90° … 0° for the base case ended at 0°).
  BeamParameters p;
  const ForeshorteningBeam model = make_beam(p);
  const Plane plane = plane_at_depth(model, 0.02);
  PassOptions opt;
  opt.end_angle_deg = 0.0;
  std::vector<PassProgress> seen;
  PassControl control;
  control.on_progress = [&](const PassProgress& pr) { seen.push_back(pr); };
  const PassResult r = run_pass({model, plane, default_contact_law()}, InitialConditions{}, opt, control);
  ASSERT_FALSE(r.failure);
  ASSERT_FALSE(seen.empty());
  const PassProgress& first = seen.front();
  EXPECT_NEAR(first.start_deg, r.summary.first_impact_deg, 1e-9);
  const double done = (first.theta_deg - first.start_deg) / (first.end_deg - first.start_deg);
  EXPECT_GE(done, 0.0);
  EXPECT_LT(done, 0.5) << "θ = " << first.theta_deg << "° from " << first.start_deg << "°";
  // The search for the first impact from a flexible start reports too (RK5 steps of 1 µs over
  // ≈ 82°: about 25 000 steps), with θ growing from θ0.
  InitialConditions flexible;
  flexible.rigid_start = false;
  flexible.q0 = Eigen::VectorXd::Zero(model.n);
  flexible.qd0 = Eigen::VectorXd::Zero(model.n);
  flexible.qd0[0] = 0.1;
  std::vector<PassProgress> searched;
  PassControl search_control;
  search_control.on_progress = [&](const PassProgress& pr) { searched.push_back(pr); };
  const FirstImpactResult f = first_impact({model, plane, default_contact_law()}, flexible, 90.0, 1e-6, search_control);
  ASSERT_TRUE(f.found);
  ASSERT_FALSE(searched.empty());
  EXPECT_DOUBLE_EQ(searched.front().start_deg, -90.0);
  EXPECT_GT(searched.front().theta_deg, -90.0);
  EXPECT_LT(searched.back().theta_deg, f.theta * 180.0 / M_PI);
  EXPECT_GT(searched.front().steps, 0);
}

TEST(Reliability, AStepThatCannotAdvanceIsAnUnderflow) {
  // A free step of 1e-300 s cannot advance t ≈ 0.0248 s (t + h == t): before, the pass stayed at the
  // same t for ever. The configuration's ranges keep the command line from it; the library stops
  // with `step_underflow` instead of hanging, in the pass and in the first impact.
  BeamParameters p;
  const ForeshorteningBeam model = make_beam(p);
  const Plane plane = plane_at_depth(model, 0.02);
  PassOptions opt;
  opt.scheme = Scheme::thesis;
  opt.free_step_s = 1e-300;
  const PassResult r = run_pass({model, plane, default_contact_law()}, InitialConditions{}, opt);
  ASSERT_TRUE(r.failure);
  EXPECT_EQ(r.failure->kind, FailureKind::step_underflow);
  EXPECT_NE(r.failure->message.find("would need over 1e12 steps"), std::string::npos) << r.failure->message;
  InitialConditions flexible;
  flexible.rigid_start = false;
  flexible.q0 = Eigen::VectorXd::Zero(5);
  flexible.qd0 = Eigen::VectorXd::Zero(5);
  flexible.qd0[0] = 0.1;
  const PassResult f = run_pass({model, plane, default_contact_law()}, flexible, [&] {
    PassOptions o = opt;
    return o;
  }());
  ASSERT_TRUE(f.failure);
  EXPECT_EQ(f.failure->kind, FailureKind::step_underflow);
}

TEST(Reliability, ManyJobsNeitherAbortNorIdle) {
  // --jobs 40000 for a two-case sweep, and 100000 for converge, ended in `terminate` (exit 134) after
  // every case ran; the runner now starts no more threads than there are jobs.
  const std::string out = fresh_dir("jobs");
  Outcome o = run("sweep --set hub.speed_rpm=3000 --vary surface.friction=0.1,0.2 --jobs 40000 -o OUT", out);
  EXPECT_EQ(o.status, 0) << o.err;
  EXPECT_TRUE(fs::exists(out + "/sweep.csv"));
  fs::remove_all(out);
  o = run("converge --jobs 100000 --rtols 1e-8 --steps 1e-6 --modes 3 --set simulation.end_angle_deg=-5", out);
  EXPECT_EQ(o.status, 0) << o.err;
}

TEST(Reliability, ASweepCaseThatCannotBeWrittenFailsTheSweep) {
  // A file where a case's folder should be: that case is `error` and the sweep exits 1 (it exited 0).
  const std::string out = fresh_dir("sweep_error");
  fs::create_directories(out);
  std::ofstream(out + "/case-0002") << "not a folder\n";
  const Outcome o = run("sweep --set hub.speed_rpm=3000 --vary surface.friction=0.1,0.2 -o OUT", out);
  EXPECT_EQ(o.status, 1) << o.err;
  EXPECT_NE(o.err.find("could not be run or written"), std::string::npos) << o.err;
  std::ifstream csv(out + "/sweep.csv");
  const std::string table((std::istreambuf_iterator<char>(csv)), {});
  EXPECT_NE(table.find(",error,"), std::string::npos) << table;
  fs::remove_all(out);
}

TEST(Reliability, TheSummaryOfAStoppedPassSaysSoAtItsTop) {
  // `run > summary.txt` of a pass stopped by the impacts cap kept a complete-looking summary: the
  // failure was on stderr only. The second line of the summary (after the case) now says where it
  // stopped and why.
  const std::string out = fresh_dir("stopped_summary");
  const std::string text = out + ".stdout";
  const std::string cmd = std::string(ROTBEAM_CLI) + " run --set simulation.max_impacts=3 -o " + out + " > " + text + " 2>/dev/null";
  const int st = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 10);
  std::ifstream in(text);
  std::string header, second;
  std::getline(in, header);
  std::getline(in, second);
  EXPECT_NE(second.find("STOPPED"), std::string::npos) << second;
  EXPECT_NE(second.find("θ = "), std::string::npos) << second;
  EXPECT_NE(second.find("numerical failure (impacts, exit 10)"), std::string::npos) << second;
  fs::remove(text);
  fs::remove_all(out);
}

TEST(Reliability, ACaseFolderThatIsALinkIsRunIntoAFolderOfItsOwn) {
  // case-0002 replaced by a link to case-0001: the resume wrote case 2 through the link into case
  // 1's folder, whose summary then said friction 0.2 while sweep.csv said 0.1. The link is now
  // removed and case 2 run into a real folder; case 1's files stay its own.
  const std::string out = fresh_dir("sweep_link");
  const std::string args = "sweep --set hub.speed_rpm=3000 --set simulation.end_angle_deg=0 --vary surface.friction=0.1,0.2 -o OUT";
  ASSERT_EQ(run(args, out).status, 0);
  fs::remove_all(out + "/case-0002");
  fs::create_directory_symlink("case-0001", out + "/case-0002");
  const Outcome o = run(args, out);
  EXPECT_EQ(o.status, 0) << o.err;
  EXPECT_FALSE(fs::is_symlink(out + "/case-0002"));
  for (const auto& [folder, mu] : {std::pair<std::string, double>{"case-0001", 0.1}, {"case-0002", 0.2}}) {
    std::ifstream in(out + "/" + folder + "/summary.json");
    ASSERT_TRUE(in) << folder;
    EXPECT_EQ(nlohmann::json::parse(in)["config"]["surface"]["friction"].get<double>(), mu) << folder;
  }
  fs::remove_all(out);
}

TEST(Reliability, ResumeChecksEveryFileOfACase) {
  // A finished case whose history.csv was truncated, or whose events.csv was deleted, is run again
  // (summary.json records the files' sizes), not marked `resumed`.
  const std::string out = fresh_dir("resume");
  ASSERT_EQ(run("sweep --set hub.speed_rpm=3000 --vary surface.friction=0.1,0.2,0.3 -o OUT", out).status, 0);
  fs::resize_file(out + "/case-0001/history.csv", 100);
  fs::remove(out + "/case-0002/events.csv");
  ASSERT_EQ(run("sweep --set hub.speed_rpm=3000 --vary surface.friction=0.1,0.2,0.3 -o OUT", out).status, 0);
  std::ifstream csv(out + "/sweep.csv");
  std::string line, table;
  int resumed = 0, done = 0;
  while (std::getline(csv, line)) {
    resumed += line.find(",resumed,") != std::string::npos;
    done += line.find(",done,") != std::string::npos;
  }
  EXPECT_EQ(done, 2);
  EXPECT_EQ(resumed, 1);
  fs::remove_all(out);
}

TEST(Reliability, ModesPlotLeavesTheUsersFilesAlone) {
  // `modes --plot X.png` used X.png.csv as its scratch table and deleted it: a user's file.
  const std::string out = fresh_dir("modes_plot");
  fs::create_directories(out);
  std::ofstream(out + "/camp.png.csv") << "mine\n";
  const Outcome o = run("modes --speeds-rpm 0:3000:4 --plot " + out + "/camp.png", out + "_x");
  if (o.status == 0) {
    EXPECT_TRUE(fs::exists(out + "/camp.png"));
  }
  std::ifstream kept(out + "/camp.png.csv");
  std::string s;
  std::getline(kept, s);
  EXPECT_EQ(s, "mine");
  fs::remove_all(out);
}

TEST(Reliability, AnInterruptedPlotLeavesNoScratchNorProcess) {
  // Ctrl-C (SIGINT to `rotbeam` alone, as `kill` sends it) while the plotting module draws the
  // Campbell diagram: before, rotbeam died at once, leaving its scratch table in TMPDIR and the
  // Python process running on as an orphan. Now the signal is passed on, both stop, the scratch
  // file is removed, and the exit is 130 with one line. The signal is sent once the scratch table
  // exists and the plotting process runs Python (≥ 0.3 s to import matplotlib).
  const std::string tmp = fresh_dir("plot_interrupt_tmp");
  fs::create_directories(tmp);
  const std::string png = tmp + "_camp.png";
  const std::string err = tmp + ".stderr";
  const pid_t pid = test::start_in_background("env TMPDIR=" + tmp + " " + std::string(ROTBEAM_CLI) + " modes --plot " + png +
                                              " 2>" + err + " >/dev/null");
  bool drawing = false;
  test::wait_until([&] {
    if (test::ended(pid)) return true;  // no use waiting on
    if (!test::runs(pid, ROTBEAM_CLI) || fs::is_empty(tmp)) return false;
    const pid_t child = test::child_of(pid);
    return drawing = child != 0 && !test::runs(child, ROTBEAM_CLI);  // forked, and the interpreter started
  });
  ::kill(pid, drawing ? SIGINT : SIGKILL);
  const int code = test::exit_code(pid);
  ASSERT_TRUE(drawing) << "the plotting process did not start";
  EXPECT_EQ(code, 130);
  std::ifstream e(err);
  const std::string message((std::istreambuf_iterator<char>(e)), {});
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;
  EXPECT_NE(message.find("interrupted while drawing"), std::string::npos) << message;
  EXPECT_TRUE(fs::is_empty(tmp)) << "scratch left in " << tmp;
  EXPECT_FALSE(fs::exists(png));
  EXPECT_NE(std::system(("pgrep -f -- '--campbel[l] " + png + "' >/dev/null").c_str()), 0) << "the plotting process lives on";
  fs::remove_all(tmp);
  fs::remove(err);
  fs::remove(png);
}

namespace {
// A stand-in for the plotting interpreter (ROTBEAM_PYTHON) that writes its process id to `pid_file`
// and sleeps `seconds`: it lets a test act while `plot` or `modes --plot` waits for its module.
std::string sleeping_python(const std::string& dir, const std::string& pid_file, int seconds) {
  const std::string script = dir + "/python";
  std::ofstream(script) << "#!/bin/sh\necho $$ > " << pid_file << "\nexec sleep " << seconds << "\n";
  fs::permissions(script, fs::perms::owner_all);
  return script;
}

// Waits (for minutes at most) for a file to be written; returns its first word.
std::string wait_for_word(const std::string& file) {
  std::string word;
  test::wait_until([&] {
    std::ifstream in(file);
    return static_cast<bool>(in >> word);
  });
  return word;
}

// True while the process runs (a zombie, ended but not yet reaped, does not count).
bool process_runs(const std::string& pid) {
  std::ifstream stat("/proc/" + pid + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return false;
  const std::size_t paren = line.rfind(')');
  return paren != std::string::npos && paren + 2 < line.size() && line[paren + 2] != 'Z';
}
}  // namespace

TEST(Reliability, AKilledRotbeamTakesItsPlottingProcessAlong) {
  // kill -9 of `rotbeam plot`/`animate`/`modes --plot` left the Python process running as an
  // orphan: its pictures appeared seconds after the killed command exited 137. The module now dies
  // with rotbeam (SIGTERM). The stand-in sleeps ten minutes; it must be gone long before (it is
  // given two minutes), once rotbeam is killed after the stand-in has started.
  const std::string dir = fresh_dir("killed_plot");
  fs::create_directories(dir);
  const std::string pid_file = dir + "/pid";
  const std::string python = sleeping_python(dir, pid_file, 600);
  const pid_t pid = test::start_in_background("env TMPDIR=" + dir + " ROTBEAM_PYTHON=" + python + " " +
                                              std::string(ROTBEAM_CLI) + " modes --plot " + dir + "/c.png >/dev/null 2>&1");
  test::wait_until([&] { return fs::exists(pid_file) && fs::file_size(pid_file) > 0; });
  ::kill(pid, SIGKILL);
  EXPECT_EQ(test::exit_code(pid), 128 + SIGKILL);
  const std::string child = wait_for_word(pid_file);
  ASSERT_FALSE(child.empty());
  test::wait_until([&] { return !process_runs(child); }, std::chrono::seconds(120));
  EXPECT_FALSE(process_runs(child)) << "the plotting process " << child << " outlived the killed rotbeam";
  if (process_runs(child)) ::kill(std::stoi(child), SIGKILL);
  fs::remove_all(dir);
}

TEST(Reliability, ARunIsRefusedInAFolderBeingDrawn) {
  // `plot DIR` read and drew the files while `run -o DIR` replaced them: the folder ended with the
  // new run beside pictures of the older one. plot and animate hold the folder's lock while they
  // draw, so the run is refused (exit 2). The stand-in interpreter keeps the plot drawing until it
  // is ended at the end of the test.
  const std::string dir = fresh_dir("drawn");
  const std::string out = dir + "/run";
  fs::create_directories(dir);
  const std::string args = "run --set hub.speed_rpm=3000 --set simulation.end_angle_deg=0 -o OUT";
  ASSERT_EQ(run(args, out).status, 0);
  const std::string pid_file = dir + "/pid";
  const std::string python = sleeping_python(dir, pid_file, 600);
  const std::string plot = "ROTBEAM_PYTHON=" + python + " " + std::string(ROTBEAM_CLI) + " plot " + out + " >/dev/null 2>&1";
  std::FILE* drawing = ::popen(plot.c_str(), "r");
  ASSERT_NE(drawing, nullptr);
  const std::string stand_in = wait_for_word(pid_file);
  ASSERT_FALSE(stand_in.empty());
  const Outcome o = run(args, out);
  EXPECT_EQ(o.status, 2) << o.err;
  EXPECT_NE(o.err.find("another rotbeam run is writing into this folder"), std::string::npos) << o.err;
  const Outcome second = run("plot OUT", out);
  EXPECT_EQ(second.status, 2) << second.err;
  EXPECT_NE(second.err.find("draw it once that has finished"), std::string::npos) << second.err;
  ::kill(std::stoi(stand_in), SIGTERM);
  ::pclose(drawing);
  fs::remove_all(dir);
}

namespace {
// Counts what a pass hands it, keeping nothing.
struct CountingSink : PassSink {
  long rows = 0;
  void row(const HistoryRow&) override { ++rows; }
  void event(const PassEvent&) override {}
};
}  // namespace

TEST(Reliability, ARigidApproachOfNearSurfaceRowsHonoursAStop) {
  // A near-surface gap wider than the whole approach makes every row of the rigid turn a
  // near-surface row: at 10 ns, millions of them, written without looking at the stop token (SIGINT
  // was ignored for minutes). A stop requested before the pass ends it within the approach's far
  // spacing, as `interrupted`.
  BeamParameters p;
  const ForeshorteningBeam model = make_beam(p);
  const Plane plane = plane_at_depth(model, 0.02);
  PassOptions opt;
  opt.near_surface_gap_m = 1.0;
  opt.near_surface_interval_s = 1e-8;
  StopToken stop;
  stop.request_stop();
  CountingSink sink;
  PassControl control;
  control.stop = &stop;
  control.sink = &sink;
  const PassResult r = run_pass({model, plane, default_contact_law()}, InitialConditions{}, opt, control);
  ASSERT_TRUE(r.failure);
  EXPECT_EQ(r.failure->kind, FailureKind::interrupted);
  EXPECT_LT(sink.rows, 10000);
}

TEST(Reliability, OneHistoryRowPerState) {
  // The state before an impact was written twice (the accepted point and the impact's own "before"
  // row): one row per state, the pre/post pair of an impact kept.
  BeamParameters p;
  const ForeshorteningBeam model = make_beam(p);
  const Plane plane = plane_at_depth(model, 0.02);
  const PassResult r = run_pass({model, plane, default_contact_law()}, InitialConditions{}, PassOptions{});
  ASSERT_FALSE(r.failure);
  ASSERT_GT(r.summary.impacts, 0);
  int duplicates = 0, pairs = 0;
  for (std::size_t i = 1; i < r.history.size(); ++i) {
    const HistoryRow &a = r.history[i - 1], &b = r.history[i];
    if (a.t != b.t || a.q != b.q) continue;
    if (a.qd == b.qd && a.phase == b.phase && a.normal_force == b.normal_force) ++duplicates;
    else ++pairs;
  }
  EXPECT_EQ(duplicates, 0);
  EXPECT_GE(pairs, r.summary.impacts);
}

TEST(Reliability, ADamagedCaseSummaryIsRunAgainOnResume) {
  // A finished case whose summary.json had `"failure": {"kind": 5}` (same sizes of the listed files)
  // ended the resume with a raw JSON type error: the case is incomplete and is run again.
  const std::string out = fresh_dir("resume_damaged");
  const std::string args = "sweep --set hub.speed_rpm=3000 --set simulation.end_angle_deg=0 --vary surface.friction=0.1,0.2 -o OUT";
  ASSERT_EQ(run(args, out).status, 0);
  const std::string summary = out + "/case-0002/summary.json";
  nlohmann::json j = nlohmann::json::parse(std::ifstream(summary));
  j["failure"] = {{"kind", 5}};
  std::ofstream(summary) << j.dump(2) << "\n";
  const Outcome o = run(args, out);
  EXPECT_EQ(o.status, 0) << o.err;
  std::ifstream csv(out + "/sweep.csv");
  const std::string table((std::istreambuf_iterator<char>(csv)), {});
  EXPECT_NE(table.find("case-0002,0.2,done,"), std::string::npos) << table;
  EXPECT_NE(table.find("case-0001,0.1,resumed,"), std::string::npos) << table;
  fs::remove_all(out);
}

TEST(Reliability, ARunFolderDoesNotBecomeASweep) {
  // A sweep into a run's folder left summary.json and sweep.csv side by side (plot drew the sweep).
  const std::string out = fresh_dir("run_then_sweep");
  ASSERT_EQ(run("run --set hub.speed_rpm=3000 --set simulation.end_angle_deg=0 -o OUT", out).status, 0);
  const Outcome o = run("sweep --set hub.speed_rpm=3000 --vary surface.friction=0.1 -o OUT", out);
  EXPECT_EQ(o.status, 2) << o.err;
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
  EXPECT_NE(o.err.find(": holds a run (summary.json), not a sweep"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(out + "/sweep.csv"));
  EXPECT_FALSE(fs::exists(out + "/case-0001"));
  fs::remove_all(out);
}

TEST(Reliability, ASweepFolderDoesNotBecomeARun) {
  // The reverse: a run into a sweep's folder mixed the two as well.
  const std::string out = fresh_dir("sweep_then_run");
  ASSERT_EQ(run("sweep --set hub.speed_rpm=3000 --set simulation.end_angle_deg=0 --vary surface.friction=0.1 -o OUT", out).status, 0);
  const Outcome o = run("run --set hub.speed_rpm=3000 --set simulation.end_angle_deg=0 -o OUT", out);
  EXPECT_EQ(o.status, 2) << o.err;
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
  EXPECT_NE(o.err.find(": holds a sweep (sweep.csv), not a run"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(out + "/summary.json"));
  fs::remove_all(out);
}

TEST(Reliability, AReproductionIsNotMixedIntoAnotherKindOfFolder) {
  // `reproduce -o RUNDIR` wrote report.md, manifest.json and its figures beside a run's files.
  const std::string out = fresh_dir("reproduce_into_others");
  for (const auto& [files, kind] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"summary.json", "history.csv"}, "a run (summary.json, history.csv)"},
           {{"sweep.csv"}, "a sweep (sweep.csv)"},
           {{"workpiece.csv"}, "a brush (workpiece.csv)"}}) {
    fs::remove_all(out);
    fs::create_directories(out);
    for (const std::string& f : files) std::ofstream(out + "/" + f) << "x\n";
    const Outcome o = run("reproduce -o OUT", out);
    EXPECT_EQ(o.status, 2) << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
    EXPECT_NE(o.err.find(": holds " + kind + ", not a reproduction; give another folder"), std::string::npos) << o.err;
    EXPECT_FALSE(fs::exists(out + "/manifest.json"));
    EXPECT_FALSE(fs::exists(out + "/thesis"));
  }
  // The reverse: a run or a sweep into a reproduction's folder.
  fs::remove_all(out);
  fs::create_directories(out);
  for (const char* f : {"manifest.json", "report.md"}) std::ofstream(out + "/" + f) << "x\n";
  for (const auto& [args, kind] : std::vector<std::pair<std::string, std::string>>{
           {"run --set simulation.end_angle_deg=0 -o OUT", "not a run"},
           {"sweep --set simulation.end_angle_deg=0 --vary hub.speed_rpm=600 -o OUT", "not a sweep"}}) {
    const Outcome o = run(args, out);
    EXPECT_EQ(o.status, 2) << o.err;
    EXPECT_NE(o.err.find(": holds a reproduction (manifest.json, report.md), " + kind), std::string::npos) << o.err;
    EXPECT_FALSE(fs::exists(out + "/summary.json"));
    EXPECT_FALSE(fs::exists(out + "/sweep.csv"));
  }
  fs::remove_all(out);
}

TEST(Reliability, PathsLabelsAndKeysAreShownEscaped) {
  // A path, a sweep case's label or a key with an escape sequence or a right-to-left override was
  // printed raw: `nothere^[[2J` cleared the terminal, U+202E reversed the rest of the line.
  const std::string out = fresh_dir("escaped");
  fs::create_directories(out);
  const std::string bidi = out + "/bidi.toml";
  std::ofstream(bidi) << "[hub]\n\"speed\u202erpm\" = 5\n";
  for (const auto& [args, shown] : std::vector<std::pair<std::string, std::string>>{
           {"impact \x1b[31mcase.toml", "\\u001b[31mcase.toml: no such configuration file"},
           {"plot nothere\x1b[2J", "nothere\\u001b[2J: no such folder"},
           {"impact a\xff" "b.toml", "a\\xffb.toml: no such configuration file"},
           {"impact " + bidi, "hub.speed\\u202erpm = 5: unknown key"},
           {"sweep --vary initial.start=rigid,\x1b[31mred -o OUT", "case-0002 (initial.start=\\u001b[31mred): initial.start = \"\\u001b[31mred\""},
           {"impact --set initial.start=\"rig\\\"id\"", "initial.start = \"rig\\\"id\": must be one of"}}) {
    const Outcome o = run(args, out);
    EXPECT_EQ(o.status, 2) << args << ": " << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
    EXPECT_NE(o.err.find(shown), std::string::npos) << o.err;
    EXPECT_EQ(o.err.find('\x1b'), std::string::npos) << o.err;
  }
  fs::remove_all(out);
}

TEST(Reliability, AFolderThatHeldNoRunKeepsTheUsersPictures) {
  // `run -o` deleted energy.png, animation.gif, force_bins.csv… of a folder that never held a run;
  // they are removed only with an older run (its summary.json), whose pictures they are.
  const std::string out = fresh_dir("users_pictures");
  fs::create_directories(out);
  for (const char* name : {"energy.png", "animation.gif", "revolutions.csv"}) std::ofstream(out + "/" + name) << "mine\n";
  const std::string args = "run --set hub.speed_rpm=3000 --set simulation.end_angle_deg=0 -o OUT";
  ASSERT_EQ(run(args, out).status, 0);
  for (const char* name : {"energy.png", "animation.gif", "revolutions.csv"}) EXPECT_TRUE(fs::exists(out + "/" + name)) << name;
  // A summary.json that is not a run's (no config, no files) is no older run either.
  fs::remove_all(out);
  fs::create_directories(out);
  std::ofstream(out + "/summary.json") << "{\"mine\": 1}\n";
  std::ofstream(out + "/energy.png") << "mine\n";
  ASSERT_EQ(run(args, out).status, 0);
  EXPECT_TRUE(fs::exists(out + "/energy.png"));
  std::ofstream(out + "/energy.png") << "drawn of the run\n";
  ASSERT_EQ(run(args, out).status, 0);
  EXPECT_FALSE(fs::exists(out + "/energy.png"));
  fs::remove_all(out);
}
