// Running one sweep cell: an interface, so the sweep's scheduling, resume and shards are tested
// without flying episodes, and its real implementation, a child process `a3rig run ...` per
// cell (a crash stays in its cell; in real time each run takes an LCM port of its own).
#pragma once

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

#include "rigs/sweep/sweep_grid.hpp"

namespace a3::rigs::sweep {

struct CellRunOutcome {
  bool ok = false;        // the runner saw nothing wrong (the episode is checked separately)
  std::string problem;    // when not ok: exit status, signal or timeout, and where the log is
};

class CellRunner {
 public:
  virtual ~CellRunner() = default;
  // Runs the cell, writing dir/episode.json. Called from several threads at once. `stop`: set
  // when the sweep is asked to stop; the run should end early (its episode written).
  virtual CellRunOutcome run(const SweepCell& cell, const std::filesystem::path& dir,
                             const std::atomic<bool>& stop) = 0;
};

struct ChildProcessOptions {
  std::filesystem::path a3rig_exe;  // the a3rig program
  std::string runtime = "virtual";   // virtual | real
  double real_time_factor = 1.0;     // real time only
  double cell_timeout_s = 900.0;     // wall seconds before the child is killed; 0: none
  std::vector<std::string> extra_run_args;  // appended to `a3rig run` (e.g. --llm-model M)
};

class ChildProcessCellRunner final : public CellRunner {
 public:
  explicit ChildProcessCellRunner(ChildProcessOptions options);
  CellRunOutcome run(const SweepCell& cell, const std::filesystem::path& dir, const std::atomic<bool>& stop) override;
  // The command line of a cell (for --dry-run and the cell's run.log).
  std::vector<std::string> command(const SweepCell& cell, const std::filesystem::path& dir) const;

 private:
  ChildProcessOptions options_;
};

}  // namespace a3::rigs::sweep
