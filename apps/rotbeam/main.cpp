// rotbeam: simulator of a flexible filament on a spinning hub striking a rigid surface.
#include "commands.hpp"
#include "common.hpp"

#include "rotbeam/version.hpp"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <map>
#include <string>
#include <poll.h>
#include <unistd.h>

namespace {

// True when standard output is a pipe whose reader has gone (`rotbeam modes … | head -1`).
bool stdout_reader_gone() {
  struct pollfd p {};
  p.fd = STDOUT_FILENO;
  p.events = POLLOUT;
  return ::poll(&p, 1, 0) == 1 && (p.revents & POLLERR) != 0;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace rotbeam::cli;
  // A reader that stops reading (`| head -1`) is not an error: instead of dying by SIGPIPE (exit
  // 141), the writes fail and the end below says nothing of it.
  std::signal(SIGPIPE, SIG_IGN);
  CLI::App app{"rotbeam: a flexible filament on a spinning hub whose tip strikes and rubs a rigid surface (a plane, a\n"
               "cylinder or a casing), alone or as a brush\n"
               "(assumed modes, momentum-balance impacts, Lagrange-multiplier contact with Coulomb friction)"};
  app.name("rotbeam");
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("rotbeam ") + rotbeam::kVersion);
  Command modes = add_modes_command(app);
  Command impact = add_impact_command(app);
  Command run = add_run_command(app);
  Command converge = add_converge_command(app);
  Command sweep = add_sweep_command(app);
  Command merge = add_merge_command(app);
  Command plot = add_plot_command(app);
  Command animate = add_animate_command(app);
  Command reproduce = add_reproduce_command(app);
  Command brush = add_brush_command(app);
  Command statics = add_static_command(app);
  Command theories = add_theories_command(app);
  Command keys = add_keys_command(app);
  Command wear = add_wear_command(app);
  Command continuation = add_continue_command(app);
  if (argc > 1 && argv[1][0] != '-' && std::string(argv[1]) != "modes" && std::string(argv[1]) != "impact" &&
      std::string(argv[1]) != "run" && std::string(argv[1]) != "converge" &&
      std::string(argv[1]) != "sweep" && std::string(argv[1]) != "merge" && std::string(argv[1]) != "brush" &&
      std::string(argv[1]) != "plot" && std::string(argv[1]) != "animate" &&
      std::string(argv[1]) != "reproduce" && std::string(argv[1]) != "static" && std::string(argv[1]) != "theories" &&
      std::string(argv[1]) != "keys" && std::string(argv[1]) != "wear" && std::string(argv[1]) != "continue") {
    print_error("unknown command '" + std::string(argv[1]) + "' (commands: run, sweep, merge, brush, wear, continue, plot, animate, reproduce, converge, theories, impact, modes, static, keys; see rotbeam --help)");
    return kBadInput;
  }
  const int code = [&]() -> int {
    try {
      app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
      return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
      return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
      return app.exit(e);
    } catch (const CLI::ParseError& e) {
      print_error(e.what());
      return kBadInput;
    }
    try {
      if (app.got_subcommand("modes")) return modes();
      if (app.got_subcommand("impact")) return impact();
      if (app.got_subcommand("run")) return run();
      if (app.got_subcommand("converge")) return converge();
      if (app.got_subcommand("sweep")) return sweep();
      if (app.got_subcommand("merge")) return merge();
      if (app.got_subcommand("plot")) return plot();
      if (app.got_subcommand("animate")) return animate();
      if (app.got_subcommand("reproduce")) return reproduce();
      if (app.got_subcommand("brush")) return brush();
      if (app.got_subcommand("static")) return statics();
      if (app.got_subcommand("theories")) return theories();
      if (app.got_subcommand("keys")) return keys();
      if (app.got_subcommand("wear")) return wear();
      if (app.got_subcommand("continue")) return continuation();
    } catch (const rotbeam::ConfigError& e) {
      print_error(e.what());
      return kBadInput;
    } catch (const std::invalid_argument& e) {
      print_error(e.what());
      return kBadInput;
    } catch (const std::exception& e) {
      print_error(e.what());
      return kRuntimeFailure;
    }
    return kBadInput;
  }();
  // Output that could not be written (a full disk, a failing device) is a failure, not a success,
  // the help and the version included; a reader that took what it wanted and left is not.
  std::cout.flush();
  if (std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout) {
    if (stdout_reader_gone()) return code;
    const int err = errno;
    print_error(std::string("standard output: the results could not be written (") +
                (err != 0 ? std::strerror(err) : "write error") + ")");
    return code == 0 ? kRuntimeFailure : code;
  }
  return code;
}
