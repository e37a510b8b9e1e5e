// The sweep grid: comma lists (with two-parameter think-time specs), seeds and ranges, checked
// axes, the expansion order, shards that partition the grid, and cell folders.
#include <gtest/gtest.h>

#include <set>

#include "rigs/sweep/sweep_grid.hpp"

namespace a3::rigs::sweep {
namespace {

using Strings = std::vector<std::string>;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SweepGrid, ThinkTimeListsKeepTwoParameterSpecsWhole) {
  EXPECT_EQ(split_think_times("0, uniform:1,4,60,normal:3,1,lognormal:3,0.5,model:ChatGPT-4o,exp:2", "--think-times"),
            (Strings{"0", "uniform:1,4", "60", "normal:3,1", "lognormal:3,0.5", "model:ChatGPT-4o", "exp:2"}));
  EXPECT_EQ(split_think_times("uniform:1,4", "--think-times"), Strings{"uniform:1,4"});
}

TEST(SweepGrid, BadThinkTimesNameTheFlagAndTheSpec) {
  const std::string unknown_model = error_of([] { split_think_times("0,model:gpt-9", "--think-times"); });
  EXPECT_NE(unknown_model.find("--think-times"), std::string::npos) << unknown_model;
  EXPECT_NE(unknown_model.find("model:gpt-9"), std::string::npos) << unknown_model;
  EXPECT_NE(error_of([] { split_think_times("0,uniform:1", "--think-times"); }).find("second parameter"),
            std::string::npos);
  EXPECT_NE(error_of([] { split_think_times("0,,5", "--think-times"); }).find("empty item"), std::string::npos);
  EXPECT_NE(error_of([] { split_think_times("-3", "--think-times"); }).find("-3"), std::string::npos);
  EXPECT_NE(error_of([] { split_think_times("5,fixed:5,5", "--think-times"); }).find("listed twice"), std::string::npos);
}

TEST(SweepGrid, SeedsTakeListsAndRanges) {
  EXPECT_EQ(parse_seeds("1-3,10, 12", "--seeds"), (std::vector<uint64_t>{1, 2, 3, 10, 12}));
  EXPECT_EQ(parse_seeds("7", "--seeds"), (std::vector<uint64_t>{7}));
  EXPECT_NE(error_of([] { parse_seeds("5-2", "--seeds"); }).find("ends before it starts"), std::string::npos);
  EXPECT_NE(error_of([] { parse_seeds("1,x", "--seeds"); }).find("'x'"), std::string::npos);
  EXPECT_NE(error_of([] { parse_seeds("1-3,2", "--seeds"); }).find("listed twice"), std::string::npos);
}

TEST(SweepGrid, AxesRejectUnknownSlicesAndAgents) {
  EXPECT_NE(error_of([] { make_axes("survey-field", "scripted", "0", "eMBB,6G", "1"); }).find("'6G'"), std::string::npos);
  EXPECT_NE(error_of([] { make_axes("survey-field", "robot", "0", "eMBB", "1"); }).find("'robot'"), std::string::npos);
  // Two items that would share a folder.
  EXPECT_NE(error_of([] { make_axes("a:b,a/b", "scripted", "0", "eMBB", "1"); }).find("share the folder"),
            std::string::npos);
  EXPECT_NO_THROW(make_axes("survey-field", "scripted,replay:x.json,llm", "0", "eMBB,URLLC,mMTC", "1"));
}

TEST(SweepGrid, ExpansionIsTheFullProductWithSeedsInnermost) {
  const SweepAxes axes = make_axes("survey-field,traffic-conflict", "scripted", "0,model:ChatGPT-4o,60",
                                   "eMBB,URLLC,mMTC", "1,2");
  const auto cells = expand_grid(axes);
  ASSERT_EQ(cells.size(), 2u * 1 * 3 * 3 * 2);
  for (std::size_t i = 0; i < cells.size(); ++i) EXPECT_EQ(cells[i].index, i);
  EXPECT_EQ(cells[0].seed, 1u);
  EXPECT_EQ(cells[1].seed, 2u);
  EXPECT_EQ(cells[1].slice, "eMBB");
  EXPECT_EQ(cells[2].slice, "URLLC");
  EXPECT_EQ(cells[6].think_time, "model:ChatGPT-4o");
  // ChatGPT-4o's 10.58 s per episode spread over 6 agent turns.
  EXPECT_NEAR(cells[6].think_time_mean_s, 10.58 / 6.0, 1e-9);
  EXPECT_EQ(cells[18].scenario, "traffic-conflict");
  std::set<std::tuple<std::string, std::string, std::string, uint64_t>> distinct;
  for (const auto& c : cells) distinct.insert({c.scenario, c.think_time, c.slice, c.seed});
  EXPECT_EQ(distinct.size(), cells.size());
}

TEST(SweepGrid, ShardsPartitionTheGrid) {
  const auto cells = expand_grid(make_axes("survey-field,nfz-detour", "scripted", "0,5,10", "eMBB,URLLC", "1-4"));
  for (int n = 1; n <= 7; ++n) {
    std::vector<int> seen(cells.size(), 0);
    std::size_t total = 0;
    for (int i = 0; i < n; ++i) {
      const auto shard = cells_of_shard(cells, parse_shard(std::to_string(i) + "/" + std::to_string(n)));
      total += shard.size();
      for (const auto& c : shard) ++seen[c.index];
      // Balanced: shard sizes differ by one at most.
      EXPECT_LE(shard.size(), (cells.size() + n - 1) / n);
      EXPECT_GE(shard.size(), cells.size() / n);
    }
    EXPECT_EQ(total, cells.size()) << n << " shards";
    for (std::size_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], 1) << "cell " << k << " with " << n << " shards";
  }
}

TEST(SweepGrid, ShardSpecsAreChecked) {
  EXPECT_EQ(parse_shard("2/5").index, 2);
  EXPECT_EQ(parse_shard("2/5").count, 5);
  for (const char* bad : {"5/5", "1", "a/3", "-1/3", "0/0", "1/2/3", ""}) {
    EXPECT_NE(error_of([&] { parse_shard(bad); }).find("--shard"), std::string::npos) << bad;
  }
}

TEST(SweepGrid, CellFoldersAreSafeNames) {
  SweepCell cell{0, "/tmp/my scenario.json", "replay:alphabench:a/b.json", "uniform:1,4", 2.5, "URLLC", 3};
  EXPECT_EQ(cell_dir("out", cell), std::filesystem::path("out/cells/_tmp_my_scenario.json/replay_alphabench_a_b.json/"
                                                         "think-uniform_1,4/URLLC/seed-3"));
  EXPECT_EQ(folder_name(".."), "___");
  EXPECT_EQ(folder_name("model:GPT-5.1-Chat"), "model_GPT-5.1-Chat");
}

}  // namespace
}  // namespace a3::rigs::sweep
