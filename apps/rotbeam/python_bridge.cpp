#include "python_bridge.hpp"

#include "common.hpp"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <filesystem>
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
// orphan behind.
void forward_signal(int signal) {
  g_forwarded = signal;
  if (g_child > 0) ::kill(static_cast<pid_t>(g_child), signal);
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

}  // namespace

int run_python_module(const std::string& module, const std::vector<std::string>& args) {
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
  ForwardInterrupts forward;
  g_forwarded = 0;
  const pid_t pid = fork();
  if (pid == 0) {
    setenv("PYTHONPATH", joined.c_str(), 1);
    setenv("MPLBACKEND", "Agg", 1);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  g_child = pid;
  if (pid > 0 && g_forwarded != 0) ::kill(pid, g_forwarded);  // a signal between fork and here
  int status = 0;
  if (pid > 0) {
    pid_t waited;
    while ((waited = waitpid(pid, &status, 0)) < 0 && errno == EINTR) {
    }
    if (waited < 0) status = 127 << 8;
  }
  // An interrupt that arrived after the module finished its work changes nothing.
  if (g_forwarded != 0 && !(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
    print_error("interrupted while drawing: the files written so far are whole, the rest are missing");
    return kInterrupted;
  }
  if (pid < 0 || (WIFEXITED(status) && WEXITSTATUS(status) == 127)) {
    print_error(std::string("cannot run the plotting module: ") + python + " -m " + module +
                " (needs Python 3 with numpy and matplotlib, and the rotbeam package; "
                "set ROTBEAM_PYTHON / ROTBEAM_PYTHONPATH)");
    return kRuntimeFailure;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : kRuntimeFailure;
}

}  // namespace rotbeam::cli
