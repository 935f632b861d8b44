// Processes a test starts in the background and acts on (interrupts, kills) once they are under
// way. A test waits for a sign that the process has reached the point it is about (its handler of
// the signal installed, a child started, a file written), polled until a generous deadline, never
// for a fixed time: a fixed sleep fails on a slow machine and, on a fast one, may signal a process
// that has already finished or not yet started, so that the test passes without testing anything.
#pragma once

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <sys/types.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace rotbeam::test {

/// Runs `command` with /bin/sh in the background; `exec` makes the process id the command's own
/// (`rotbeam`'s, or `env`'s and then `rotbeam`'s for `env VAR=value rotbeam …`).
inline pid_t start_in_background(const std::string& command) {
  const std::string line = "exec " + command;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", line.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

/// Waits for the process to end: its exit code, or 128 + the signal that ended it (as a shell says).
inline int exit_code(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
}

/// True once the child process `pid` has ended (it is left to exit_code to collect).
inline bool ended(pid_t pid) {
  siginfo_t info{};
  return ::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid;
}

/// Polls `ready` every 5 ms until it holds or `deadline` has passed: whether it held.
inline bool wait_until(const std::function<bool()>& ready, std::chrono::seconds deadline = std::chrono::seconds(300)) {
  const auto end = std::chrono::steady_clock::now() + deadline;
  while (!ready()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

/// True when process `pid` runs the executable `program` (not the shell or `env` before it).
inline bool runs(pid_t pid, const std::string& program) {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/" + std::to_string(pid) + "/exe", ec);
  return !ec && std::filesystem::equivalent(exe, program, ec) && !ec;
}

/// True when process `pid` has a handler of its own for `signal` (/proc/PID/status, SigCgt).
inline bool catches(pid_t pid, int signal) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("SigCgt:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) >> (signal - 1)) & 1u;
  return false;
}

/// True when `program` runs as process `pid` with its handler of `signal` installed: the point
/// after which the signal reaches the code a test is about.
inline bool runs_and_catches(pid_t pid, const std::string& program, int signal) {
  return runs(pid, program) && catches(pid, signal);
}

/// A live child process of process `pid` (a zombie does not count), or 0 when it has none.
inline pid_t child_of(pid_t pid) {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc", ec)) {
    std::ifstream stat(entry.path() / "stat");
    std::string line;
    if (!std::getline(stat, line)) continue;
    // pid (comm) state ppid …: comm may hold spaces and parentheses, so read from the last ')'.
    const std::size_t paren = line.rfind(')');
    if (paren == std::string::npos || paren + 4 > line.size()) continue;
    const char state = line[paren + 2];
    if (state != 'Z' && std::stol(line.substr(paren + 4)) == static_cast<long>(pid)) return std::stoi(line);
  }
  return 0;
}

}  // namespace rotbeam::test
