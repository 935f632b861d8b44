// Running the Python plotting module (rotbeam.plots) from the command line.
#pragma once

#include <string>
#include <vector>

namespace rotbeam::cli {

/// Runs `PYTHON -m MODULE ARGS…` (rotbeam.plots, rotbeam.animate) with PYTHONPATH pointing at the rotbeam package: the
/// build tree's (beside the binary), the install tree's (<prefix>/lib/python3/dist-packages), or
/// ROTBEAM_PYTHONPATH. PYTHON is ROTBEAM_PYTHON, else the interpreter the module was built for.
/// Returns the module's exit code (127 when it cannot start).
int run_python_module(const std::string& module, const std::vector<std::string>& args);

/// run_python_module("rotbeam.plots", args).
inline int run_python_plots(const std::vector<std::string>& args) { return run_python_module("rotbeam.plots", args); }

}  // namespace rotbeam::cli
