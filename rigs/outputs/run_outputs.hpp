// What a run writes into its output folder, and the checks around it: the free space before
// take-off (an estimate from the scenario), and the run's status when an output was lost
// (`output_failed: <file>: <reason>`, exit status 8).
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rigs/outputs/episode_writer.hpp"
#include "rigs/run/run_options.hpp"
#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {

// Set to 1 to fly even when the output folder looks too small.
inline constexpr const char* kSkipSpaceCheckEnv = "A3_SKIP_SPACE_CHECK";

struct OutputSpaceEstimate {
  std::uint64_t episode_bytes = 0;
  std::uint64_t lcm_log_bytes = 0;  // 0 with --no-lcm-log
  std::uint64_t plot_bytes = 0;     // 0 with --no-plot
  std::uint64_t report_bytes = 0;   // 0 with --no-report
  std::uint64_t total() const { return episode_bytes + lcm_log_bytes + plot_bytes + report_bytes; }
};

// The bytes a run of `scenario` writes at most, from its mission time limit.
OutputSpaceEstimate estimate_output_bytes(const Scenario& scenario, const RunOptions& options);

// Thrown before take-off: "<folder>: too little free space for the run: <n> bytes needed
// (episode ..., LCM log ..., plot ...), <m> free; nothing flown (A3_SKIP_SPACE_CHECK=1 flies anyway)".
class OutputSpaceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws OutputSpaceError when the output folder's filesystem has less room than the estimate,
// unless $A3_SKIP_SPACE_CHECK is 1.
void check_output_space(const Scenario& scenario, const RunOptions& options);

// The run's status once its outputs are written: `output_failed: <first lost output>` when the
// episode itself was lost, or when the flight ended well (exit 0) and another output was lost;
// otherwise the flight's status, which keeps its meaning (the lost outputs are listed beside it).
std::string status_with_lost_outputs(const std::string& flight_status, const std::vector<std::string>& lost,
                                     bool episode_written);

struct WrittenOutputs {
  std::string status;                  // status_with_lost_outputs
  nlohmann::json episode;              // as written (or as it would have been)
  std::filesystem::path episode_path;  // empty: not written
  std::string plot_problem;            // "" when drawn (or not asked for)
  std::string report_problem;          // "" when report.html was written (or not asked for)
  std::vector<std::string> lost;       // "<file>: <reason>", in the order they failed
};

// Writes episode.json (with the lost outputs in _rig.outputs_lost and, when the status was
// changed, the flight's own in _rig.flight_status), then the plot and report.html. `lcm_log_failure` is the
// log's failure ("" when it was written). Never throws for a write that fails: it is lost.
WrittenOutputs write_run_outputs(const Scenario& scenario, const RunOptions& options, const RecordedEpisode& rec,
                                 RunFacts facts, const std::string& lcm_log_failure);

}  // namespace a3::rigs
