// episode/: an episode read once, its parts by name, and every problem named with file and path.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "common/json_file.hpp"
#include "episode/episode.hpp"

namespace a3::episode {
namespace {

namespace fs = std::filesystem;

const char* kEpisode = R"({
  "initial_state": {"uav": {"pose": {"x": 0, "y": 0, "z": 0}}},
  "dialogue": [
    {"turn": 1, "speaker": "agent", "text": "Arming.", "actions": [{"type": "mcp", "name": "arm", "args": {}}],
     "net": {"slice": "URLLC", "lat_ms": 5, "jitter_ms": 1, "loss_pct": 0, "throughput_mbps": 100, "edge_load": 0.2}},
    {"turn": 2, "speaker": "user", "text": "Go.",
     "net": {"slice": "eMBB", "lat_ms": 20, "jitter_ms": 3, "loss_pct": 1, "throughput_mbps": 300, "edge_load": 0.5}},
    {"turn": 3, "speaker": "agent", "text": "Done.", "actions": []}
  ],
  "success": true,
  "_meta": {"seed": 77, "gen_time_s": 12.5, "attempts_used": 2,
            "usage": {"prompt_tokens": 100, "completion_tokens": 50.4, "total_tokens": 150, "cost": 0.01}},
  "_rig": {"scenario": "nfz-detour", "status": "completed"}
})";

