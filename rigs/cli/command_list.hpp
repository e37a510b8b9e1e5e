// `a3rig --help`: the commands one line each, grouped by what a user does with them (fly,
// serve, evaluate, tools), with an example per group. A command's own --help keeps its whole text.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace a3::rigs {

// The first sentence of a command's description, cut to fit a 100-column line after the name.
std::string command_summary(const std::string& description);

// Lists a command's subcommands one line each (its first sentence), in their groups.
class CommandListFormatter : public CLI::Formatter {
 public:
  std::string make_subcommand(const CLI::App* sub) const override;
};

// Puts every top-level command in its group (an unknown one in "Other") and sets the
// program's footer: one example per group.
void group_commands(CLI::App& app);

}  // namespace a3::rigs
