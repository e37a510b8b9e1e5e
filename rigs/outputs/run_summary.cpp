// Scoring a written episode and printing a run's closing lines.
#include "rigs/outputs/run_summary.hpp"

#include <algorithm>
#include <string>

#include "rigs/outputs/episode_score.hpp"
#include "rigs/run/realtime_report.hpp"

namespace a3::rigs {
namespace {

std::string pace(const RunResult& r, const RunOptions& o) {
  if (o.runtime == Runtime::kVirtual) {
    return std::to_string(static_cast<int>(r.mission_time_s / std::max(r.wall_time_s, 1e-9))) + "x faster than real time";
  }
  return "achieved real-time factor " + std::to_string(r.achieved_real_time_factor);
}

void print_score(std::FILE* out, const nlohmann::json& episode) {
  const EpisodeScore score = score_episode(episode);
  if (score.valid) {
    const eval::Pillars& p = score.pillars;
    std::fprintf(out, "α³ = %.4f  (TO %.3f  SP %.3f  TC %.3f  IQ %.3f  NR %.3f  CC %.3f)\n", p.alpha3, p.to, p.sp,
                 p.tc, p.iq, p.nr, p.cc);
    return;
  }
  std::fprintf(out, "the episode is not a valid α³-Bench episode (α³ = 0):\n");
  for (const auto& v : score.violations) std::fprintf(out, "  %s\n", v.c_str());
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
  if (o.write_report) {  // last, so that the page to open is the last line
    if (r.report_problem.empty()) {
      std::fprintf(out, "report:  %s (open it in a browser: map, timelines, score, dialogue)\n",
                   (o.out_dir / "report.html").c_str());
    } else {
      std::fprintf(out, "report:  not written (%s)\n", r.report_problem.c_str());
    }
  }
  std::fflush(out);
}

}  // namespace a3::rigs
