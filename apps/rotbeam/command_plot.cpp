// `rotbeam plot DIR`: the pictures of a run or a sweep folder (Python's rotbeam.plots).
#include "commands.hpp"
#include "common.hpp"
#include "python_bridge.hpp"

#include <filesystem>

namespace rotbeam::cli {

namespace {
struct PlotOptions {
  std::string folder, output;
  bool cases = false;
};
}  // namespace

Command add_plot_command(CLI::App& app) {
  auto opts = std::make_shared<PlotOptions>();
  CLI::App* sub = app.add_subcommand("plot", "Write the PNG pictures of a run folder or a sweep folder (matplotlib)");
  sub->add_option("folder", opts->folder, "A folder written by `rotbeam run` or `rotbeam sweep`")->required();
  sub->add_option("-o,--output", opts->output, "Where to write the PNGs (default: the folder)")->check(non_empty_path());
  sub->add_flag("--cases", opts->cases, "For a sweep, also the pictures of every case");
  return [opts] {
    namespace fs = std::filesystem;
    const fs::path dir(opts->folder);
    std::error_code ec;
    if (!fs::exists(dir, ec))  // a loop of links is not "no such folder": the system's words
      throw ConfigError(path_text(opts->folder) + ": " + (ec ? ec.message() : std::string("no such folder")));
    if (!fs::exists(dir / "summary.json") && !fs::exists(dir / "sweep.csv"))
      throw ConfigError(opts->folder + ": neither a run folder (summary.json) nor a sweep folder (sweep.csv)");
    const FolderLock lock = drawing_lock(dir);  // no run replaces the files while they are drawn
    std::vector<std::string> args = {opts->folder};
    if (!opts->output.empty()) args.insert(args.end(), {"-o", opts->output});
    if (opts->cases) args.push_back("--cases");
    return run_python_plots(args);
  };
}

}  // namespace rotbeam::cli
