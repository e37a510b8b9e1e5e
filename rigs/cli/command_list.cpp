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
      {"scenario", "Tools"}, {"can", "Tools"}};
  return kGroups;
}

constexpr const char* kExamples =
    "Examples (one per group):\n"
    "  a3rig run --scenario traffic-conflict --runtime virtual    fly a mission in about a second\n"
    "  a3rig serve-model --responder scripted --port 8088         a local model for --agent llm\n"
    "  a3rig score ../shared/alphabench/eval_runs                 the public corpus's leaderboard\n"
    "  a3rig scenario generate --seed 7 --difficulty hard         a generated mission as a file\n"
    "a3rig COMMAND --help gives a command's options, statuses and exit codes;\n"
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
