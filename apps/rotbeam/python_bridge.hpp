// Running the Python package's modules from the command line: the pictures (rotbeam.plots,
// rotbeam.animate, rotbeam.reproduce) and a sweep's netCDF file (rotbeam.netcdf).
#pragma once

#include <string>
#include <vector>

namespace rotbeam::cli {

/// Runs `PYTHON -m MODULE ARGS…` (rotbeam.plots, rotbeam.animate) with PYTHONPATH pointing at the rotbeam package: the
/// build tree's (beside the binary), the install tree's (<prefix>/lib/python3/dist-packages), or
/// ROTBEAM_PYTHONPATH. PYTHON is ROTBEAM_PYTHON, else the interpreter the module was built for.
/// Returns the exit code the module announced on its result pipe (0, 1, 2 or 130); 1, with one line
/// on stderr, when PYTHON did not start the module or it stopped without announcing one (a crash, a
/// signal): a child's own exit code is never passed on. `what` names the module in those messages.
/// An interrupt (SIGINT/SIGTERM, passed on to the module) returns 130 with one line saying so, or
/// with none when `report_interrupt` is false: the caller says what the interruption left.
int run_python_module(const std::string& module, const std::vector<std::string>& args,
                      const std::string& what = "the plotting module", bool report_interrupt = true);

/// run_python_module("rotbeam.plots", args).
inline int run_python_plots(const std::vector<std::string>& args) { return run_python_module("rotbeam.plots", args); }

}  // namespace rotbeam::cli
