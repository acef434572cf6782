// The msislab command line: parses arguments; each subcommand's options and callback live beside
// the command in app/ (app/cli.hpp). Exit status 0 on success, 2 on bad input with one line on
// stderr naming the file, line or key (docs/cli.md), 1 with one line on stderr when a run cannot
// go on (a non-finite estimate), 3 when a Monte Carlo or sweep finished with failed runs (set by
// the command, app/cli.hpp), 128 + the signal when a long command is stopped.
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "app/cli.hpp"
#include "io/input_error.hpp"

namespace {
constexpr int kFailure = 1;
constexpr int kBadInput = 2;
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"msislab: a testbed for underwater SLAM with a mechanically scanned imaging sonar"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "msislab " MSISLAB_VERSION);  // project(VERSION) in CMake
  msislab::app::CommandLine line{argc, argv};
  msislab::app::add_commands(app, line);
  if (const std::string unknown = msislab::app::unknown_command_message(app, argc, argv);
      !unknown.empty()) {
    std::cerr << "msislab: " << unknown << "\n";
    return kBadInput;
  }
  try {
    app.parse(argc, argv);  // runs the chosen subcommand's callback
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "msislab: " << e.what() << " (see msislab --help)\n";
    return kBadInput;
  } catch (const msislab::io::InputError& e) {
    std::cerr << "msislab: " << e.what() << "\n";
    return kBadInput;
  } catch (const std::exception& e) {  // a run that cannot go on (a NumericalError)
    std::cerr << "msislab: " << e.what() << "\n";
    return kFailure;
  }
  return line.exit_status;
}
