// Self-registering subcommands of the `a3rig` program.
//
// A subcommand is one file rigs/cli/cmd_<name>.cpp that defines a function adding its
// CLI11 subcommand to the app and registers it with A3_REGISTER_COMMAND. The file is
// picked up by rigs/CMakeLists.txt without editing any shared file. Node subcommands
// (`a3rig node <name>`) attach to the "node" parent with app.get_subcommand("node").
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace a3::rigs {

// Adds one subcommand (with its callback) to `app`.
using CommandRegistrar = std::function<void(CLI::App& app)>;

struct RegisteredCommand {
  std::string sort_key;  // registration order in --help: by this key
  CommandRegistrar add_to;
};

inline std::vector<RegisteredCommand>& command_registry() {
  static std::vector<RegisteredCommand> commands;
  return commands;
}

struct CommandRegistration {
  CommandRegistration(std::string sort_key, CommandRegistrar registrar) {
    command_registry().push_back({std::move(sort_key), std::move(registrar)});
  }
};

// The exit status a subcommand's callback wants the program to return.
inline int& command_exit_status() {
  static int status = 0;
  return status;
}

}  // namespace a3::rigs

#define A3_CONCAT_INNER(a, b) a##b
#define A3_CONCAT(a, b) A3_CONCAT_INNER(a, b)
// A3_REGISTER_COMMAND("20-score", [](CLI::App& app) { ... });
// Variadic, so that commas inside the lambda (braced initialisers) need no extra parentheses.
#define A3_REGISTER_COMMAND(sort_key, ...)                                      \
  static const ::a3::rigs::CommandRegistration A3_CONCAT(a3_command_, __LINE__) { \
    sort_key, __VA_ARGS__                                                       \
  }