std::string error_of(std::string_view text) {
  try {
    Episode::parse(text, "ep.json");
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(Episode, TurnsAndTheirPartsByName) {
  const Episode e = Episode::parse(kEpisode, "ep.json");
  ASSERT_EQ(e.turn_count(), 3u);
  EXPECT_EQ(e.speaker(1), "user");
  EXPECT_EQ(e.turns_of("agent"), (std::vector<std::size_t>{0, 2}));
  EXPECT_EQ(e.actions(0).at(0).at("name"), "arm");
  EXPECT_TRUE(e.actions(2).empty());
  EXPECT_EQ(e.net(1).at("slice"), "eMBB");
  EXPECT_EQ(e.turn_where(2), "ep.json: /dialogue/2");
  ASSERT_NE(e.rig(), nullptr);
  EXPECT_EQ(e.rig()->at("scenario"), "nfz-detour");
  ASSERT_NE(e.initial_state(), nullptr);
}

TEST(Episode, MetaIsTyped) {
  const EpisodeMeta m = Episode::parse(kEpisode, "ep.json").meta();
  EXPECT_TRUE(m.present);
  EXPECT_FALSE(m.generation_failed);
  EXPECT_EQ(m.seed, 77);
  EXPECT_EQ(m.gen_time_s, 12.5);
  EXPECT_EQ(m.attempts_used, 2.0);
  EXPECT_EQ(m.usage_count("completion_tokens"), 50);
  EXPECT_EQ(m.usage_count("total_tokens"), 150);
  EXPECT_EQ(m.usage_count("reasoning_tokens"), 0);
  ASSERT_TRUE(m.usage.has_value());
  EXPECT_EQ(m.usage->at("cost"), 0.01);
  const EpisodeMeta none = Episode::parse(R"({"dialogue": []})", "x").meta();
  EXPECT_FALSE(none.present);
  EXPECT_FALSE(none.seed.has_value());
  EXPECT_FALSE(none.usage.has_value());
  const EpisodeMeta stub =
      Episode::parse(R"({"dialogue": [], "_meta": {"generation_failed": true, "error": "timeout"}})", "x").meta();
  EXPECT_TRUE(stub.generation_failed);
  EXPECT_EQ(stub.error, "timeout");
}

TEST(Episode, WithoutMetaKeepsTheRecordedKeyOrder) {
  const std::string text = Episode::parse(kEpisode, "ep.json").without_meta().dump();
  EXPECT_EQ(text.find("_meta"), std::string::npos);
  EXPECT_EQ(text.rfind("{\"initial_state\":", 0), 0u) << text.substr(0, 40);
  EXPECT_LT(text.find("\"dialogue\""), text.find("\"success\""));
  EXPECT_LT(text.find("\"success\""), text.find("\"_rig\""));
}

TEST(Episode, ProblemsAreNamedWithFileAndPath) {
  EXPECT_EQ(error_of("[]"), "ep.json: an episode is a JSON object, got array");
  EXPECT_EQ(error_of("{}"), "ep.json: /dialogue: missing");
  EXPECT_EQ(error_of(R"({"dialogue": {}})"), "ep.json: /dialogue: expected an array, got object");
  EXPECT_EQ(error_of(R"({"dialogue": [], "_meta": {"seed": "x"}})"), "(accepted)");  // read when asked
  EXPECT_NE(error_of(R"({"dialogue": [], "dialogue": []})").find("dialogue"), std::string::npos);
  EXPECT_NE(error_of("{\"dialogue\": [").find("ep.json"), std::string::npos);

  const Episode e = Episode::parse(R"({"dialogue": [7, {"turn": 2}, {"speaker": "agent", "actions": 1}],
                                       "_meta": {"seed": "x", "gen_time_s": "slow"}})", "ep.json");
  auto problem = [](auto&& read) {
    try {
      read();
    } catch (const common::InputError& x) {
      return std::string(x.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(problem([&] { e.speaker(0); }), "ep.json: /dialogue/0: a turn is an object, got number");
  EXPECT_EQ(problem([&] { e.speaker(1); }), "ep.json: /dialogue/1/speaker: missing");
  EXPECT_EQ(problem([&] { e.net(1); }), "ep.json: /dialogue/1/net: missing");
  EXPECT_EQ(problem([&] { e.actions(2); }), "ep.json: /dialogue/2/actions: expected an array, got number");
  EXPECT_EQ(problem([&] { e.meta(); }), "ep.json: /_meta/seed: expected a number, got string");
  EXPECT_EQ(problem([&] { Episode::parse(R"({"dialogue": [], "_meta": {"seed": 1e300}})", "ep.json").meta(); }),
            "ep.json: /_meta/seed: out of the 64-bit integer range");
  EXPECT_EQ(problem([&] { Episode::parse(R"({"dialogue": [], "_meta": 3})", "ep.json").meta(); }),
            "ep.json: /_meta: expected an object, got number");
}

TEST(Episode, FilesAreReadBoundedAndNamed) {
  const fs::path dir = fs::temp_directory_path() / ("a3_episode_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "ep.json") << kEpisode;
  EXPECT_EQ(Episode::load(dir / "ep.json").where(), (dir / "ep.json").string());
  EXPECT_EQ(Episode::load(dir / "ep.json").meta().seed, 77);
  try {
    Episode::load(dir / "missing.json");
    ADD_FAILURE() << "a missing file was read";
  } catch (const common::InputError& x) {
    EXPECT_NE(std::string(x.what()).find("missing.json: cannot read"), std::string::npos) << x.what();
  }
  fs::resize_file(dir / "ep.json", kMaxEpisodeBytes + 1);
  try {
    Episode::load(dir / "ep.json");
    ADD_FAILURE() << "a file over the size bound was read";
  } catch (const common::InputError& x) {
    EXPECT_NE(std::string(x.what()).find("larger than 16 MiB"), std::string::npos) << x.what();
  }
  fs::remove_all(dir);
}

// Every episode of the public α³-Bench release reads, with its turns' speakers and `_meta`.
TEST(Episode, EveryPublicEpisodeReads) {
  const char* shared = std::getenv("A3_SHARED_DIR");
  const fs::path root = fs::path(shared != nullptr ? shared : A3_SHARED_DIR_DEFAULT) / "alphabench";
  if (!fs::is_directory(root)) {
    GTEST_SKIP() << root << " not found: put the α³-Bench public release in ../shared/alphabench or set A3_SHARED_DIR";
  }
  int files = 0, stubs = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_regular_file() || name.rfind("sc-", 0) != 0 || entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    const Episode e = Episode::load(entry.path());
    const EpisodeMeta m = e.meta();
    ASSERT_TRUE(m.present);
    if (m.generation_failed) {
      ++stubs;
    } else {
      EXPECT_TRUE(m.seed.has_value());
      EXPECT_TRUE(m.gen_time_s.has_value());
      EXPECT_EQ(e.turns_of("agent").size() + e.turns_of("user").size(), e.turn_count());
    }
    ++files;
  }
  std::cout << files << " episodes read, " << stubs << " failure stubs\n";
  EXPECT_GE(files, 200);
}

}  // namespace
}  // namespace a3::episode
