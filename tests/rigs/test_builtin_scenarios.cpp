// Every built-in scenario, flown by the scripted agent in virtual time, completes: the vehicle
// lands, the objectives are met, the episode is a valid α³-Bench episode that `a3rig score`
// reads, and α³ ≥ 0.9.
#include <gtest/gtest.h>

#include <set>

#include "eval/corpus_scorer.hpp"
#include "rigs/scenario/scenario.hpp"
#include "tests/rigs/rig_test_support.hpp"

namespace a3::rigs {
namespace {

class BuiltinScenario : public ::testing::TestWithParam<std::string> {};

TEST_P(BuiltinScenario, ScriptedAgentCompletesItInVirtualTime) {
  RunOptions o = a3::test::virtual_run(GetParam(), GetParam());
  const RunResult r = a3::test::run(o);
  const nlohmann::json& e = r.episode;
  EXPECT_EQ(r.status, "completed") << GetParam();
  EXPECT_TRUE(e.value("success", false)) << e["_rig"]["objectives"].dump();
  const a3::test::Scored s = a3::test::score(e);
  ASSERT_TRUE(s.valid) << s.problems;
  EXPECT_GE(s.pillars.alpha3, 0.9) << "TO " << s.pillars.to << " SP " << s.pillars.sp << " TC " << s.pillars.tc
                                   << " IQ " << s.pillars.iq << " NR " << s.pillars.nr << " CC " << s.pillars.cc;
  const auto& turns = e["dialogue"];
  EXPECT_GE(turns.size(), 8u);
  EXPECT_LE(turns.size(), 12u);
  // The vehicle really flew and is down, disarmed, near home.
  EXPECT_GT(e["_rig"]["trajectory"]["max_altitude_m"].get<double>(), 10.0);
  EXPECT_NEAR(e["final_state"]["uav"]["pose"]["z"].get<double>(), 0.0, 0.05);
  EXPECT_FALSE(e["_rig"]["trajectory"]["crashed"].get<bool>());
  // It scores as a corpus would: write it where `a3rig score` looks.
  const auto dir = o.out_dir / "runs" / "a3rig" / "scripted" / "uav";
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(r.episode_path, dir / "sc-0000-ep-00.json", std::filesystem::copy_options::overwrite_existing);
  const eval::JsonSchemaValidator validator(eval::episode_schema_json(), eval::kEpisodeSchemaName);
  const eval::ScoreResult scored = eval::score_corpus({o.out_dir / "runs"}, validator, eval::ScoreOptions{});
  ASSERT_EQ(scored.models.size(), 1u);
  EXPECT_EQ(scored.valid, 1u);
  EXPECT_NEAR(scored.models[0].mean, s.pillars.alpha3, 1e-12);
  std::filesystem::remove_all(o.out_dir);
}

INSTANTIATE_TEST_SUITE_P(All, BuiltinScenario, ::testing::ValuesIn(builtin_scenario_names()),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

TEST(BuiltinScenarios, AtLeastSixCoveringTheMissionKinds) {
  std::set<std::string> kinds;
  bool degradation = false, nfz = false, traffic = false;
  for (const auto& name : builtin_scenario_names()) {
    const Scenario s = load_scenario(name, ".");
    for (const auto& o : s.mission.objectives) kinds.insert(agent::to_string(o.type));
    degradation |= !s.network.degradations.empty();
    nfz |= !s.airspace.no_fly_zones.empty();
    traffic |= !s.airspace.traffic.empty();
  }
  EXPECT_GE(builtin_scenario_names().size(), 6u);
  for (const char* k : {"survey", "image_point", "delivery", "thermal_search", "return_and_land"}) {
    EXPECT_TRUE(kinds.count(k)) << k;
  }
  EXPECT_TRUE(degradation);
  EXPECT_TRUE(nfz);
  EXPECT_TRUE(traffic);
}

}  // namespace
}  // namespace a3::rigs
