// Scheduling a sweep's cells on worker threads, each driving one cell at a time.
#include "rigs/sweep/sweep_runner.hpp"

#include <algorithm>
#include <chrono>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "rigs/sweep/cell_result.hpp"

namespace a3::rigs::sweep {

std::filesystem::path results_path(const std::filesystem::path& out_dir, const Shard& shard) {
  if (shard.count == 1) return out_dir / "results.csv";
  return out_dir / ("results.shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) + ".csv");
}

std::vector<int> missing_shards(const std::filesystem::path& out_dir, int count) {
  std::vector<int> missing;
  for (int i = 0; i < count; ++i) {
    if (!std::filesystem::exists(results_path(out_dir, Shard{i, count}))) missing.push_back(i);
  }
  return missing;
}

SweepRunSummary run_sweep(const std::vector<SweepCell>& grid, const SweepRunOptions& options, CellRunner& runner,
                          const ProgressCallback& progress, const std::atomic<bool>& stop) {
  if (options.jobs < 1) throw std::invalid_argument("--jobs " + std::to_string(options.jobs) + ": must be at least 1");
  const std::vector<SweepCell> cells = cells_of_shard(grid, options.shard);
  SweepRunSummary summary;
  summary.rows.resize(cells.size());
  summary.counts.total = cells.size();
  std::filesystem::create_directories(options.out_dir);

  // Which cells are complete already, so that the ETA counts only the work left.
  std::vector<char> complete(cells.size(), 0);
  for (std::size_t i = 0; i < cells.size() && !options.rerun_complete; ++i) {
    complete[i] = check_cell(cell_dir(options.out_dir, cells[i]), cells[i]).complete;
  }
  summary.counts.to_run = static_cast<std::size_t>(std::count(complete.begin(), complete.end(), 0));

  const auto start = std::chrono::steady_clock::now();
  std::mutex mutex;
  std::atomic<std::size_t> next{0};
  enum class Outcome { kRan, kSkipped, kFailed, kNotRun };
  auto record = [&](Outcome outcome) {
    std::lock_guard lock(mutex);
    if (outcome == Outcome::kRan) ++summary.counts.ran;
    if (outcome == Outcome::kSkipped) ++summary.counts.skipped;
    if (outcome == Outcome::kFailed) ++summary.counts.failed;
    if (outcome == Outcome::kNotRun) summary.stopped = true;
    summary.counts.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (progress && outcome != Outcome::kNotRun) progress(summary.counts);
  };

  auto worker = [&] {
    EpisodeScorer scorer;
    auto run_cell = [&](std::size_t i) {
      const SweepCell& cell = cells[i];
      const auto dir = cell_dir(options.out_dir, cell);
      const std::string relative = (cell_dir("", cell) / "episode.json").string();
      if (complete[i]) {
        const CellCheck done = check_cell(dir, cell);
        if (done.complete) {
          summary.rows[i] = scorer.row(cell, done.episode, relative);
          record(Outcome::kSkipped);
          return;
        }
      }
      if (stop.load()) {
        summary.rows[i] = row_without_episode(cell, "not_run: the sweep was stopped");
        record(Outcome::kNotRun);
        return;
      }
      CellRunOutcome outcome;
      CellCheck check;
      for (int attempt = 0;; ++attempt) {
        std::filesystem::remove(dir / "episode.json");  // a stale file must not pass for this run's
        outcome = runner.run(cell, dir, stop);
        check = check_cell(dir, cell);
        // A loaded host broke the real-time contract: the outcome is the host's, try again.
        if (check.complete || !check.realtime_violated || attempt >= options.realtime_retries || stop.load()) break;
        std::lock_guard lock(mutex);
        ++summary.realtime_reruns;
      }
      if (check.complete) {
        summary.rows[i] = scorer.row(cell, check.episode, relative);
        record(Outcome::kRan);
        return;
      }
      std::string why = outcome.ok ? check.why_not : outcome.problem + "; " + check.why_not;
      if (check.realtime_violated) why = check.why_not + " (after " + std::to_string(options.realtime_retries) + " reruns)";
      summary.rows[i] = row_without_episode(cell, (stop.load() ? "stopped: " : "failed: ") + why);
      record(Outcome::kFailed);
    };
    for (std::size_t i = next++; i < cells.size(); i = next++) {
      try {
        run_cell(i);
      } catch (const std::exception& e) {  // a cell's trouble (disk full, unreadable file) stays in its row
        summary.rows[i] = row_without_episode(cells[i], std::string("failed: ") + e.what());
        record(Outcome::kFailed);
      }
    }
  };
  const std::size_t thread_count = std::min<std::size_t>(static_cast<std::size_t>(options.jobs), std::max<std::size_t>(cells.size(), 1));
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < thread_count; ++t) threads.emplace_back(worker);
  for (auto& t : threads) t.join();

  summary.counts.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary.results_path = results_path(options.out_dir, options.shard);
  write_results_csv(summary.results_path, summary.rows);
  return summary;
}

}  // namespace a3::rigs::sweep
