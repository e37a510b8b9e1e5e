// Episode files in, verdicts out: valid episodes, failure stubs, and every kind of bad input
// (syntax, truncation, types, size, encoding, semantic rules), each reported with where and why.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "eval/episode_reader.hpp"
#include "eval/episode_schema.hpp"
#include "tests/eval/episode_builder.hpp"

namespace a3::eval {
namespace {

using nlohmann::json;

class EpisodeReaderTest : public ::testing::Test {
 protected:
  EpisodeCheck check(const json& episode) { return reader_.check_text(episode.dump()); }
  EpisodeCheck check(const std::string& text) { return reader_.check_text(text); }

  static bool has(const EpisodeCheck& c, const std::string& path, const std::string& rule) {
    return std::any_of(c.violations.begin(), c.violations.end(), [&](const Violation& v) {
      return v.json_path == path && v.rule == rule;
    });
  }
  static std::string all(const EpisodeCheck& c) {
    std::string s;
    for (const auto& v : c.violations) s += to_string(v) + "\n";
    return s;
  }

  const ScoringProfile profile_ = release_profile();
  const JsonSchemaValidator validator_{episode_schema_json(), kEpisodeSchemaName};
  EpisodeReader reader_{validator_, profile_, 1u << 20};
};

TEST_F(EpisodeReaderTest, AValidEpisodeYieldsItsFacts) {
  json e = a3::test::make_episode();
  e["dialogue"][2]["actions"].push_back(a3::test::make_a2a("collision_avoidance"));
  e["dialogue"][2]["obs"].push_back(a3::test::make_a2a_obs("collision_avoidance"));
  e["dialogue"][3]["net"] = a3::test::make_net("mMTC", 120, 3.0, 2.0, 0.9);
  e["final_state"]["uav"]["pose"]["z"] = 8;  // an integer where others write 8.0
  e["_meta"]["attempts_used"] = 2;
  const EpisodeCheck c = check(e);
  ASSERT_EQ(c.status, EpisodeStatus::kValid) << all(c);
  EXPECT_TRUE(c.violations.empty());
  ASSERT_EQ(c.facts.turns.size(), 10u);
  EXPECT_EQ(c.facts.turns[0].speaker, Speaker::kAgent);
  EXPECT_EQ(c.facts.turns[1].speaker, Speaker::kUser);
  EXPECT_EQ(c.facts.turns[2].structured_actions, 2);
  EXPECT_EQ(c.facts.turns[2].matched_actions, 2);
  EXPECT_EQ(c.facts.turns[3].slice, "mMTC");
  EXPECT_DOUBLE_EQ(c.facts.turns[3].lat_ms, 120);
  EXPECT_DOUBLE_EQ(c.facts.turns[3].loss_pct, 3.0);
  EXPECT_DOUBLE_EQ(c.facts.turns[3].throughput_mbps, 2.0);
  EXPECT_DOUBLE_EQ(c.facts.turns[3].edge_load, 0.9);
  EXPECT_DOUBLE_EQ(c.facts.final_z_m, 8.0);
  EXPECT_DOUBLE_EQ(c.facts.alt_min_m, 30.0);
  EXPECT_DOUBLE_EQ(c.facts.alt_max_m, 400.0);
  EXPECT_DOUBLE_EQ(c.facts.battery_pct, 80.0);
  EXPECT_DOUBLE_EQ(c.facts.total_tokens, 4000);
  EXPECT_DOUBLE_EQ(c.facts.gen_time_s, 10.0);
  EXPECT_EQ(c.facts.attempts_used, 2);
  EXPECT_EQ(c.attempts_used, 2);
  EXPECT_TRUE(c.facts.success);
}

TEST_F(EpisodeReaderTest, A2aAnswerWithoutFromOrStatusIsValidButNotMatchedForTc) {
  json e = a3::test::make_episode();
  json obs = a3::test::make_a2a_obs("path_plan");
  obs.erase("status");
  e["dialogue"][4]["actions"].push_back(a3::test::make_a2a("path_plan"));
  e["dialogue"][4]["obs"].push_back(obs);
  const EpisodeCheck c = check(e);
  ASSERT_EQ(c.status, EpisodeStatus::kValid) << all(c);
  EXPECT_EQ(c.facts.turns[4].structured_actions, 2);
  EXPECT_EQ(c.facts.turns[4].matched_actions, 1);
}

TEST_F(EpisodeReaderTest, FailureStubIsRecognisedAndCountsOneAttempt) {
  const EpisodeCheck c = check(a3::test::make_failure_stub());
  EXPECT_EQ(c.status, EpisodeStatus::kFailureStub) << all(c);
  EXPECT_EQ(c.attempts_used, 1);
  json stub = a3::test::make_failure_stub();
  stub["_meta"]["attempts_used"] = 3;
  EXPECT_EQ(check(stub).attempts_used, 3);
  // A stub with turns is not a stub.
  stub["dialogue"] = a3::test::make_episode()["dialogue"];
  const EpisodeCheck bad = check(stub);
  EXPECT_EQ(bad.status, EpisodeStatus::kInvalid);
  EXPECT_TRUE(has(bad, "/dialogue", "schema")) << all(bad);
}

TEST_F(EpisodeReaderTest, NotJsonTruncatedEmptyAndTrailingGarbage) {
  EpisodeCheck c = check(std::string("this is not json"));
  EXPECT_EQ(c.status, EpisodeStatus::kInvalid);
  EXPECT_TRUE(has(c, "", "json-syntax"));
  EXPECT_NE(c.violations[0].message.find("line 1, column "), std::string::npos) << all(c);

  const std::string text = a3::test::make_episode().dump(2);
  c = check(text.substr(0, text.size() / 2));
  EXPECT_EQ(c.status, EpisodeStatus::kInvalid);
  EXPECT_NE(c.violations[0].message.find("truncated"), std::string::npos) << all(c);

  c = check(std::string(""));
  EXPECT_TRUE(has(c, "", "json-syntax"));

  c = check(text + " {}");
  EXPECT_TRUE(has(c, "", "json-syntax")) << all(c);

  c = check(std::string("{\n  \"a\": 1,\n  \"b\": tru\n}"));
  EXPECT_NE(c.violations[0].message.find("line 3"), std::string::npos) << all(c);
}

TEST_F(EpisodeReaderTest, InvalidUtf8IsRejectedWithItsOffset) {
  std::string text = a3::test::make_episode().dump();
  const std::size_t at = text.find("clear");
  text[at] = static_cast<char>(0xC3);  // a lead byte followed by ASCII
  const EpisodeCheck c = check(text);
  EXPECT_EQ(c.status, EpisodeStatus::kInvalid);
  EXPECT_NE(c.violations[0].message.find("byte " + std::to_string(at)), std::string::npos)
      << all(c);
}

TEST_F(EpisodeReaderTest, WrongTypesNameTheJsonPath) {
  json e = a3::test::make_episode();
  e["dialogue"][3]["net"]["lat_ms"] = "fast";
  e["success"] = "yes";
  const EpisodeCheck c = check(e);
  EXPECT_EQ(c.status, EpisodeStatus::kInvalid);
  EXPECT_TRUE(has(c, "/dialogue/3/net/lat_ms", "schema")) << all(c);
  EXPECT_TRUE(has(c, "/success", "schema")) << all(c);
  // The schema errors name the leaf, not every enclosing object.
  EXPECT_FALSE(has(c, "/dialogue/3", "schema")) << all(c);
  EXPECT_FALSE(has(c, "/dialogue", "schema")) << all(c);
}

TEST_F(EpisodeReaderTest, MissingSectionsAndBadEnums) {
  json e = a3::test::make_episode();
  e.erase("final_state");
  e["dialogue"][0]["net"]["slice"] = "5G";
  e["dialogue"][1]["actions"].push_back({{"type", "rpc"}});
  const EpisodeCheck c = check(e);
  EXPECT_EQ(c.status, EpisodeStatus::kInvalid);
  EXPECT_TRUE(has(c, "", "schema")) << all(c);  // required final_state
  EXPECT_TRUE(has(c, "/dialogue/0/net/slice", "schema")) << all(c);
  EXPECT_TRUE(has(c, "/dialogue/1/actions/0/type", "schema")) << all(c);
  EXPECT_EQ(check(json::array()).status, EpisodeStatus::kInvalid);
  EXPECT_EQ(check(json(42)).status, EpisodeStatus::kInvalid);
}

TEST_F(EpisodeReaderTest, SemanticRulesEachNameTheirRuleAndPath) {
  json e = a3::test::make_episode();
  e["dialogue"][5]["speaker"] = "system";
  e["dialogue"][7]["speaker"] = "agent";  // after turn 6 (agent): twice in a row
  e["dialogue"][2]["actions"].push_back({{"type", "mcp"}, {"name", "land"}});  // no args
  e["dialogue"][4]["actions"].push_back(a3::test::make_mcp("capture_image"));  // unanswered
  e["dialogue"][6]["obs"].push_back({{"result", 1}});  // names no tool or task
  e["dialogue"][8]["actions"].push_back(a3::test::make_a2a("swarm_status_check"));  // unanswered
  const EpisodeCheck c = check(e);
  EXPECT_EQ(c.status, EpisodeStatus::kInvalid);
  EXPECT_TRUE(has(c, "/dialogue/5/speaker", "role")) << all(c);
  EXPECT_TRUE(has(c, "/dialogue/7/speaker", "alternation")) << all(c);
  EXPECT_TRUE(has(c, "/dialogue/2/actions/1", "action-fields")) << all(c);
  EXPECT_TRUE(has(c, "/dialogue/4/actions/1", "unanswered-action")) << all(c);
  EXPECT_TRUE(has(c, "/dialogue/6/obs/1", "observation-fields")) << all(c);
  EXPECT_TRUE(has(c, "/dialogue/8/speaker", "alternation")) << all(c);  // agent after agent
  EXPECT_TRUE(has(c, "/dialogue/8/actions/1", "unanswered-action")) << all(c);
  EXPECT_EQ(c.violations.size(), 7u) << all(c);
}

TEST_F(EpisodeReaderTest, TurnCountMustBeEightToTwelve) {
  EXPECT_EQ(check(a3::test::make_episode(8)).status, EpisodeStatus::kValid);
  EXPECT_EQ(check(a3::test::make_episode(12)).status, EpisodeStatus::kValid);
  const EpisodeCheck seven = check(a3::test::make_episode(7));
  EXPECT_TRUE(has(seven, "/dialogue", "turn-count")) << all(seven);
  EXPECT_TRUE(has(check(a3::test::make_episode(13)), "/dialogue", "turn-count"));
}

TEST_F(EpisodeReaderTest, AnObservationForAnotherToolDoesNotAnswer) {
  json e = a3::test::make_episode();
  e["dialogue"][0]["obs"][0]["tool"] = "set_waypoint";
  const EpisodeCheck c = check(e);
  EXPECT_TRUE(has(c, "/dialogue/0/actions/0", "unanswered-action")) << all(c);
}

TEST_F(EpisodeReaderTest, SizeLimitAndUnreadableFiles) {
  const a3::test::TempDir dir("reader");
  std::string big = a3::test::make_episode().dump();
  big.append((1u << 20) + 10 - big.size(), ' ');  // valid JSON, over the 1 MiB limit
  a3::test::write_text(dir.path() / "big.json", big);
  EpisodeCheck c = reader_.check_file(dir.path() / "big.json");
  EXPECT_EQ(c.status, EpisodeStatus::kInvalid);
  EXPECT_TRUE(has(c, "", "file-size")) << all(c);

  c = reader_.check_file(dir.path() / "missing.json");
  EXPECT_TRUE(has(c, "", "file-read")) << all(c);
  c = reader_.check_file(dir.path());
  EXPECT_TRUE(has(c, "", "file-read")) << all(c);

  a3::test::write_json(dir.path() / "ok.json", a3::test::make_episode());
  EXPECT_EQ(reader_.check_file(dir.path() / "ok.json").status, EpisodeStatus::kValid);
}

TEST_F(EpisodeReaderTest, AttemptsOfAnInvalidButReadableFileAreCounted) {
  json e = a3::test::make_episode();
  e["_meta"]["attempts_used"] = 3;
  e["dialogue"][0]["speaker"] = "assistant";
  const EpisodeCheck c = check(e);
  EXPECT_EQ(c.status, EpisodeStatus::kInvalid);
  EXPECT_EQ(c.attempts_used, 3);
  e["_meta"]["attempts_used"] = "three";
  EXPECT_EQ(check(e).attempts_used, 1);
}

TEST_F(EpisodeReaderTest, ReaderIsReusableAcrossFiles) {
  // The parse memory is kept between files: a big file followed by small ones.
  json big = a3::test::make_episode(12);
  for (auto& turn : big["dialogue"]) turn["intent"] = std::string(50000, 'x');
  EXPECT_EQ(check(big).status, EpisodeStatus::kValid);
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(check(a3::test::make_episode(8 + i % 5)).status, EpisodeStatus::kValid);
    EXPECT_EQ(check(std::string("{")).status, EpisodeStatus::kInvalid);
  }
}

}  // namespace
}  // namespace a3::eval
