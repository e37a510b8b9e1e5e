// The plan, the resume check, the workers and the atomic writes of `a3rig generate`.
#include "rigs/generate/generate_run.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "common/atomic_file.hpp"
#include "common/json_text.hpp"
#include "episode/episode.hpp"
#include "eval/episode_schema.hpp"
#include "eval/json_schema_validator.hpp"
#include "eval/json_shape.hpp"
#include "eval/scoring_profile.hpp"

namespace a3::rigs {
namespace {

namespace fs = std::filesystem;

struct Task {
  const GenerateScenario* scenario = nullptr;
  int64_t seed = 0;
  fs::path path;
};

// `_meta.seed` of an existing episode file, if it is an episode with one.
std::optional<int64_t> recorded_seed(const fs::path& path) {
  try {
    return episode::Episode::load(path).meta().seed;
  } catch (const common::InputError&) {
    return {};
  }
}

// Temporary files an interrupted run left behind: sc-XXXX-ep-YY.json.tmp-PID (common/atomic_file),
// or sc-XXXX-ep-YY.json.PID-N.tmp from earlier versions.
void remove_stale_temporaries(const fs::path& dir) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    const bool old_style = name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0;
    if (name.rfind("sc-", 0) == 0 && name.find(".json.") != std::string::npos &&
        (old_style || name.find(".json.tmp-") != std::string::npos)) {
      std::error_code ignored;
      fs::remove(entry.path(), ignored);
    }
  }
}

}  // namespace

std::string episode_file_name(int number, std::size_t index) {
  char name[40];
  std::snprintf(name, sizeof name, "sc-%04d-ep-%02zu.json", number, index);
  return name;
}

GenerateRunSummary run_generate(const GenerateRunOptions& options, const GenerateChatFactory& make_chat,
                                const std::function<void(const GenerateProgress&)>& on_episode,
                                const std::function<bool()>& stop_requested) {
  if (options.scenarios.empty()) throw std::invalid_argument("no scenario to generate episodes for");
  if (options.seeds.empty()) throw std::invalid_argument("--seeds: give at least one episode seed");
  if (options.seeds.size() > 100) throw std::invalid_argument("--seeds: at most 100 seeds (ep-00..ep-99)");
  if (std::set<int64_t>(options.seeds.begin(), options.seeds.end()).size() != options.seeds.size()) {
    throw std::invalid_argument("--seeds: a seed is given twice (each seed is one episode, ep-YY by position)");
  }
  if (options.jobs < 1) throw std::invalid_argument("--jobs " + std::to_string(options.jobs) + ": must be >= 1");
  if (options.output_dir.empty()) throw std::invalid_argument("no output folder");
  std::error_code ec;
  fs::create_directories(options.output_dir, ec);
  if (ec || !fs::is_directory(options.output_dir)) {
    throw std::invalid_argument("cannot make the output folder " + options.output_dir.string() +
                                (ec ? " (" + ec.message() + ")" : std::string(" (a file is in the way)")));
  }
  remove_stale_temporaries(options.output_dir);

  const eval::JsonSchemaValidator validator(eval::episode_schema_json(), eval::kEpisodeSchemaName);
  const eval::ScoringProfile profile = eval::release_profile();
  GenerateRunSummary summary;
  std::vector<Task> tasks;
  {
    eval::EpisodeReader reader(validator, profile);
    for (const auto& scenario : options.scenarios) {
      for (std::size_t i = 0; i < options.seeds.size(); ++i) {
        ++summary.planned;
        Task task{&scenario, options.seeds[i], options.output_dir / episode_file_name(scenario.number, i)};
        if (fs::exists(task.path)) {
          const eval::EpisodeCheck check = reader.check_file(task.path);
          if (check.status == eval::EpisodeStatus::kValid) {
            const auto seed = recorded_seed(task.path);
            if (seed && *seed != task.seed) {
              throw std::invalid_argument(task.path.string() + " is an episode of seed " + std::to_string(*seed) +
                                          ", but --seeds puts seed " + std::to_string(task.seed) + " at ep-" +
                                          task.path.filename().string().substr(11, 2) +
                                          ": resume with the seed list that wrote it, or use another --out");
            }
            ++summary.kept_valid;
            continue;
          }
          if (check.status == eval::EpisodeStatus::kFailureStub && !options.retry_failed) {
            ++summary.kept_stubs;
            continue;
          }
          if (check.status == eval::EpisodeStatus::kInvalid) ++summary.replaced_invalid;
        }
        tasks.push_back(std::move(task));
      }
    }
  }

  const auto t0 = std::chrono::steady_clock::now();
  std::atomic<std::size_t> next{0};
  std::atomic<bool> abort{false};
  std::mutex mutex;  // summary, progress
  std::size_t done = 0;
  auto worker = [&] {
    GenerateChat chat;
    eval::EpisodeReader reader(validator, profile);
    while (!abort.load()) {
      if (stop_requested && stop_requested()) {
        std::lock_guard<std::mutex> lock(mutex);
        summary.stopped = true;
        return;
      }
      const std::size_t index = next.fetch_add(1);
      if (index >= tasks.size()) return;
      const Task& task = tasks[index];
      try {
        if (!chat) chat = make_chat();
        const GeneratedEpisode episode = generate_episode(chat, reader, *task.scenario, task.seed, options.model_label);
        common::write_file_atomically(task.path, common::dump_json_text(episode.document));
        std::lock_guard<std::mutex> lock(mutex);
        ++done;
        (episode.generation_failed ? summary.generated_stubs : summary.generated_valid) += 1;
        summary.total_tokens += episode.usage.total_tokens;
        if (on_episode) {
          GenerateProgress p;
          p.file = task.path.string();
          p.outcome = episode.generation_failed ? GenerateProgress::Outcome::kFailureStub
                                                : GenerateProgress::Outcome::kValid;
          p.attempts_used = episode.attempts_used;
          p.gen_time_s = episode.gen_time_s;
          p.total_tokens = episode.usage.total_tokens;
          p.attempt_errors = episode.attempt_errors;
          p.done = done;
          p.to_do = tasks.size();
          p.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          p.eta_s = p.elapsed_s / static_cast<double>(done) * static_cast<double>(tasks.size() - done);
          on_episode(p);
        }
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(mutex);
        if (summary.stop_error.empty()) summary.stop_error = e.what();
        abort = true;
        return;
      }
    }
  };
  const int threads = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(options.jobs), tasks.size()));
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
  if (threads >= 1) worker();
  for (auto& t : pool) t.join();
  summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  summary.not_generated = tasks.size() - summary.generated_valid - summary.generated_stubs;
  return summary;
}

}  // namespace a3::rigs
