// The free-space check before take-off, and writing a run's outputs so that a failed write is
// named in the run's status instead of being lost silently.
#include "rigs/outputs/run_outputs.hpp"

#include <cmath>
#include <cstdlib>
#include <string>

#include "common/atomic_file.hpp"
#include "common/json_file.hpp"
#include "rigs/report/episode_report.hpp"

namespace a3::rigs {
namespace {

// Measured 2026-11-25 (tests/rigs/test_run_outputs.cpp, RunOutputsMeasured, --runtime virtual,
// seed 42): survey-field 253.0 s of mission wrote episode.lcmlog 23 497 704 B (92 876 B per
// simulated second), episode.json 66 955 B, plot 72 903 B (PNG 61 064 B); parcel-delivery
// 233.0 s: 21 637 921 B (92 867 B/s), 62 889 B, 77 735 B (PNG 66 778 B). The log grows with
// the rig's fixed message rates, whatever the mission (the two agree to 0.01 %); rounded up.
constexpr double kLcmLogBytesPerSimulatedSecond = 100'000.0;
// The episode: the 1 Hz trajectory and the turns grow with the mission (~270 B/s measured).
constexpr double kEpisodeBytesPerSimulatedSecond = 400.0;
constexpr double kEpisodeFixedBytes = 64.0 * 1024.0;
// trajectory.png (~65 KB, whatever the mission) + .tsv (~40 B/s) + .gp.
constexpr double kPlotFixedBytes = 128.0 * 1024.0;
constexpr double kPlotBytesPerSimulatedSecond = 64.0;
// report.html: the episode's JSON again, d3 (~150 KB) and the page's own script and style.
constexpr double kReportFixedBytes = 256.0 * 1024.0;

std::string mib(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / 1048576.0);
  return text;
}

bool space_check_skipped() {
  const char* skip = std::getenv(kSkipSpaceCheckEnv);
  return skip != nullptr && std::string(skip) == "1";
}

// The episode as written: the lost outputs beside the status, and the flight's own status when
// the run's status differs from it.
void note_lost_outputs(nlohmann::json& episode, const std::string& status, const std::string& flight_status,
                       const std::vector<std::string>& lost) {
  episode["_rig"]["status"] = status;
  if (status != flight_status) episode["_rig"]["flight_status"] = flight_status;
  if (!lost.empty()) episode["_rig"]["outputs_lost"] = lost;
}

// When this fails too, the episode written before stays (whole, without the plot's or the
// report's failure).
void rewrite_episode_naming_lost_outputs(const RunOptions& o, WrittenOutputs& out, const std::string& flight_status) {
  out.status = status_with_lost_outputs(flight_status, out.lost, true);
  note_lost_outputs(out.episode, out.status, flight_status, out.lost);
  try {
    write_episode(o.out_dir, out.episode);
  } catch (const common::OutputError&) {
  }
}

// report.html beside the episode: a write that fails is a lost output; a report that cannot be
// made (d3 not installed) is a problem the run prints, as a plot without gnuplot is.
void write_report(const Scenario& s, const RunOptions& o, WrittenOutputs& out, const std::string& flight_status) {
  try {
    write_episode_report(o.out_dir / "report.html", out.episode, s, (o.out_dir / "episode.json").string());
  } catch (const common::OutputError& e) {
    out.lost.push_back(e.what());
    out.report_problem = e.what();
    if (!out.episode_path.empty()) rewrite_episode_naming_lost_outputs(o, out, flight_status);
  } catch (const common::InputError& e) {
    out.report_problem = e.what();
  }
}

}  // namespace

OutputSpaceEstimate estimate_output_bytes(const Scenario& s, const RunOptions& o) {
  const double seconds = s.mission.time_limit_s + 1.0;  // a run ends at its time limit (checked every 0.5 s)
  OutputSpaceEstimate e;
  e.episode_bytes = static_cast<std::uint64_t>(std::ceil(kEpisodeFixedBytes + kEpisodeBytesPerSimulatedSecond * seconds));
  if (o.write_lcm_log) e.lcm_log_bytes = static_cast<std::uint64_t>(std::ceil(kLcmLogBytesPerSimulatedSecond * seconds));
  if (o.write_plot) e.plot_bytes = static_cast<std::uint64_t>(std::ceil(kPlotFixedBytes + kPlotBytesPerSimulatedSecond * seconds));
  if (o.write_report) e.report_bytes = static_cast<std::uint64_t>(std::ceil(kReportFixedBytes + e.episode_bytes));
  return e;
}

void check_output_space(const Scenario& s, const RunOptions& o) {
  if (space_check_skipped()) return;
  const OutputSpaceEstimate need = estimate_output_bytes(s, o);
  const std::uint64_t free = common::free_bytes_at(o.out_dir);
  if (free >= need.total()) return;
  throw OutputSpaceError(o.out_dir.string() + ": too little free space for the run: " + std::to_string(need.total()) +
                         " bytes needed (" + mib(need.total()) + ": episode " + std::to_string(need.episode_bytes) +
                         ", LCM log " + std::to_string(need.lcm_log_bytes) + ", plot " + std::to_string(need.plot_bytes) +
                         ", report " + std::to_string(need.report_bytes) + "), " + std::to_string(free) + " free; nothing flown (" + kSkipSpaceCheckEnv +
                         "=1 flies anyway)");
}

std::string status_with_lost_outputs(const std::string& flight_status, const std::vector<std::string>& lost,
                                     bool episode_written) {
  if (!episode_written) {
    for (const std::string& what : lost) {
      if (what.find("episode.json: ") != std::string::npos) return "output_failed: " + what;
    }
  }
  if (lost.empty() || flight_status.rfind("output_failed", 0) == 0) return flight_status;
  const bool flight_ended_well = flight_status == "completed" || flight_status == "crashed" ||
                                 flight_status == "time_limit" || flight_status == "dialogue_ended_airborne";
  return flight_ended_well ? "output_failed: " + lost.front() : flight_status;
}

WrittenOutputs write_run_outputs(const Scenario& s, const RunOptions& o, const RecordedEpisode& rec, RunFacts facts,
                                 const std::string& lcm_log_failure) {
  WrittenOutputs out;
  if (!lcm_log_failure.empty()) out.lost.push_back(lcm_log_failure);
  const std::string flight_status = facts.status;
  out.status = status_with_lost_outputs(flight_status, out.lost, true);
  facts.status = out.status;
  out.episode = build_episode(s, o, rec, facts);
  note_lost_outputs(out.episode, out.status, flight_status, out.lost);
  try {
    write_episode(o.out_dir, out.episode);
    out.episode_path = o.out_dir / "episode.json";
  } catch (const common::OutputError& e) {
    out.lost.push_back(e.what());
  }
  if (o.write_plot) {
    try {
      out.plot_problem = write_trajectory_plot(o.out_dir, s, rec);
    } catch (const common::OutputError& e) {
      out.lost.push_back(e.what());
      out.plot_problem = e.what();
      if (!out.episode_path.empty()) rewrite_episode_naming_lost_outputs(o, out, flight_status);
    }
  }
  if (o.write_report) write_report(s, o, out, flight_status);
  out.status = status_with_lost_outputs(flight_status, out.lost, !out.episode_path.empty());
  out.episode["_rig"]["status"] = out.status;
  return out;
}

}  // namespace a3::rigs
