// The scoring pipeline: walker → batches of files → threads (read, validate, extract, score) →
// in-order aggregation, with listing and aggregation overlapped with the checking.
#include "eval/corpus_scorer.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <set>
#include <utility>

#include "common/batch_pool.hpp"

namespace a3::eval {
namespace {

constexpr std::size_t kBatchFiles = 1024;

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// One pass over the corpus: per_file runs on the workers, in_order on the caller's thread.
struct Pass {
  const std::vector<std::filesystem::path>& roots;
  const JsonSchemaValidator& validator;
  const ScoringProfile& profile;
  std::size_t threads;
  std::uintmax_t max_file_bytes;
  CorpusOptions corpus;

  template <typename Result, typename PerFile, typename InOrder, typename AfterBatch>
  void run(PerFile per_file, InOrder in_order, AfterBatch after_batch,
           std::vector<std::string>* warnings, uint64_t* ignored_json) {
    common::BatchPool pool(threads);
    std::vector<std::unique_ptr<EpisodeReader>> readers;
    for (std::size_t w = 0; w < pool.workers(); ++w) {
      readers.push_back(std::make_unique<EpisodeReader>(validator, profile, max_file_bytes));
    }
    CorpusWalker walker(roots, corpus);
    // Two batches in flight: while the workers check batch `cur`, this thread lists the next
    // one; it then helps finish `cur`, starts `next`, and consumes `cur` while `next` runs.
    std::vector<EpisodeFile> files[2];
    std::vector<Result> results[2];
    auto list_batch = [&](int k) {
      files[k].clear();
      while (files[k].size() < kBatchFiles) {
        auto file = walker.next();
        if (!file) break;
        files[k].push_back(std::move(*file));
      }
      results[k].assign(files[k].size(), Result{});
    };
    auto start_batch = [&](int k) {
      pool.start(files[k].size(), [&, k](std::size_t i, std::size_t worker) {
        results[k][i] = per_file(*readers[worker], files[k][i]);
      });
    };
    int cur = 0;
    list_batch(cur);
    if (!files[cur].empty()) start_batch(cur);
    while (!files[cur].empty()) {
      const int next = 1 - cur;
      list_batch(next);
      pool.finish();
      if (!files[next].empty()) start_batch(next);
      for (std::size_t i = 0; i < files[cur].size(); ++i) in_order(files[cur][i], results[cur][i]);
      after_batch();
      cur = next;
    }
    if (warnings != nullptr) *warnings = walker.warnings();
    if (ignored_json != nullptr) *ignored_json = walker.ignored_json_files();
  }
};

struct ScoredFile {
  EpisodeCheck check;
  Pillars pillars;
};

}  // namespace

std::optional<double> median_turns(const std::vector<uint64_t>& count_by_turns) {
  uint64_t total = 0;
  for (uint64_t c : count_by_turns) total += c;
  if (total == 0) return std::nullopt;
  // Values at ranks (total-1)/2 and total/2 (0-based); their mean is the median.
  auto value_at = [&](uint64_t rank) {
    uint64_t seen = 0;
    for (std::size_t t = 0; t < count_by_turns.size(); ++t) {
      seen += count_by_turns[t];
      if (seen > rank) return static_cast<double>(t);
    }
    return static_cast<double>(count_by_turns.size() - 1);
  };
  return 0.5 * (value_at((total - 1) / 2) + value_at(total / 2));
}

ScoreResult score_corpus(const std::vector<std::filesystem::path>& roots,
                         const JsonSchemaValidator& validator, const ScoreOptions& options) {
  const auto start = Clock::now();
  ScoreResult result;
  const ScoringProfile& profile = options.profile;
  Pass pass{roots, validator, profile, options.threads, options.max_file_bytes, options.corpus};
  const int passes = profile.optimal_turns_from_median ? 2 : 1;
  uint64_t done = 0;
  auto report = [&](int pass_number) {
    if (options.on_progress) {
      options.on_progress({done, seconds_since(start), pass_number, passes});
    }
  };

  // Pass 1 (paper profile only): the median turn count of the valid successful episodes.
  result.optimal_turns = profile.optimal_turns;
  if (profile.optimal_turns_from_median) {
    std::vector<uint64_t> count_by_turns;
    pass.run<int>(
        [](EpisodeReader& reader, const EpisodeFile& file) {
          const EpisodeCheck check = reader.check_file(file.path);
          return check.status == EpisodeStatus::kValid && check.facts.success
                     ? static_cast<int>(check.facts.turns.size())
                     : -1;
        },
        [&](const EpisodeFile&, int turns) {
          ++done;
          if (turns < 0) return;
          if (count_by_turns.size() <= static_cast<std::size_t>(turns)) {
            count_by_turns.resize(static_cast<std::size_t>(turns) + 1, 0);
          }
          ++count_by_turns[static_cast<std::size_t>(turns)];
        },
        [&] { report(1); }, nullptr, nullptr);
    if (auto median = median_turns(count_by_turns)) {
      result.optimal_turns = *median;
    } else {
      result.warnings.push_back("no valid successful episode: T_opt falls back to " +
                                std::to_string(profile.optimal_turns));
    }
    done = 0;
  }

  // Scoring pass.
  const double optimal_turns = result.optimal_turns;
  std::map<std::pair<std::string, std::string>, ModelAccumulator> models;
  std::set<int> scenarios, episodes;
  std::vector<std::string> warnings;
  pass.run<ScoredFile>(
      [&](EpisodeReader& reader, const EpisodeFile& file) {
        ScoredFile scored{reader.check_file(file.path), {}};
        if (scored.check.status == EpisodeStatus::kValid) {
          scored.pillars = score_pillars(scored.check.facts, profile, optimal_turns);
        }
        return scored;
      },
      [&](const EpisodeFile& file, const ScoredFile& scored) {
        ++done;
        ++result.files;
        if (file.name) {
          scenarios.insert(file.name->scenario);
          episodes.insert(file.name->episode);
        }
        auto key = std::make_pair(file.model, file.domain);
        auto it = models.find(key);
        if (it == models.end()) it = models.emplace(key, ModelAccumulator(file.model, file.domain)).first;
        const bool valid = scored.check.status == EpisodeStatus::kValid;
        if (valid) {
          ++result.valid;
          it->second.add_valid(scored.check.facts, scored.pillars);
        } else {
          (scored.check.status == EpisodeStatus::kFailureStub ? result.failure_stubs
                                                              : result.invalid) += 1;
          it->second.add_failure(scored.check.status, scored.check.attempts_used);
        }
        if (options.on_episode) {
          options.on_episode({file, scored.check, valid ? &scored.pillars : nullptr});
        }
      },
      [&] { report(passes); }, &warnings, &result.ignored_json_files);
  result.warnings.insert(result.warnings.end(), warnings.begin(), warnings.end());

  result.scenarios_found = static_cast<int64_t>(scenarios.size());
  result.episodes_per_scenario = static_cast<int64_t>(episodes.size());
  result.budget = options.budget.value_or(result.scenarios_found * result.episodes_per_scenario);
  if (result.budget <= 0) result.budget = static_cast<int64_t>(result.files);
  for (const auto& [key, accumulator] : models) {
    result.models.push_back(accumulator.summarize(result.budget, profile.ci95_z));
  }
  std::stable_sort(result.models.begin(), result.models.end(),
                   [](const ModelSummary& a, const ModelSummary& b) {
                     if (a.alpha3_rel != b.alpha3_rel) return a.alpha3_rel > b.alpha3_rel;
                     return a.mean > b.mean;
                   });
  result.seconds = seconds_since(start);
  return result;
}

CheckSummary check_corpus(const std::vector<std::filesystem::path>& roots,
                      const JsonSchemaValidator& validator, std::size_t threads,
                      std::uintmax_t max_file_bytes,
                      const std::function<void(const EpisodeFile&, const EpisodeCheck&)>& on_file) {
  const ScoringProfile profile = release_profile();
  Pass pass{roots, validator, profile, threads, max_file_bytes, {}};
  CheckSummary summary;
  pass.run<EpisodeCheck>(
      [](EpisodeReader& reader, const EpisodeFile& file) { return reader.check_file(file.path); },
      [&](const EpisodeFile& file, const EpisodeCheck& check) {
        ++summary.files;
        on_file(file, check);
      },
      [] {}, &summary.warnings, nullptr);
  return summary;
}

}  // namespace a3::eval
