// Nothing lost on a full disk (issue 14): `a3rig run` refuses to fly when the output folder is
// too small, and when a write fails during or after the flight the run says which file was lost
// (status output_failed, exit 8) and never leaves a file cut short or 0 bytes. The full disk is
// a tmpfs of a few pages; the tests skip, saying why, when they cannot mount one (not root).
// `a3rig score` creates a missing output folder, or says why it cannot.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

#include "common/png_output.hpp"
#include "tests/eval/episode_builder.hpp"
#include "tests/integration/run_command.hpp"
#include "tests/test_support.hpp"
#include "tests/tiny_tmpfs.hpp"

namespace a3 {
namespace {

namespace fs = std::filesystem;
using test::a3rig;
using test::quote;
using test::run_command;

constexpr std::uint64_t kPage = 4096;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::uint64_t pages(std::uint64_t bytes) { return (bytes + kPage - 1) / kPage * kPage; }

// A virtual-time flight of parcel-delivery (the shortest built-in mission) into `out`.
test::CommandResult fly(const fs::path& out, const std::string& flags, const std::string& env = "") {
  return run_command(env + " " + a3rig() + " run --scenario parcel-delivery --runtime virtual --seed 42 --quiet --out " +
                         quote(out.string()) + " " + flags,
                     true);
}

// Every file left in `dir`, with its size: no temporary file, no 0-byte file may remain.
std::string listing(const fs::path& dir) {
  std::string text;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    text += e.path().filename().string() + " " + (e.is_regular_file() ? std::to_string(e.file_size()) : "dir") + "\n";
  }
  return text;
}

void expect_no_partial_files(const fs::path& dir) {
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    EXPECT_EQ(name.find(".tmp-"), std::string::npos) << listing(dir);
    if (e.is_regular_file() && name != "gnuplot.log") {
      EXPECT_GT(e.file_size(), 0u) << listing(dir);
    }
  }
}

void expect_valid_episode(const fs::path& episode) {
  const auto r = run_command(a3rig() + " validate " + quote(episode.string()), true);
  EXPECT_EQ(r.exit_status, 0) << r.output;
}

// The sizes of a run's files, from a flight into an ordinary folder.
struct ReferenceSizes {
  std::uint64_t episode = 0, tsv = 0, gp = 0, png = 0;
};

const ReferenceSizes& reference_sizes() {
  static const ReferenceSizes sizes = [] {
    const test::TempDir dir("outputs-reference");
    const auto r = fly(dir.path(), "--no-lcm-log");
    EXPECT_EQ(r.exit_status, 0) << r.output;
    ReferenceSizes s;
    s.episode = fs::file_size(dir.path() / "episode.json");
    s.tsv = fs::file_size(dir.path() / "trajectory.tsv");
    s.gp = fs::file_size(dir.path() / "trajectory.gp");
    s.png = fs::file_size(dir.path() / "trajectory.png");
    return s;
  }();
  return sizes;
}

