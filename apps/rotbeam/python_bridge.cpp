#include "python_bridge.hpp"

#include "common.hpp"

#include <cstdlib>
#include <filesystem>
#include <sys/wait.h>
#include <unistd.h>

#ifndef ROTBEAM_PYTHON_EXECUTABLE
#define ROTBEAM_PYTHON_EXECUTABLE "python3"
#endif

namespace rotbeam::cli {

namespace fs = std::filesystem;

int run_python_plots(const std::vector<std::string>& args) {
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
  std::vector<std::string> argv_storage = {python, "-m", "rotbeam.plots"};
  argv_storage.insert(argv_storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_storage) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    setenv("PYTHONPATH", joined.c_str(), 1);
    setenv("MPLBACKEND", "Agg", 1);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  if (pid >= 0 && waitpid(pid, &status, 0) < 0) status = 127 << 8;
  if (pid < 0 || (WIFEXITED(status) && WEXITSTATUS(status) == 127)) {
    print_error(std::string("cannot run the plotting module: ") + python +
                " -m rotbeam.plots (needs Python 3 with numpy and matplotlib, and the rotbeam package; "
                "set ROTBEAM_PYTHON / ROTBEAM_PYTHONPATH)");
    return kRuntimeFailure;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : kRuntimeFailure;
}

}  // namespace rotbeam::cli
