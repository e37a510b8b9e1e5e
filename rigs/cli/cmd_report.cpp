// `a3rig report EPISODE_OR_RUN_FOLDER [-o report.html]`: the episode report (episode_report.hpp).
#include <CLI/CLI.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "common/json_file.hpp"
#include "rigs/cli/command_registry.hpp"
#include "rigs/generator/scenario_spec.hpp"
#include "rigs/report/episode_report.hpp"
#include "rigs/scenario/shared_dir.hpp"

namespace a3::rigs {
namespace {

namespace fs = std::filesystem;

struct ReportArgs {
  std::string input;
  std::string out;
  std::string scenario;
  std::string shared_dir;
};

// A run folder holds episode.json; anything else is the episode file itself.
fs::path episode_file(const fs::path& input) {
  if (!fs::is_directory(input)) return input;
  const fs::path inside = input / "episode.json";
  if (!fs::is_regular_file(inside)) {
    throw common::InputError(input.string() + ": not a run folder (no episode.json in it); give an episode file or a folder written by a3rig run");
  }
  return inside;
}

bool is_inside(const fs::path& file, const fs::path& folder) {
  std::error_code ec;
  const fs::path f = fs::weakly_canonical(fs::absolute(file), ec);
  const fs::path d = fs::weakly_canonical(fs::absolute(folder), ec);
  if (ec || d.empty()) return false;
  const auto [folder_end, file_at] = std::mismatch(d.begin(), d.end(), f.begin(), f.end());
  return folder_end == d.end();
}

// Beside the episode: report.html for a run's episode.json, <name>.html for any other file;
// but an episode of the shared corpus (someone else's data) gets <name>.html in the current folder.
fs::path default_output(const fs::path& episode, const fs::path& shared) {
  if (episode.filename() == "episode.json") return episode.parent_path() / "report.html";
  if (is_inside(episode, shared)) return episode.filename().replace_extension(".html");
  fs::path out = episode;
  return out.replace_extension(".html");
}

int run_report(const ReportArgs& args) {
  const fs::path episode_path = episode_file(args.input);
  const episode::Episode episode = episode::Episode::load(episode_path);
  const fs::path shared = args.shared_dir.empty() ? default_shared_dir() : fs::path(args.shared_dir);
  const std::optional<Scenario> scenario =
      args.scenario.empty() ? scenario_of_episode(episode, shared) : std::optional<Scenario>(load_scenario_spec(args.scenario, shared));
  const fs::path out = args.out.empty() ? default_output(episode_path, shared) : fs::path(args.out);
  write_episode_report(out, nlohmann::json(episode.document()), scenario, episode_path.string());
  std::cout << "report: " << out.string() << (scenario ? "" : " (no scenario found: the map shows no world)") << "\n";
  return 0;
}

}  // namespace

A3_REGISTER_COMMAND("16-report", [](CLI::App& app) {
  auto args = std::make_shared<ReportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Write one self-contained HTML page for an episode (a run folder or an episode file, the public "
      "corpus's too): the map (geofence, no-fly zones, objectives, peers' plans, the track coloured by "
      "agent turn, safety events), timelines (altitude, speed, battery, link, turns with think time and "
      "link delay), the score and the dialogue, with a time slider. Opens offline in any browser.");
  cmd->add_option("input", args->input, "a run folder (with episode.json) or an episode file")->required()->check(CLI::ExistingPath);
  cmd->add_option("-o,--out", args->out, "the HTML file (default: report.html in a run folder, else <episode>.html beside it; for an episode of the "
                  "shared corpus, <episode>.html in the current folder)");
  cmd->add_option("--scenario", args->scenario,
                  "the scenario to draw the world from (default: the one the episode names, or its initial_state)");
  cmd->add_option("--shared-dir", args->shared_dir, "the shared folder for alphabench: scenarios (default: ../shared or $A3_SHARED_DIR)");
  cmd->callback([args] { command_exit_status() = run_report(*args); });
});

}  // namespace a3::rigs
