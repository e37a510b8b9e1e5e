// `a3rig --help`: the commands one line each, grouped by what a user does with them (fly,
// serve, evaluate, tools), with an example per group. A command's own --help: its summary (the
// description's first paragraph up to "Exit status"), usage and options, then a closing section
// with the rest (exit status, environment, details); all of it wrapped at 100 columns.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace a3::rigs {

// The first sentence of a command's description, cut to fit a 100-column line after the name.
std::string command_summary(const std::string& description);

// `text` in lines of at most `width` columns (UTF-8 characters), broken between words; its own
// line breaks are kept.
std::string wrapped(const std::string& text, std::size_t width);

// A description split for a command's help: the summary and the closing section.
struct HelpSections {
  std::string summary;
  std::string closing;
};
HelpSections help_sections(const std::string& description);

// A command's closing section as its --help ends with it (exit status, environment, details),
// wrapped; "" when it has none. `a3rig help COMMAND` prints just this.
std::string closing_section(const CLI::App& command);

// Lists a command's subcommands one line each (its first sentence), in their groups; a command's
// own help as above.
class CommandListFormatter : public CLI::Formatter {
 public:
  std::string make_subcommand(const CLI::App* sub) const override;
  std::string make_description(const CLI::App* app) const override;
  std::string make_footer(const CLI::App* app) const override;
  std::string make_option_desc(const CLI::Option* option) const override;
};

// Puts every top-level command in its group (an unknown one in "Other") and sets the
// program's footer: one example per group.
void group_commands(CLI::App& app);

}  // namespace a3::rigs
