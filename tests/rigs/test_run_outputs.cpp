// rigs/outputs/run_outputs: the run's status when an output is lost, the free-space estimate
// before take-off, and the refusal on a filesystem too small (a tmpfs; skipped when not root).
#include "rigs/generator/scenario_spec.hpp"
#include "rigs/outputs/run_outputs.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdio>

#include "rigs/outputs/run_summary.hpp"
#include "rigs/run/rig_runner.hpp"
#include "tests/rigs/rig_test_support.hpp"
#include "tests/tiny_tmpfs.hpp"

namespace a3::rigs {
namespace {

const std::string kLog = "out/episode.lcmlog: No space left on device";
const std::string kEpisode = "out/episode.json: No space left on device";

TEST(RunOutputs, AFlightThatEndedWellBecomesOutputFailedNamingTheFirstLostFile) {
  for (const char* ended : {"completed", "crashed", "time_limit", "dialogue_ended_airborne"}) {
    const std::string status = status_with_lost_outputs(ended, {kLog, "out/trajectory.png: x"}, true);
    EXPECT_EQ(status, "output_failed: " + kLog) << ended;
    EXPECT_EQ(run_exit_status(status), 8);
  }
  EXPECT_EQ(status_with_lost_outputs("completed", {}, true), "completed");
}

TEST(RunOutputs, AnotherEndingKeepsItsStatusWhenTheEpisodeWasWritten) {
  EXPECT_EQ(status_with_lost_outputs("interrupted", {kLog}, true), "interrupted");
  EXPECT_EQ(status_with_lost_outputs("node_failed: fc: gone", {kLog}, true), "node_failed: fc: gone");
}

TEST(RunOutputs, ALostEpisodeIsOutputFailedWhateverEndedTheFlight) {
  EXPECT_EQ(status_with_lost_outputs("interrupted", {kLog, kEpisode}, false), "output_failed: " + kEpisode);
  EXPECT_EQ(status_with_lost_outputs("completed", {kEpisode}, false), "output_failed: " + kEpisode);
}

TEST(RunOutputs, TheEstimateGrowsWithTheTimeLimitAndDropsWhatIsNotWritten) {
  RunOptions o = test::virtual_run("parcel-delivery", "estimate");
  o.write_lcm_log = true;
  o.write_plot = true;
  o.write_report = true;
  Scenario s = load_scenario_spec(o.scenario, o.shared_dir);
  const OutputSpaceEstimate all = estimate_output_bytes(s, o);
  EXPECT_GT(all.lcm_log_bytes, all.episode_bytes);
  EXPECT_GT(all.plot_bytes, 0u);
  EXPECT_GT(all.report_bytes, all.episode_bytes);
  s.mission.time_limit_s *= 2.0;
  EXPECT_GT(estimate_output_bytes(s, o).lcm_log_bytes, all.lcm_log_bytes);
  o.write_lcm_log = false;
  o.write_plot = false;
  o.write_report = false;
  const OutputSpaceEstimate episode_only = estimate_output_bytes(s, o);
  EXPECT_EQ(episode_only.lcm_log_bytes + episode_only.plot_bytes + episode_only.report_bytes, 0u);
  EXPECT_EQ(episode_only.total(), episode_only.episode_bytes);
}

// A real flight's files fit in the estimate for its scenario (the sizes are printed: they are the
// source of the constants in run_outputs.cpp).
class RunOutputsMeasured : public ::testing::TestWithParam<const char*> {};

TEST_P(RunOutputsMeasured, AFlightsFilesFitInTheEstimate) {
  RunOptions o = test::virtual_run(GetParam(), "measured");
  o.write_lcm_log = true;
  o.write_plot = true;
  o.write_report = true;
  const Scenario s = load_scenario_spec(o.scenario, o.shared_dir);
  const RunResult r = test::run(o);
  ASSERT_EQ(r.status, "completed");
  namespace fs = std::filesystem;
  const auto size = [&](const char* name) { return fs::file_size(o.out_dir / name); };
  const std::uint64_t plot = size("trajectory.png") + size("trajectory.tsv") + size("trajectory.gp");
  std::printf("%s: mission %.1f s: episode.json %ju B (%.0f B/s), episode.lcmlog %ju B (%.0f B/s), plot %ju B (png %ju)\n",
              GetParam(), r.mission_time_s, static_cast<std::uintmax_t>(size("episode.json")),
              size("episode.json") / r.mission_time_s, static_cast<std::uintmax_t>(size("episode.lcmlog")),
              size("episode.lcmlog") / r.mission_time_s, static_cast<std::uintmax_t>(plot),
              static_cast<std::uintmax_t>(size("trajectory.png")));
  const OutputSpaceEstimate e = estimate_output_bytes(s, o);
  EXPECT_LE(size("episode.json"), e.episode_bytes);
  EXPECT_LE(size("episode.lcmlog"), e.lcm_log_bytes);
  EXPECT_LE(plot, e.plot_bytes);
  EXPECT_LE(size("report.html"), e.report_bytes);
  fs::remove_all(o.out_dir);
}

INSTANTIATE_TEST_SUITE_P(BuiltIn, RunOutputsMeasured, ::testing::Values("parcel-delivery", "survey-field"));

TEST(RunOutputsFaults, ASmallFilesystemIsRefusedBeforeTakeOffUnlessSkipped) {
  test::TinyTmpfs disk(64 * 1024);
  if (!disk.skip_reason().empty()) GTEST_SKIP() << disk.skip_reason();
  RunOptions o = test::virtual_run("parcel-delivery", "space");
  o.out_dir = disk.path() / "run";
  o.write_lcm_log = true;
  const Scenario s = load_scenario_spec(o.scenario, o.shared_dir);
  try {
    check_output_space(s, o);
    FAIL() << "no OutputSpaceError";
  } catch (const OutputSpaceError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(o.out_dir.string() + ": too little free space for the run: " +
                             std::to_string(estimate_output_bytes(s, o).total()) + " bytes needed",
                         0),
              0u)
        << what;
    EXPECT_NE(what.find(", 65536 free; nothing flown"), std::string::npos) << what;
  }
  EXPECT_FALSE(std::filesystem::exists(o.out_dir));
  ::setenv(kSkipSpaceCheckEnv, "1", 1);
  EXPECT_NO_THROW(check_output_space(s, o));
  ::unsetenv(kSkipSpaceCheckEnv);
}

// Ctrl-C before the first half second, on a disk with room for the episode but not the log:
// the run keeps its status (interrupted, exit 3) and names the lost log beside it.
TEST(RunOutputsFaults, AnInterruptedRunWhoseLogFailedSaysBoth) {
  test::TinyTmpfs disk(24 * 1024);
  if (!disk.skip_reason().empty()) GTEST_SKIP() << disk.skip_reason();
  RunOptions o = test::virtual_run("parcel-delivery", "interrupted");
  o.out_dir = disk.path() / "run";
  o.write_lcm_log = true;
  ::setenv(kSkipSpaceCheckEnv, "1", 1);
  const std::atomic<bool> stop{true};
  const RunResult r = run_episode(load_scenario_spec(o.scenario, o.shared_dir), o, {}, &stop);
  ::unsetenv(kSkipSpaceCheckEnv);
  const std::string lost = (o.out_dir / "episode.lcmlog").string() + ": No space left on device";
  EXPECT_EQ(r.status, "interrupted");
  EXPECT_EQ(run_exit_status(r.status), 3);
  EXPECT_EQ(r.outputs_lost, std::vector<std::string>{lost});
  EXPECT_EQ(r.episode_path, o.out_dir / "episode.json");
  EXPECT_EQ(r.episode["_rig"]["status"], "interrupted");
  EXPECT_EQ(r.episode["_rig"]["outputs_lost"], nlohmann::json::array({lost}));
  EXPECT_FALSE(r.episode["_rig"].contains("flight_status"));
  EXPECT_FALSE(std::filesystem::exists(o.out_dir / "episode.lcmlog"));
  char* text = nullptr;
  std::size_t size = 0;
  std::FILE* out = ::open_memstream(&text, &size);
  print_run_summary(out, r, o);
  std::fclose(out);
  const std::string summary(text, size);
  std::free(text);
  EXPECT_NE(summary.find("lcm log: not written (" + lost + ")\n"), std::string::npos) << summary;
  EXPECT_NE(summary.find("status:  interrupted;"), std::string::npos) << summary;
}

}  // namespace
}  // namespace a3::rigs
