// Scores a corpus: walks the folders, checks and scores every episode file on a pool of
// threads, and aggregates per model (SPEC-alpha3.md §2–§3). Streams: memory holds one batch
// of files and the per-model sums, never the corpus. Results reach the caller in corpus order.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "eval/corpus.hpp"
#include "eval/episode_reader.hpp"
#include "eval/json_schema_validator.hpp"
#include "eval/model_summary.hpp"
#include "eval/pillars.hpp"
#include "eval/scoring_profile.hpp"

namespace a3::eval {

struct ScoredEpisode {
  const EpisodeFile& file;
  const EpisodeCheck& check;
  const Pillars* pillars;  // valid episodes only
};

struct ScoreProgress {
  uint64_t files_done = 0;
  double elapsed_s = 0.0;
  int pass = 1;      // the paper profile reads the corpus twice
  int passes = 1;
};

struct ScoreOptions {
  ScoringProfile profile = release_profile();
  std::optional<int64_t> budget;  // default: scenarios found × episodes per scenario
  std::size_t threads = 0;        // 0: one per hardware thread
  std::uintmax_t max_file_bytes = kDefaultMaxEpisodeFileBytes;
  CorpusOptions corpus;
  std::function<void(const ScoredEpisode&)> on_episode;  // in corpus order, on the caller's thread
  std::function<void(const ScoreProgress&)> on_progress;  // after each batch
};

struct ScoreResult {
  std::vector<ModelSummary> models;  // the leaderboard: best alpha3_rel first
  uint64_t files = 0, valid = 0, failure_stubs = 0, invalid = 0;
  int64_t scenarios_found = 0;
  int64_t episodes_per_scenario = 0;
  int64_t budget = 0;               // the budget used for every model
  double optimal_turns = 0.0;       // T_opt used
  double seconds = 0.0;
  uint64_t ignored_json_files = 0;
  std::vector<std::string> warnings;
};

// Throws std::invalid_argument for a root that does not exist.
ScoreResult score_corpus(const std::vector<std::filesystem::path>& roots,
                         const JsonSchemaValidator& validator, const ScoreOptions& options);

struct CheckSummary {
  uint64_t files = 0;
  std::vector<std::string> warnings;  // folders that could not be read
};

// Checks files (validation only, no scoring) with the same walking and threading; calls
// on_file in corpus order.
CheckSummary check_corpus(const std::vector<std::filesystem::path>& roots,
                      const JsonSchemaValidator& validator, std::size_t threads,
                      std::uintmax_t max_file_bytes,
                      const std::function<void(const EpisodeFile&, const EpisodeCheck&)>& on_file);

// The median of the turn counts in a histogram (count per T); nothing when it is empty.
std::optional<double> median_turns(const std::vector<uint64_t>& count_by_turns);

}  // namespace a3::eval
