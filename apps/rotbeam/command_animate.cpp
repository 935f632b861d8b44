// `rotbeam animate DIR`: an animation of a run (Python's rotbeam.animate): the filament's shape
// through contact, as GIF and, where ffmpeg is installed, MP4.
#include "commands.hpp"
#include "common.hpp"
#include "python_bridge.hpp"

#include "rotbeam/pass_output.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>

namespace rotbeam::cli {

namespace {

// The widest hub angle a window may name [deg]: the end of the longest run the keys allow
// (simulation.revolutions ≤ 1e7 whole turns from -90°), with room.
constexpr double kMaxWindowDeg = 1e10;

// A check for a number in (0, max]: "must be a number in (0, MAX], got VALUE" (CLI11's PositiveNumber
// stated a range from 0 with a 309-digit end, and let 1e300 through).
CLI::Validator positive_at_most(double max) {
  char text[48];
  std::snprintf(text, sizeof text, "(0, %g]", max);
  const std::string range = text;
  return CLI::Validator(
      [range, max](std::string& s) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        if (s.empty() || end != s.c_str() + s.size() || !(v > 0.0) || !(v <= max))
          return "must be a number in " + range + ", got " + s;
        return "";
      },
      "in " + range);
}
// A check for a number in [min, max], in the form of positive_at_most (CLI11's Range printed
// "Value 0 not in range 0.100000 to 100.000000"); `whole` asks for a whole number, written as one
// ("1e3" is refused in words, not as out of range).
CLI::Validator number_in(double min, double max, bool whole) {
  const std::string range = "[" + number_text(min) + ", " + number_text(max) + "]";
  return CLI::Validator(
      [range, min, max, whole](std::string& s) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        const bool digits = !s.empty() && s.find_first_not_of("0123456789", s[0] == '+' || s[0] == '-' ? 1 : 0) == std::string::npos;
        if (s.empty() || end != s.c_str() + s.size() || !(v >= min) || !(v <= max) || (whole && !digits))
          return std::string(whole ? "must be a whole number in " : "must be a number in ") + range + ", got " + s;
        return "";
      },
      "in " + range);
}

// --window FROM:TO: two finite hub angles [deg], FROM below TO (the module's own check printed
// argparse's usage block and exited 1; -1e308:1e308 overflowed in matplotlib, a traceback).
CLI::Validator hub_angle_window() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        const std::size_t colon = s.find(':');
        double v[2] = {0.0, 0.0};
        const std::string part[2] = {colon == std::string::npos ? s : s.substr(0, colon),
                                     colon == std::string::npos ? std::string() : s.substr(colon + 1)};
        for (int k = 0; k < 2; ++k) {
          char* end = nullptr;
          v[k] = std::strtod(part[k].c_str(), &end);
          if (colon == std::string::npos || part[k].empty() || end != part[k].c_str() + part[k].size() ||
              !std::isfinite(v[k]) || std::abs(v[k]) > kMaxWindowDeg)
            return "must be FROM:TO, two hub angles in degrees within ±" + number_text(kMaxWindowDeg) +
                   " (e.g. -12:40), got " + s;
        }
        if (!(v[0] < v[1])) return "FROM must be below TO, got " + s;
        return "";
      },
      "FROM:TO");
}

struct AnimateOptions {
  std::string folder, output, window;
  std::optional<int> frames;
  std::optional<double> frames_per_degree, zoom_mm;
  double magnify = 1.0, fps = 20.0;
  bool quiet = false;
};
}  // namespace

Command add_animate_command(CLI::App& app) {
  auto opts = std::make_shared<AnimateOptions>();
  CLI::App* sub = app.add_subcommand("animate", "An animation of a run: the filament bending through contact (GIF; MP4 with ffmpeg)");
  sub->add_option("folder", opts->folder, "A folder written by `rotbeam run`")->required();
  sub->add_option("-o,--output", opts->output,
                  "A .gif or .mp4 file (default: DIR/animation.gif, and DIR/animation.mp4 where ffmpeg is installed)")
      ->check(non_empty_path());
  CLI::Option* frames = sub->add_option("--frames", opts->frames, "Number of frames (default 240, at most 2000)")->check(number_in(2, 2000, true));
  sub->add_option("--frames-per-degree", opts->frames_per_degree, "Frames per degree of hub angle instead")
      ->check(positive_at_most(1e3))
      ->excludes(frames);
  sub->add_option("--window", opts->window,
                  "FROM:TO, the hub angles shown [deg] (default: the contact region with a margin; the last revolution "
                  "of a run over many)")
      ->check(hub_angle_window());
  sub->add_option("--zoom", opts->zoom_mm, "Half-width of the view around the tip [mm] (default: three surface depths, at least 2.5)")
      ->check(number_in(1e-3, 1e4, false));
  sub->add_option("--magnify", opts->magnify, "Draw the deflection this many times (default 1: to scale)")
      ->check(number_in(1e-3, 1e6, false));
  sub->add_option("--fps", opts->fps, "Frames per second of the file (default 20)")->check(number_in(0.1, 100.0, false));
  sub->add_flag("--quiet", opts->quiet, "No frame counter and no `wrote` lines (notes and errors are still said)");
  return [opts] {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(fs::path(opts->folder), ec))  // a loop of links is not "no such folder": the system's words
      throw ConfigError(path_text(opts->folder) + ": " + (ec ? ec.message() : std::string("no such folder")));
    if (!fs::exists(fs::path(opts->folder) / "summary.json"))
      throw ConfigError(path_text(opts->folder) + ": not a run folder (no summary.json)");
    // A brush's folder holds sums over its filaments, no filament's history to animate (it named a
    // summary entry the brush does not write).
    if (brush_output_folder(opts->folder))
      throw ConfigError(path_text(opts->folder) + ": holds a brush (rotbeam brush), not a run: animate draws one "
                        "filament's run; draw the brush with `rotbeam plot " + opts->folder +
                        "`, or animate one of its filaments with `rotbeam run` (without the [brush] keys)");
    if (!opts->output.empty()) check_output_file("-o", opts->output, {".gif", ".mp4"});
    else
      try {  // the default files: a folder under their names stopped the animation once drawn
        refuse_folders_under_file_names(opts->folder, {"animation.gif", "animation.mp4"}, "animate");
      } catch (const std::runtime_error& e) {
        throw ConfigError(e.what());
      }
    const FolderLock lock = drawing_lock(opts->folder);  // no run replaces the files while they are drawn
    std::vector<std::string> args = {opts->folder};
    if (!opts->output.empty()) args.insert(args.end(), {"-o", opts->output});
    if (opts->frames) args.insert(args.end(), {"--frames", std::to_string(*opts->frames)});
    if (opts->frames_per_degree) args.insert(args.end(), {"--frames-per-degree", number_text(*opts->frames_per_degree)});
    if (!opts->window.empty()) args.push_back("--window=" + opts->window);
    if (opts->zoom_mm) args.insert(args.end(), {"--zoom", number_text(*opts->zoom_mm)});
    args.insert(args.end(), {"--magnify", number_text(opts->magnify), "--fps", number_text(opts->fps)});
    if (opts->quiet) args.push_back("--quiet");
    return run_python_module("rotbeam.animate", args);
  };
}

}  // namespace rotbeam::cli
