// The msislab command line, one subcommand per app/*_command.cpp: each command's file registers
// its subcommand, its options and the callback that runs it and prints its summary
// (add_*_command), so tools/msislab.cpp only parses and maps errors to exit statuses.
#pragma once

#include <cstddef>
#include <string>

namespace CLI {
class App;
}

namespace msislab::app {

/// What the callbacks share with main: argv (to rerun a drawing command under xvfb-run) and the
/// exit status a command sets (kRunsFailedStatus, or 128 + the signal when a long command is
/// stopped).
struct CommandLine {
  int argc = 0;
  char** argv = nullptr;
  int exit_status = 0;
};

/// The exit status of a `montecarlo` or `sweep` (or a merge of either) that finished and wrote its
/// summary while some runs have a failed method: distinct from 0 so that a script under `set -e`
/// does not publish a summary with failures as if it were whole (docs/cli.md).
inline constexpr int kRunsFailedStatus = 3;

/// 0 when `failed` is 0; else prints "COMMAND: finished, but F of N runs have a failed method
/// (exit status 3); see FAILED_JSON" on stderr and returns kRunsFailedStatus. `failed_json` names
/// where the failed.json files are (a shell pattern).
int failed_runs_status(const std::string& command, std::size_t failed, std::size_t runs,
                       const std::string& failed_json);

void add_run_command(CLI::App& app, CommandLine& line);
void add_eval_command(CLI::App& app, CommandLine& line);
void add_simulate_command(CLI::App& app, CommandLine& line);
void add_montecarlo_command(CLI::App& app, CommandLine& line);
void add_sweep_command(CLI::App& app, CommandLine& line);
void add_image_command(CLI::App& app, CommandLine& line);
void add_scans_command(CLI::App& app, CommandLine& line);
void add_footprint_command(CLI::App& app, CommandLine& line);
void add_segment_command(CLI::App& app, CommandLine& line);
void add_plot_command(CLI::App& app, CommandLine& line);
void add_report_command(CLI::App& app, CommandLine& line);
void add_fidelity_command(CLI::App& app, CommandLine& line);
void add_check_command(CLI::App& app, CommandLine& line);

/// --force: the output folder may replace a folder that msislab did not write (never an input).
void add_force_flag(CLI::App& command, bool& force);

/// Every subcommand, in the order of `msislab --help`.
void add_commands(CLI::App& app, CommandLine& line);

/// When the first argument is a word (not an option) that names none of app's subcommands:
/// "unknown command 'WORD' (did you mean 'NEAREST'? see msislab --help)", NEAREST the subcommand
/// near enough to be a typo of it (io::closest_key; without one, no question); else empty. main
/// checks it before parsing, so that a misspelt command is named, and `msislab simulat --help` is
/// an error, not the main help.
std::string unknown_command_message(CLI::App& app, int argc, char** argv);

/// "robocentric, worldcentric, ...": the methods for help texts.
std::string method_list();

/// The figures of a Monte Carlo or sweep directory, drawn by `msislab plot DIR` in a child process
/// and listed as "COMMAND: wrote FILE"; a failure to draw is reported on stderr and leaves the
/// statistics (and the exit status) alone.
void draw_and_list_figures(const std::string& command, const std::string& dir);

}  // namespace msislab::app
