// `a3rig score DIR...`: scores α³-Bench episode corpora (SPEC-alpha3.md §2–§3) and prints the
// leaderboard; optionally one row per episode and the paper's figures.
#include <CLI/CLI.hpp>

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "eval/corpus_scorer.hpp"
#include "eval/episode_schema.hpp"
#include "eval/leaderboard_format.hpp"
#include "eval/leaderboard_plots.hpp"
#include "eval/per_episode_writer.hpp"
#include "rigs/cli/command_registry.hpp"
#include "rigs/cli/flag_checks.hpp"

namespace a3::rigs {
namespace {

constexpr std::size_t kInvalidFilesListed = 20;

struct ScoreArgs {
  std::vector<std::string> paths;
  std::optional<int64_t> budget;
  std::string profile = "release";
  std::string format = "table";
  std::string output;
  std::string per_episode;
  std::string plots;
  std::string model;
  std::string domain = "uav";
  std::size_t threads = 0;
  double max_file_mb = 16.0;
  bool quiet = false;
};

int run_score(const ScoreArgs& args) {
  const eval::JsonSchemaValidator validator(eval::episode_schema_json(), eval::kEpisodeSchemaName);
  eval::ScoreOptions options;
  options.profile = eval::profile_by_name(args.profile);
  options.budget = args.budget;
  options.threads = args.threads;
  options.max_file_bytes = static_cast<std::uintmax_t>(args.max_file_mb * 1048576.0);
  options.corpus.model_override = args.model;
  options.corpus.domain_override = args.domain;
  const auto format = eval::parse_leaderboard_format(args.format);

  std::unique_ptr<eval::PerEpisodeWriter> per_episode;
  if (!args.per_episode.empty()) {
    per_episode = std::make_unique<eval::PerEpisodeWriter>(args.per_episode);
  }
  uint64_t invalid_listed = 0;
  options.on_episode = [&](const eval::ScoredEpisode& episode) {
    if (per_episode) per_episode->write(episode);
    if (episode.check.status != eval::EpisodeStatus::kInvalid) return;
    if (invalid_listed++ < kInvalidFilesListed) {
      const auto& violations = episode.check.violations;
      std::cerr << "a3rig score: invalid: " << episode.file.path.string() << ": "
                << (violations.empty() ? std::string("invalid") : eval::to_string(violations.front()));
      if (violations.size() > 1) std::cerr << " (+" << violations.size() - 1 << " more)";
      std::cerr << "\n";
    }
  };
  const bool show_progress = !args.quiet && ::isatty(STDERR_FILENO);
  double last_progress_s = 0.0;
  options.on_progress = [&](const eval::ScoreProgress& p) {
    if (!show_progress || p.elapsed_s - last_progress_s < 1.0) return;
    last_progress_s = p.elapsed_s;
    std::fprintf(stderr, "\ra3rig score: pass %d/%d: %llu files (%.0f files/s)   ", p.pass,
                 p.passes, static_cast<unsigned long long>(p.files_done),
                 p.files_done / std::max(p.elapsed_s, 1e-9));
  };

  std::vector<std::filesystem::path> roots(args.paths.begin(), args.paths.end());
  const eval::ScoreResult result = eval::score_corpus(roots, validator, options);
  if (show_progress && last_progress_s > 0.0) std::fprintf(stderr, "\n");
  if (per_episode) per_episode->close();
  if (invalid_listed > kInvalidFilesListed) {
    std::cerr << "a3rig score: ... and " << invalid_listed - kInvalidFilesListed
              << " more invalid files (--per-episode FILE lists every file with its reason)\n";
  }
  for (const auto& warning : result.warnings) std::cerr << "a3rig score: warning: " << warning << "\n";

  if (result.files == 0) {
    std::cerr << "a3rig score: no episode files found in the given folders (looked for "
                 "<provider>/<model>/<domain>/sc-XXXX-ep-YY.json and a3rig's episode.json)\n";
    return 2;
  }
  if (args.output.empty()) {
    eval::write_leaderboard(std::cout, result.models, format);
    std::cout.flush();
  } else {
    std::ostringstream table;
    eval::write_leaderboard(table, result.models, format);
    common::write_file_atomically(args.output, table.str());
  }
  if (!args.plots.empty()) eval::write_leaderboard_plots(args.plots, result.models);

  if (!args.quiet) {
    std::fprintf(stderr,
                 "a3rig score: %llu files (%llu valid, %llu failure stubs, %llu invalid), %zu "
                 "models, in %.2f s (%.0f files/s); profile %s, budget %lld (%s), T_opt %g\n",
                 static_cast<unsigned long long>(result.files),
                 static_cast<unsigned long long>(result.valid),
                 static_cast<unsigned long long>(result.failure_stubs),
                 static_cast<unsigned long long>(result.invalid), result.models.size(),
                 result.seconds, result.files / std::max(result.seconds, 1e-9),
                 options.profile.name.c_str(), static_cast<long long>(result.budget),
                 args.budget ? "--budget"
                             : (std::to_string(result.scenarios_found) + " scenarios x " +
                                std::to_string(result.episodes_per_scenario) + " episodes each")
                                   .c_str(),
                 result.optimal_turns);
    if (result.ignored_json_files > 0) {
      std::fprintf(stderr, "a3rig score: ignored %llu .json files not named sc-XXXX-ep-YY.json\n",
                   static_cast<unsigned long long>(result.ignored_json_files));
    }
    if (!args.plots.empty()) std::cerr << "a3rig score: figures written to " << args.plots << "\n";
  }
  return result.invalid > 0 ? 1 : 0;
}

}  // namespace

A3_REGISTER_COMMAND("30-score", [](CLI::App& app) {
  auto args = std::make_shared<ScoreArgs>();
  CLI::App* cmd = app.add_subcommand(
      "score",
      "Score α³-Bench episode corpora: the six pillars and α³ per episode, the model-level "
      "aggregates, and a leaderboard (SPEC-alpha3.md). Folders are searched for "
      "<provider>/<model>/<domain>/sc-XXXX-ep-YY.json (the α³-Bench layout; flat folders need --model) "
      "and for a3rig's own episode.json (a run or sweep folder: one row per agent, think time and "
      "slice, named from the file's _meta and _rig). Invalid files "
      "count as failures and are listed on stderr. Exit status: 0 every file valid, 1 some "
      "invalid, 2 nothing found or a usage error.");
  cmd->add_option("paths", args->paths, "corpus folders (or episode files)")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_option("--budget", args->budget,
                  "episode budget B per model (default: scenarios found x episodes per scenario)")
      ->check(a3::rigs::positive());
  cmd->add_option("--profile", args->profile,
                  "release (default: reproduces the public leaderboard) or paper (the paper's "
                  "budgets, median T_opt)")
      ->check(CLI::IsMember({"release", "paper"}));
  cmd->add_option("--format", args->format, "table (default), csv, json or markdown")
      ->check(CLI::IsMember({"table", "csv", "json", "markdown"}));
  cmd->add_option("-o,--output", args->output, "write the leaderboard to this file, not stdout");
  cmd->add_option("--per-episode", args->per_episode,
                  "write one row per episode (every pillar and its inputs): CSV, or JSON Lines "
                  "if the name ends in .jsonl");
  cmd->add_option("--plots", args->plots, "write the leaderboard figures (PNG, gnuplot) here");
  cmd->add_option("--model", args->model,
                  "every episode found belongs to this model (for flat folders)");
  cmd->add_option("--domain", args->domain, "domain label with --model (default uav)");
  cmd->add_option("--threads", args->threads, "worker threads (default: one per CPU)");
  cmd->add_option("--max-file-mb", args->max_file_mb,
                  "files larger than this are invalid (default 16)")
      ->check(a3::rigs::positive());
  cmd->add_flag("-q,--quiet", args->quiet, "no progress or summary on stderr");
  cmd->callback([args] { command_exit_status() = run_score(*args); });
});

}  // namespace a3::rigs
