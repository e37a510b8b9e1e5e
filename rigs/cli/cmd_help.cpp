// `a3rig help COMMAND [SUBCOMMAND]`: a command's long texts (its statuses and exit codes, the
// environment variables it reads, details), the closing section of its --help, without the
// options: what a user looks up after the first run.
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "rigs/cli/command_list.hpp"
#include "rigs/cli/command_registry.hpp"

namespace a3::rigs {
namespace {

// The command named by `words` below the program ("node fc"), or an error naming the known ones.
const CLI::App& find_command(const CLI::App& program, const std::vector<std::string>& words) {
  const CLI::App* at = &program;
  std::string path = "a3rig";
  for (const std::string& word : words) {
    const CLI::App* next = nullptr;
    std::string known;
    for (const CLI::App* sub : at->get_subcommands({})) {
      if (sub->get_name() == word) next = sub;
      if (sub->get_name() != "help") known += (known.empty() ? "" : ", ") + sub->get_name();
    }
    if (next == nullptr) throw std::invalid_argument(path + " has no command '" + word + "' (known: " + known + ")");
    at = next;
    path += " " + word;
  }
  return *at;
}

int print_long_texts(const CLI::App& program, const std::vector<std::string>& words) {
  const CLI::App& command = find_command(program, words);
  std::string name = "a3rig";
  for (const std::string& word : words) name += " " + word;
  const std::string closing = closing_section(command);
  if (closing.empty()) {
    std::cout << name << " has no long texts beyond its options: " << name << " --help\n";
  } else {
    std::cout << closing;
  }
  return 0;
}

}  // namespace

A3_REGISTER_COMMAND("95-help", [](CLI::App& app) {
  auto words = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd = app.add_subcommand(
      "help",
      "Print a command's long texts: its statuses and exit codes, the environment variables it reads and "
      "details, as its --help ends with them, without the options (e.g. a3rig help run). "
      "Exit status: 0 printed, 2 no such command.");
  cmd->add_option("command", *words, "the command, and its subcommand if it has them (e.g. run, sweep, node fc)")
      ->required();
  const CLI::App* program = &app;
  cmd->callback([program, words] {
    try {
      command_exit_status() = print_long_texts(*program, *words);
    } catch (const std::invalid_argument& e) {
      std::cerr << "a3rig help: " << e.what() << "\n";
      command_exit_status() = 2;
    }
  });
});

}  // namespace a3::rigs
