// The `a3rig` program: one binary, one subcommand per job (see rigs/cli/).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <memory>
#include <string>
#include <exception>
#include <iostream>

#include "rigs/cli/command_list.hpp"
#include "rigs/cli/command_registry.hpp"

namespace {

// "a3rig", "a3rig run", "a3rig node part": the (sub)command being parsed when an error came.
std::string command_path(const CLI::App& app) {
  std::string path = "a3rig";
  for (const CLI::App* at = &app; at != nullptr;) {
    const auto parsed = at->get_subcommands();
    at = parsed.empty() ? nullptr : parsed.back();
    if (at != nullptr) path += " " + at->get_name();
  }
  return path;
}

// A usage error: one line naming the command, the flag and what was wrong; exit status 2.
// --help and --version (CLI11's "errors" with code 0) print what they print and return 0.
int usage_error(const CLI::App& app, const CLI::ParseError& e) {
  if (e.get_exit_code() == 0) return app.exit(e);
  const std::string command = command_path(app);
  std::cerr << command << ": " << e.what() << " (" << command << " --help lists the options)\n";
  return 2;
}

// `a3rig --check-args COMMAND ...`: the command line is parsed and checked (flags, values, files
// that must exist, required options, unexpected arguments) and nothing runs: once CLI11 has
// checked everything, the program's own parse-complete callback, which comes before any
// command's, ends the parse. The README test checks the README's commands this way, so a
// renamed flag fails the suite.
struct ArgumentsChecked {};

bool take_check_args_flag(int& argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) != "--check-args") return false;
  std::rotate(argv + 1, argv + 2, argv + argc);
  --argc;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const bool check_only = take_check_args_flag(argc, argv);
  CLI::App app{
      "a3rig: a co-simulation rig in which LLM agents fly a physical UAV model over emulated 6G\n"
      "links, with a real flight-controller interface on CAN; episodes are scored with α³-Bench."};
  app.formatter(std::make_shared<a3::rigs::CommandListFormatter>());
  app.set_version_flag("--version", std::string("a3rig ") + A3RIG_VERSION);
  app.require_subcommand(1);
  app.fallthrough(false);
  CLI::App* node = app.add_subcommand(
      "node", "Run one rig node on its own (real time, talking LCM / CAN)");
  node->require_subcommand(1);

  auto& commands = a3::rigs::command_registry();
  std::sort(commands.begin(), commands.end(),
            [](const auto& a, const auto& b) { return a.sort_key < b.sort_key; });
  for (const auto& command : commands) command.add_to(app);
  if (node->get_subcommands({}).empty()) app.remove_subcommand(node);
  a3::rigs::group_commands(app);
  if (check_only) app.parse_complete_callback([] { throw ArgumentsChecked{}; });

  try {
    app.parse(argc, argv);
  } catch (const ArgumentsChecked&) {
    std::cout << command_path(app) << ": the command line is valid (--check-args: nothing run)\n";
    return 0;
  } catch (const CLI::ParseError& e) {
    return usage_error(app, e);
  } catch (const std::exception& e) {
    std::cerr << "a3rig: error: " << e.what() << "\n";
    return 2;
  }
  return a3::rigs::command_exit_status();
}
