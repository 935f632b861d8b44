#include "python_bridge.hpp"

#include "common.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef ROTBEAM_PYTHON_EXECUTABLE
#define ROTBEAM_PYTHON_EXECUTABLE "python3"
#endif

namespace rotbeam::cli {

namespace fs = std::filesystem;

namespace {

volatile sig_atomic_t g_child = 0;     // the plotting process while it runs
volatile sig_atomic_t g_forwarded = 0;  // the interrupt passed on to it (0: none)

// SIGINT/SIGTERM while the plotting module runs: passed on to it, so that it stops and this process
// removes its scratch files and reports the interrupt, instead of dying first and leaving an
// orphan behind. It is passed on as SIGTERM: before the module has installed its handler (while
// the interpreter starts), SIGTERM ends Python silently, where SIGINT would print a KeyboardInterrupt
// traceback; once installed, the handler ends it quietly with 130 either way.
void forward_signal(int signal) {
  g_forwarded = signal;
  if (g_child > 0) ::kill(static_cast<pid_t>(g_child), SIGTERM);
}

// Installs forward_signal for SIGINT and SIGTERM for its lifetime, then restores what was there.
class ForwardInterrupts {
 public:
  ForwardInterrupts() {
    struct sigaction sa {};
    sa.sa_handler = forward_signal;
    sigemptyset(&sa.sa_mask);
    ::sigaction(SIGINT, &sa, &old_int_);
    ::sigaction(SIGTERM, &sa, &old_term_);
  }
  ~ForwardInterrupts() {
    g_child = 0;
    ::sigaction(SIGINT, &old_int_, nullptr);
    ::sigaction(SIGTERM, &old_term_, nullptr);
  }
  ForwardInterrupts(const ForwardInterrupts&) = delete;
  ForwardInterrupts& operator=(const ForwardInterrupts&) = delete;

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

// "SIGKILL", "SIGSEGV", …: the name of a signal that ended the plotting process.
std::string signal_name(int signal) {
  const char* abbrev = ::sigabbrev_np(signal);
  return abbrev ? std::string("SIG") + abbrev : "signal " + std::to_string(signal);
}

}  // namespace

int run_python_module(const std::string& module, const std::vector<std::string>& args, const std::string& what,
                      bool report_interrupt) {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  std::string python_path;
  if (const char* env = std::getenv("ROTBEAM_PYTHONPATH")) {
    python_path = env;
  } else if (!ec && fs::exists(exe.parent_path() / "python" / "rotbeam" / "plots.py")) {
    python_path = (exe.parent_path() / "python").string();
  } else if (!ec) {
    python_path = (exe.parent_path().parent_path() / "lib" / "python3" / "dist-packages").string();
  }
  const char* python = std::getenv("ROTBEAM_PYTHON") ? std::getenv("ROTBEAM_PYTHON") : ROTBEAM_PYTHON_EXECUTABLE;
  std::string joined = python_path;
  if (const char* existing = std::getenv("PYTHONPATH")) joined += std::string(":") + existing;
  std::vector<std::string> argv_storage = {python, "-m", module};
  argv_storage.insert(argv_storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_storage) argv.push_back(a.data());
  argv.push_back(nullptr);
  // The module writes `started` and `result CODE` on this pipe: a program that is not the module
  // (ROTBEAM_PYTHON=/bin/true, /bin/sh) writes nothing, and its exit code is never taken as ours.
  int report[2] = {-1, -1};
  if (::pipe2(report, O_CLOEXEC) != 0) {
    print_error("cannot run " + what + ": no pipe (" + std::strerror(errno) + ")");
    return kRuntimeFailure;
  }
  ::fcntl(report[0], F_SETFL, O_NONBLOCK);
  ForwardInterrupts forward;
  g_forwarded = 0;
  const pid_t parent = ::getpid();
  const pid_t pid = fork();
  if (pid == 0) {
    // The module dies with this process: a rotbeam killed by SIGKILL left it running, and its
    // pictures appeared seconds after the command the user killed had exited. SIGTERM lets it
    // remove its temporaries; a parent already gone before the request took effect is checked.
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) _exit(kInterrupted);
    // Its own process group: a Ctrl-C at the terminal reaches rotbeam alone, which passes it on
    // (forward_signal), instead of reaching the interpreter mid-start as well.
    ::setpgid(0, 0);
    ::close(report[0]);
    ::fcntl(report[1], F_SETFD, 0);  // kept across exec
    setenv("ROTBEAM_RESULT_FD", std::to_string(report[1]).c_str(), 1);
    setenv("PYTHONPATH", joined.c_str(), 1);
    setenv("MPLBACKEND", "Agg", 1);
    ::signal(SIGPIPE, SIG_DFL);  // rotbeam ignores it; the module gets the default
    execvp(argv[0], argv.data());
    _exit(127);
  }
  ::close(report[1]);
  g_child = pid;
  if (pid > 0 && g_forwarded != 0) ::kill(pid, SIGTERM);  // a signal between fork and here
  int status = 0;
  if (pid > 0) {
    pid_t waited;
    while ((waited = waitpid(pid, &status, 0)) < 0 && errno == EINTR) {
    }
    if (waited < 0) status = 127 << 8;
  }
  std::string said;
  char buf[256];
  for (ssize_t got; (got = ::read(report[0], buf, sizeof buf)) > 0 || (got < 0 && errno == EINTR);)
    if (got > 0) said.append(buf, static_cast<std::size_t>(got));
  ::close(report[0]);
  const bool started = said.find("started\n") != std::string::npos;
  const std::size_t at = said.find("result ");
  int result = -1;
  if (at != std::string::npos) result = std::atoi(said.c_str() + at + 7);
  // An interrupt that arrived after the module finished its work changes nothing.
  if (g_forwarded != 0 && !(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
    if (!report_interrupt) return kInterrupted;
    print_error(what == "the plotting module"
                    ? "interrupted while drawing: the files written so far are whole, the rest are missing"
                    : "interrupted while " + what + " ran: it wrote nothing under its file's name");
    return kInterrupted;
  }
  const std::string how = WIFSIGNALED(status) ? std::string("killed by signal ") + std::to_string(WTERMSIG(status)) +
                                                     " (" + signal_name(WTERMSIG(status)) + ")"
                                              : "exit " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1);
  if (pid < 0 || !started) {
    print_error("cannot run " + what + ": " + python + " -m " + module + " did not start it (" +
                (pid < 0 ? std::string("no process") : how) +
                (std::getenv("ROTBEAM_PYTHON") ? std::string(", ROTBEAM_PYTHON=") + python : std::string()) +
                "; needs Python 3 with numpy and matplotlib, and the rotbeam package; set ROTBEAM_PYTHON / "
                "ROTBEAM_PYTHONPATH)");
    return kRuntimeFailure;
  }
  if (result < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != result) {
    print_error(what + " " + module + " stopped before it finished (" + how + ")");
    return kRuntimeFailure;
  }
  // The module's codes are rotbeam's (0, 1, 2 damaged input, 130); any other is a failure.
  return result == 0 || result == 1 || result == 2 || result == kInterrupted ? result : kRuntimeFailure;
}

}  // namespace rotbeam::cli
