// The grouped, one-line-per-command list of `a3rig --help` (command_list.hpp).
#include "rigs/cli/command_list.hpp"

#include <algorithm>
#include <map>
#include <sstream>

namespace a3::rigs {
namespace {

constexpr std::size_t kNameColumns = 16;  // "  serve-model   "
constexpr std::size_t kLineColumns = 100;

// The group of each top-level command, and the example shown for each group.
const std::map<std::string, std::string>& command_groups() {
  static const std::map<std::string, std::string> kGroups = {
      {"run", "Fly"},       {"mcp", "Fly"},       {"sweep", "Fly"},    {"node", "Fly"},
      {"serve-model", "Serve"},
      {"score", "Evaluate"}, {"validate", "Evaluate"}, {"report", "Evaluate"}, {"generate", "Evaluate"},
      {"scenario", "Tools"}, {"can", "Tools"}, {"topology", "Tools"}, {"help", "Tools"}};
  return kGroups;
}

constexpr const char* kExamples =
    "Examples (one per group):\n"
    "  a3rig run --scenario traffic-conflict --runtime virtual    fly a mission in about a second\n"
    "  a3rig serve-model --responder scripted --port 8088         a local model for --agent llm\n"
    "  a3rig score ../shared/alphabench/eval_runs                 the public corpus's leaderboard\n"
    "  a3rig scenario generate --seed 7 --difficulty hard         a generated mission as a file\n"
    "a3rig COMMAND --help gives a command's options, statuses and exit codes;\n"
    "a3rig help COMMAND gives just its long texts (statuses, exit codes, environment, details);\n"
    "a3rig --check-args COMMAND ... checks a command line (flags, values, files) without running it.";

}  // namespace

std::string command_summary(const std::string& description) {
  // Up to the first sentence's end, colon, dash, semicolon or parenthesis: the command's gist.
  std::size_t end = std::string::npos;
  for (const char* stop : {". ", ": ", " (", " — ", "; "}) end = std::min(end, description.find(stop));
  std::string first = description.substr(0, end);
  if (!first.empty() && first.back() == '.') first.pop_back();
  const std::size_t room = kLineColumns - kNameColumns;
  // Cut at a word boundary, counting UTF-8 characters (α³ is one column, two bytes).
  std::size_t columns = 0, cut = first.size(), last_space = std::string::npos;
  for (std::size_t i = 0; i < first.size(); ++i) {
    if ((static_cast<unsigned char>(first[i]) & 0xC0) == 0x80) continue;
    if (first[i] == ' ') last_space = i;
    if (++columns > room - 1) {
      cut = last_space != std::string::npos ? last_space : i;
      break;
    }
  }
  return cut < first.size() ? first.substr(0, cut) + "…" : first;
}

std::string wrapped(const std::string& text, std::size_t width) {
  std::string out;
  std::size_t line_columns = 0;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (!out.empty()) out += '\n';
    line_columns = 0;
    std::istringstream words(line);
    for (std::string word; words >> word;) {
      std::size_t columns = 0;
      for (const char c : word) columns += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
      if (line_columns > 0 && line_columns + 1 + columns > width) {
        out += '\n';
        line_columns = 0;
      } else if (line_columns > 0) {
        out += ' ';
        ++line_columns;
      }
      out += word;
      line_columns += columns;
    }
  }
  return out;
}

HelpSections help_sections(const std::string& description) {
  const std::size_t paragraph_end = description.find('\n');
  const std::string first = description.substr(0, paragraph_end);
  const std::string rest = paragraph_end == std::string::npos ? "" : description.substr(paragraph_end + 1);
  const std::size_t exit_status = first.find(" Exit status");
  if (exit_status == std::string::npos) return {first, rest};
  return {first.substr(0, exit_status), first.substr(exit_status + 1) + (rest.empty() ? "" : "\n" + rest)};
}

std::string CommandListFormatter::make_description(const CLI::App* app) const {
  if (app->get_parent() == nullptr) return CLI::Formatter::make_description(app);
  const std::string summary = help_sections(app->get_description()).summary;
  return summary.empty() ? "" : wrapped(summary, kLineColumns) + "\n";
}

std::string closing_section(const CLI::App& command) {
  std::string closing = help_sections(command.get_description()).closing;
  if (!command.get_footer().empty()) closing += (closing.empty() ? "" : "\n") + command.get_footer();
  std::string spaced;  // a blank line between paragraphs
  for (const char c : closing) spaced += c == '\n' ? std::string("\n\n") : std::string(1, c);
  return closing.empty() ? "" : wrapped(spaced, kLineColumns) + "\n";
}

std::string CommandListFormatter::make_footer(const CLI::App* app) const {
  if (app->get_parent() == nullptr) return CLI::Formatter::make_footer(app);  // the examples, aligned
  return closing_section(*app);
}

std::string CommandListFormatter::make_option_desc(const CLI::Option* option) const {
  return wrapped(option->get_description(), kLineColumns - get_column_width());
}

std::string CommandListFormatter::make_subcommand(const CLI::App* sub) const {
  std::string name = "  " + sub->get_name();
  name.resize(std::max(name.size() + 1, kNameColumns), ' ');
  return name + command_summary(sub->get_description()) + "\n";
}

void group_commands(CLI::App& app) {
  for (CLI::App* command : app.get_subcommands({})) {
    const auto group = command_groups().find(command->get_name());
    command->group(group == command_groups().end() ? "Other" : group->second);
  }
  app.footer(kExamples);
}

}  // namespace a3::rigs
