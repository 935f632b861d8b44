// `rotbeam plot DIR`: the pictures of a run or a sweep folder (Python's rotbeam.plots).
#include "commands.hpp"
#include "common.hpp"
#include "python_bridge.hpp"

#include "rotbeam/pass_output.hpp"

#include <filesystem>

namespace rotbeam::cli {

namespace {
struct PlotOptions {
  std::string folder, output;
  bool cases = false;
  std::string brute_force;
};
}  // namespace

Command add_plot_command(CLI::App& app) {
  auto opts = std::make_shared<PlotOptions>();
  CLI::App* sub = app.add_subcommand("plot", "Write the PNG pictures of a run, sweep or brush folder (matplotlib)");
  sub->add_option("folder", opts->folder,
                  "A folder written by `rotbeam run`, `sweep`, `merge`, `brush`, `wear` or `continue`")->required();
  sub->add_option("-o,--output", opts->output, "Where to write the PNGs (default: the folder)")->check(non_empty_path());
  sub->add_flag("--cases", opts->cases, "For a sweep, also the pictures of every case");
  sub->add_option("--brute-force", opts->brute_force,
                  "For a continuation, a sweep folder over the same key whose steady states are drawn over the branch")
      ->check(non_empty_path());
  return [opts] {
    namespace fs = std::filesystem;
    const fs::path dir(opts->folder);
    std::error_code ec;
    if (!fs::exists(dir, ec))  // a loop of links is not "no such folder": the system's words
      throw ConfigError(path_text(opts->folder) + ": " + (ec ? ec.message() : std::string("no such folder")));
    if (!fs::exists(dir / "summary.json") && !fs::exists(dir / "sweep.csv"))
      throw ConfigError(opts->folder + ": neither a run folder (summary.json) nor a sweep folder (sweep.csv)");
    // A folder under a picture's name would stop the drawing after the pictures before it: refused
    // before any is drawn, as run and brush refuse one under their files' names.
    const fs::path out = opts->output.empty() ? dir : fs::path(opts->output);
    const std::vector<std::string> run_pictures = {"normal_force_vs_y.png", "tip_path.png", "modal_coordinates.png",
                                                   "energy.png", "impacts.png"};
    const std::vector<std::string> brush_pictures = {"brush_force.png", "brush_profile.png", "brush_filaments.png"};
    try {
      if (fs::exists(dir / "summary.json")) {
        refuse_folders_under_file_names(out, brush_output_folder(dir) ? brush_pictures : run_pictures, "plot");
      } else {
        refuse_folders_under_file_names(out, {"sweep_metrics.png", "sweep_normal_force_vs_y.png", "rub_map.png",
                                              "brush_map.png"}, "plot");
        if (opts->cases)
          for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
            if (e.is_directory(ec) && e.path().filename().string().rfind("case-", 0) == 0) {
              refuse_folders_under_file_names(out / e.path().filename(), run_pictures, "plot");
              refuse_folders_under_file_names(out / e.path().filename(), brush_pictures, "plot");
            }
      }
    } catch (const std::runtime_error& e) {
      throw ConfigError(e.what());
    }
    const FolderLock lock = drawing_lock(dir);  // no run replaces the files while they are drawn
    std::vector<std::string> args = {opts->folder};
    if (!opts->output.empty()) args.insert(args.end(), {"-o", opts->output});
    if (opts->cases) args.push_back("--cases");
    if (!opts->brute_force.empty()) args.insert(args.end(), {"--brute-force", opts->brute_force});
    return run_python_plots(args);
  };
}

}  // namespace rotbeam::cli
