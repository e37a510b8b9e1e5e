// The `a3rig` program: one binary, one subcommand per job (see rigs/cli/).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <exception>
#include <iostream>

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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "a3rig — co-simulation rig that evaluates LLM agents flying UAV missions over "
      "emulated 6G links, and scores episodes with the α³-Bench metric."};
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

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return usage_error(app, e);
  } catch (const std::exception& e) {
    std::cerr << "a3rig: error: " << e.what() << "\n";
    return 2;
  }
  return a3::rigs::command_exit_status();
}
