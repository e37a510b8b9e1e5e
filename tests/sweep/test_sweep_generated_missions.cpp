// gen:N in a sweep's --scenarios: expanded to N generated missions before the grid, so cell
// indices and shards are fixed, with distinct folder names that keep the knobs readable.
#include <gtest/gtest.h>

#include <set>

#include "rigs/sweep/sweep_grid.hpp"

namespace a3::rigs::sweep {
namespace {

using Strings = std::vector<std::string>;

TEST(SweepGeneratedMissions, GenCountExpandsToSeedsOneToNWithTheKnobs) {
  const SweepAxes axes = make_axes("survey-field,gen:3:hard+wind=2,gen:5-6", "scripted", "0", "URLLC", "1");
  EXPECT_EQ(axes.scenarios, (Strings{"survey-field", "gen:1:hard+wind=2", "gen:2:hard+wind=2", "gen:3:hard+wind=2",
                                     "gen:5", "gen:6"}));
}

TEST(SweepGeneratedMissions, CellsAndShardsAreTheSameOnEveryExpansion) {
  const auto a = expand_grid(make_axes("gen:4:easy", "scripted", "0", "URLLC", "1-2"));
  const auto b = expand_grid(make_axes("gen:4:easy", "scripted", "0", "URLLC", "1-2"));
  ASSERT_EQ(a.size(), 8u);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].scenario, b[i].scenario);
  EXPECT_EQ(a[2].scenario, "gen:2:easy");
  EXPECT_EQ(cells_of_shard(a, {1, 4}).front().scenario, "gen:1:easy");
}

TEST(SweepGeneratedMissions, FoldersAreDistinctAndKeepTheKnobs) {
  const auto cells = expand_grid(make_axes("gen:12:medium+nfz=2", "scripted", "0", "URLLC", "1"));
  std::set<std::string> folders;
  for (const auto& c : cells) folders.insert(folder_name(c.scenario));
  EXPECT_EQ(folders.size(), 12u);
  EXPECT_TRUE(folders.count("gen_12_medium+nfz=2"));
}

TEST(SweepGeneratedMissions, BadCountsAndOverlapsAreRefused) {
  EXPECT_THROW(make_axes("gen:x", "scripted", "0", "URLLC", "1"), std::invalid_argument);
  EXPECT_THROW(make_axes("gen:0", "scripted", "0", "URLLC", "1"), std::invalid_argument);
  EXPECT_THROW(make_axes("gen:3,gen:2-4", "scripted", "0", "URLLC", "1"), std::invalid_argument);
}

}  // namespace
}  // namespace a3::rigs::sweep
