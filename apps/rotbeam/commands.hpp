// Subcommand registration: each adds itself to the app and returns the code to run when chosen.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace rotbeam::cli {

using Command = std::function<int()>;

Command add_modes_command(CLI::App& app);
Command add_impact_command(CLI::App& app);
Command add_run_command(CLI::App& app);
Command add_converge_command(CLI::App& app);
Command add_sweep_command(CLI::App& app);
Command add_merge_command(CLI::App& app);
Command add_plot_command(CLI::App& app);
Command add_animate_command(CLI::App& app);
Command add_reproduce_command(CLI::App& app);
Command add_brush_command(CLI::App& app);
Command add_static_command(CLI::App& app);
Command add_theories_command(CLI::App& app);
Command add_keys_command(CLI::App& app);
Command add_wear_command(CLI::App& app);
Command add_continue_command(CLI::App& app);

}  // namespace rotbeam::cli