TEST(OutputsFullDisk, TooLittleFreeSpaceRefusesToFlyNamingTheFolderAndTheBytes) {
  test::TinyTmpfs disk(64 * 1024);
  if (!disk.skip_reason().empty()) GTEST_SKIP() << disk.skip_reason();
  const fs::path out = disk.path() / "run";
  const auto r = fly(out, "");
  EXPECT_EQ(r.exit_status, 2) << r.output;
  EXPECT_NE(r.output.find(out.string() + ": too little free space for the run: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" bytes needed ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("), 65536 free; nothing flown (A3_SKIP_SPACE_CHECK=1 flies anyway)"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out / "episode.json"));
  EXPECT_FALSE(fs::exists(out / "episode.lcmlog"));
}

TEST(OutputsFullDisk, ALogThatFillsTheDiskIsNamedAndTheEpisodeIsStillWritten) {
  const ReferenceSizes& ref = reference_sizes();
  // Room for the episode and the plot, not for the LCM log (megabytes).
  test::TinyTmpfs disk(pages(ref.episode) + pages(ref.tsv) + pages(ref.gp) + 2 * pages(ref.png) + 8 * kPage);
  if (!disk.skip_reason().empty()) GTEST_SKIP() << disk.skip_reason();
  const fs::path out = disk.path() / "run";
  const auto r = fly(out, "--no-report", "A3_SKIP_SPACE_CHECK=1");
  const std::string lost = (out / "episode.lcmlog").string() + ": No space left on device";
  EXPECT_EQ(r.exit_status, 8) << r.output;
  EXPECT_NE(r.output.find("status:  output_failed: " + lost + " (the flight ended completed)"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("lcm log: not written (" + lost + ")"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("episode: " + (out / "episode.json").string() + "\n"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "episode.lcmlog")) << listing(out);
  expect_no_partial_files(out);
  expect_valid_episode(out / "episode.json");
  const auto episode = nlohmann::json::parse(slurp(out / "episode.json"));
  EXPECT_EQ(episode["_rig"]["status"], "output_failed: " + lost);
  EXPECT_EQ(episode["_rig"]["flight_status"], "completed");
  EXPECT_EQ(episode["_rig"]["outputs_lost"], nlohmann::json::array({lost}));
  EXPECT_TRUE(episode["success"].get<bool>());
}

TEST(OutputsFullDisk, AnEpisodeThatCannotBeWrittenIsAbsentNotEmptyAndExits8) {
  test::TinyTmpfs disk(2 * kPage);
  if (!disk.skip_reason().empty()) GTEST_SKIP() << disk.skip_reason();
  const fs::path out = disk.path() / "run";
  const auto r = fly(out, "--no-lcm-log --no-plot", "A3_SKIP_SPACE_CHECK=1");
  const std::string lost = (out / "episode.json").string() + ": No space left on device";
  EXPECT_EQ(r.exit_status, 8) << r.output;
  EXPECT_NE(r.output.find("episode: not written (" + lost + ")"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("status:  output_failed: " + lost + " (the flight ended completed)"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out / "episode.json")) << listing(out);
  expect_no_partial_files(out);
}

TEST(OutputsFullDisk, APlotCutShortIsReportedNotWrittenAndRemoved) {
  const ReferenceSizes& ref = reference_sizes();
  // The episode, the plot's data and script fit; the PNG does not.
  test::TinyTmpfs disk(pages(ref.episode) + pages(ref.tsv) + pages(ref.gp) + pages(ref.png / 3));
  if (!disk.skip_reason().empty()) GTEST_SKIP() << disk.skip_reason();
  const fs::path out = disk.path() / "run";
  const auto r = fly(out, "--no-lcm-log --no-report", "A3_SKIP_SPACE_CHECK=1");
  const std::string png = (out / "trajectory.png").string();
  EXPECT_EQ(r.exit_status, 8) << r.output;
  EXPECT_NE(r.output.find("plot:    not written (" + png + ": "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("status:  output_failed: " + png + ": "), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "trajectory.png")) << listing(out);
  expect_no_partial_files(out);
  expect_valid_episode(out / "episode.json");
}

TEST(OutputsFullDisk, AReportThatDoesNotFitIsNamedAndTheEpisodeStays) {
  const ReferenceSizes& ref = reference_sizes();
  // The episode fits, twice (it is written again naming the lost report); report.html does not.
  test::TinyTmpfs disk(2 * pages(ref.episode) + 4 * kPage);
  if (!disk.skip_reason().empty()) GTEST_SKIP() << disk.skip_reason();
  const fs::path out = disk.path() / "run";
  const auto r = fly(out, "--no-lcm-log --no-plot", "A3_SKIP_SPACE_CHECK=1");
  const std::string lost = (out / "report.html").string() + ": No space left on device";
  EXPECT_EQ(r.exit_status, 8) << r.output;
  EXPECT_NE(r.output.find("report:  not written (" + lost + ")"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("status:  output_failed: " + lost + " (the flight ended completed)"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out / "report.html")) << listing(out);
  expect_no_partial_files(out);
  expect_valid_episode(out / "episode.json");
  const auto episode = nlohmann::json::parse(slurp(out / "episode.json"));
  EXPECT_EQ(episode["_rig"]["outputs_lost"], nlohmann::json::array({lost}));
}

TEST(OutputsFullDisk, LeaderboardFiguresThatDoNotFitAreNamedAndNotLeftHalfWritten) {
  const test::TempDir dir("outputs-plots");
  const auto corpus = dir.path() / "corpus" / "acme" / "agent" / "uav";
  test::write_json(corpus / "sc-0000-ep-00.json", test::make_episode());
  test::TinyTmpfs disk(6 * kPage);  // the data and script fit, not five PNGs
  if (!disk.skip_reason().empty()) GTEST_SKIP() << disk.skip_reason();
  const fs::path plots = disk.path() / "figures";
  const auto r = run_command(a3rig() + " score -q --plots " + quote(plots.string()) + " " +
                                 quote((dir.path() / "corpus").string()),
                             true);
  EXPECT_EQ(r.exit_status, 2) << r.output;
  EXPECT_NE(r.output.find("a3rig: error: " + plots.string() + "/"), std::string::npos) << r.output;
  for (const auto& e : fs::directory_iterator(plots)) {
    const std::string name = e.path().filename().string();
    EXPECT_EQ(name.find(".tmp-"), std::string::npos) << listing(plots);
    if (e.path().extension() == ".png") {
      EXPECT_TRUE(common::png_is_complete(e.path())) << name;
    }
  }
}

TEST(OutputsFolders, ScoreCreatesAMissingPerEpisodeFolder) {
  const test::TempDir dir("outputs-score");
  const auto corpus = dir.path() / "corpus" / "acme" / "agent" / "uav";
  test::write_json(corpus / "sc-0000-ep-00.json", test::make_episode());
  const fs::path csv = dir.path() / "missing" / "dir" / "x.csv";
  const auto r = run_command(a3rig() + " score -q --per-episode " + quote(csv.string()) + " -o " +
                                 quote((dir.path() / "also" / "missing" / "board.txt").string()) + " " +
                                 quote((dir.path() / "corpus").string()),
                             true);
  EXPECT_EQ(r.exit_status, 0) << r.output;
  EXPECT_NE(slurp(csv).find("sc-0000-ep-00.json"), std::string::npos) << slurp(csv);
  EXPECT_NE(slurp(dir.path() / "also" / "missing" / "board.txt").find("acme/agent"), std::string::npos);
}

TEST(OutputsFolders, ScoreNamesWhyItCannotCreateTheFolder) {
  const test::TempDir dir("outputs-score-file");
  const auto corpus = dir.path() / "corpus" / "acme" / "agent" / "uav";
  test::write_json(corpus / "sc-0000-ep-00.json", test::make_episode());
  test::write_text(dir.path() / "plain", "a file, not a folder");
  const auto r = run_command(a3rig() + " score -q --per-episode " + quote((dir.path() / "plain" / "x.csv").string()) +
                                 " " + quote((dir.path() / "corpus").string()),
                             true);
  EXPECT_EQ(r.exit_status, 2) << r.output;
  EXPECT_NE(r.output.find((dir.path() / "plain").string() + ": cannot create the folder: Not a directory"),
            std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace a3
