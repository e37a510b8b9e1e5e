// `a3rig validate FILE|DIR...`: checks episode files against the episode schema and the
// semantic rules; per file, valid or the list of violations (file, JSON path, rule).
#include <CLI/CLI.hpp>

#include <nlohmann/json.hpp>

#include <iostream>
#include <string>
#include <vector>

#include "common/json_text.hpp"
#include "eval/corpus_scorer.hpp"
#include "eval/episode_schema.hpp"
#include "rigs/cli/command_registry.hpp"
#include "rigs/cli/flag_checks.hpp"

namespace a3::rigs {
namespace {

struct ValidateArgs {
  std::vector<std::string> paths;
  std::string format = "text";
  bool quiet = false;
  std::size_t threads = 0;
  double max_file_mb = 16.0;
};

int run_validate(const ValidateArgs& args) {
  const eval::JsonSchemaValidator validator(eval::episode_schema_json(), eval::kEpisodeSchemaName);
  const bool json = args.format == "json";
  uint64_t valid = 0, stubs = 0, invalid = 0;
  std::vector<std::filesystem::path> roots(args.paths.begin(), args.paths.end());
  const auto summary = eval::check_corpus(
      roots, validator, args.threads, static_cast<std::uintmax_t>(args.max_file_mb * 1048576.0),
      [&](const eval::EpisodeFile& file, const eval::EpisodeCheck& check) {
        switch (check.status) {
          case eval::EpisodeStatus::kValid: ++valid; break;
          case eval::EpisodeStatus::kFailureStub: ++stubs; break;
          case eval::EpisodeStatus::kInvalid: ++invalid; break;
        }
        if (json) {
          nlohmann::ordered_json row;
          row["file"] = file.path.string();
          row["status"] = eval::to_string(check.status);
          row["violations"] = nlohmann::ordered_json::array();
          for (const auto& v : check.violations) {
            row["violations"].push_back({{"path", v.json_path}, {"rule", v.rule}, {"message", v.message}});
          }
          std::cout << common::dump_json_text(row) << "\n";  // file names need not be UTF-8
          return;
        }
        if (check.status == eval::EpisodeStatus::kInvalid) {
          std::cout << "INVALID " << file.path.string() << "\n";
          for (const auto& v : check.violations) {
            std::cout << "  " << file.path.string() << ": " << eval::to_string(v) << "\n";
          }
        } else if (!args.quiet) {
          std::cout << "ok      " << file.path.string()
                    << (check.status == eval::EpisodeStatus::kFailureStub
                            ? " (failure stub)"
                            : " (" + std::to_string(check.facts.turns.size()) + " turns)")
                    << "\n";
        }
      });
  std::cout.flush();
  for (const auto& warning : summary.warnings) std::cerr << "a3rig validate: warning: " << warning << "\n";
  std::cerr << "a3rig validate: " << summary.files << " files: " << valid << " valid episodes, "
            << stubs << " failure stubs, " << invalid << " invalid\n";
  if (summary.files == 0) {
    std::cerr << "a3rig validate: no episode files found (folders are searched for "
                 "sc-XXXX-ep-YY.json; name files explicitly to check others)\n";
    return 2;
  }
  return invalid > 0 ? 1 : 0;
}

}  // namespace

A3_REGISTER_COMMAND("20-validate", [](CLI::App& app) {
  auto args = std::make_shared<ValidateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "validate",
      "Check episode files against the α³-Bench episode schema (JSON Schema 2020-12, via "
      "valijson) and the semantic rules (roles, alternation, 8..12 turns, each action answered "
      "by an observation). Exit status: 0 all valid, 1 some invalid, 2 nothing to check or a "
      "usage error.");
  cmd->add_option("paths", args->paths,
                  "episode files, or folders searched recursively for sc-XXXX-ep-YY.json")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_option("--format", args->format, "text (default) or json (one JSON object per line)")
      ->check(CLI::IsMember({"text", "json"}));
  cmd->add_flag("-q,--quiet", args->quiet, "print only the invalid files and the summary");
  cmd->add_option("--threads", args->threads, "worker threads (default: one per CPU)");
  cmd->add_option("--max-file-mb", args->max_file_mb,
                  "files larger than this are invalid (default 16)")
      ->check(a3::rigs::positive());
  cmd->callback([args] { command_exit_status() = run_validate(*args); });
});

}  // namespace a3::rigs
