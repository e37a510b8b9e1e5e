// Scoring a written episode and printing a run's closing lines.
#include "rigs/core/run_summary.hpp"

#include <algorithm>
#include <string>

#include "common/json_text.hpp"
#include "eval/episode_reader.hpp"
#include "eval/episode_schema.hpp"
#include "eval/pillars.hpp"
#include "rigs/core/realtime_report.hpp"

namespace a3::rigs {
namespace {

std::string pace(const RunResult& r, const RunOptions& o) {
  if (o.runtime == Runtime::kVirtual) {
    return std::to_string(static_cast<int>(r.mission_time_s / std::max(r.wall_time_s, 1e-9))) + "x faster than real time";
  }
  return "achieved real-time factor " + std::to_string(r.achieved_real_time_factor);
}

void print_score(std::FILE* out, const nlohmann::json& episode) {
  const eval::JsonSchemaValidator validator(eval::episode_schema_json(), eval::kEpisodeSchemaName);
  const eval::ScoringProfile profile = eval::release_profile();
  eval::EpisodeReader reader(validator, profile);
  const eval::EpisodeCheck check = reader.check_text(common::dump_json_text(episode));
  if (check.status == eval::EpisodeStatus::kValid) {
    const eval::Pillars p = eval::score_pillars(check.facts, profile, profile.optimal_turns);
    std::fprintf(out, "α³ = %.4f  (TO %.3f  SP %.3f  TC %.3f  IQ %.3f  NR %.3f  CC %.3f)\n", p.alpha3, p.to, p.sp,
                 p.tc, p.iq, p.nr, p.cc);
    return;
  }
  std::fprintf(out, "the episode is not a valid α³-Bench episode (α³ = 0):\n");
  for (const auto& v : check.violations) std::fprintf(out, "  %s\n", eval::to_string(v).c_str());
}

// The file's path, or "not written (<file>: <reason>)" when it is among the lost outputs.
std::string written_or_why(const std::filesystem::path& file, const RunResult& r) {
  for (const std::string& what : r.outputs_lost) {
    if (what.rfind(file.string() + ": ", 0) == 0) return "not written (" + what + ")";
  }
  return file.string();
}

}  // namespace

void print_run_summary(std::FILE* out, const RunResult& r, const RunOptions& o) {
  const std::filesystem::path episode = o.out_dir / "episode.json";
  std::fprintf(out, "episode: %s\n", written_or_why(episode, r).c_str());
  if (o.write_lcm_log) std::fprintf(out, "lcm log: %s\n", written_or_why(o.out_dir / "episode.lcmlog", r).c_str());
  if (o.write_plot) {
    if (r.plot_problem.empty()) {
      std::fprintf(out, "plot:    %s\n", (o.out_dir / "trajectory.png").c_str());
    } else {
      std::fprintf(out, "plot:    not written (%s)\n", r.plot_problem.c_str());
    }
  }
  std::string status = r.status;
  if (!r.flight_status.empty() && r.flight_status != r.status) status += " (the flight ended " + r.flight_status + ")";
  std::fprintf(out, "status:  %s; mission %.1f s in %.1f s wall (%s)\n", status.c_str(), r.mission_time_s,
               r.wall_time_s, pace(r, o).c_str());
  if (r.episode.contains("_rig") && r.episode["_rig"].contains("realtime")) {
    std::fprintf(out, "real time: %s\n", realtime_summary(r.episode["_rig"]["realtime"]).c_str());
  }
  std::fprintf(out, "success: %s\n", r.episode.value("success", false) ? "true" : "false");
  print_score(out, r.episode);
  std::fflush(out);
}

}  // namespace a3::rigs
