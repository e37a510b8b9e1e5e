// Episodes that are JSON but not safe or not unambiguous to read: nesting deeper than
// kMaxEpisodeDepth (a recursive parser or validator would overflow its stack) and duplicate
// keys (a3rig and Python's json would score different values). Both are invalid episodes with a
// JSON path, never a crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "eval/episode_reader.hpp"
#include "eval/episode_schema.hpp"
#include "eval/json_shape.hpp"
#include "tests/eval/episode_builder.hpp"

namespace a3::eval {
namespace {

using nlohmann::json;

class EpisodeJsonShapeTest : public ::testing::Test {
 protected:
  EpisodeCheck check(const std::string& text) { return reader_.check_text(text); }

  static std::string all(const EpisodeCheck& c) {
    std::string s;
    for (const auto& v : c.violations) s += to_string(v) + "\n";
    return s;
  }

  const ScoringProfile profile_ = release_profile();
  const JsonSchemaValidator validator_{episode_schema_json(), kEpisodeSchemaName};
  EpisodeReader reader_{validator_, profile_, 4u << 20};
};

std::string nested_objects(int depth) {
  std::string text;
  for (int i = 0; i < depth; ++i) text += "{\"a\":";
  return text + "1" + std::string(depth, '}');
}

TEST_F(EpisodeJsonShapeTest, HugeNestingIsInvalidNotACrash) {
  for (const std::string& text : {std::string(131072, '['), std::string(100000, '[') + std::string(100000, ']'),
                                  nested_objects(200000)}) {
    const EpisodeCheck c = check(text);
    EXPECT_EQ(c.status, EpisodeStatus::kInvalid);
    ASSERT_FALSE(c.violations.empty());
  }
  const EpisodeCheck closed = check(std::string(100000, '[') + std::string(100000, ']'));
  ASSERT_EQ(closed.violations.size(), 1u) << all(closed);
  EXPECT_EQ(closed.violations[0].rule, "json-depth");
  EXPECT_EQ(closed.violations[0].json_path.size(), 2u * kMaxEpisodeDepth);  // "/0" per level
  EXPECT_NE(closed.violations[0].message.find("limit of " + std::to_string(kMaxEpisodeDepth)), std::string::npos);
  EXPECT_EQ(check(nested_objects(200000)).violations.at(0).rule, "json-depth");
}

TEST_F(EpisodeJsonShapeTest, DeepArgsInAnEpisodeAreInvalidAtTheirPath) {
  json e = a3::test::make_episode();
  json deep = 1;
  for (int i = 0; i < kMaxEpisodeDepth; ++i) deep = json{{"k", deep}};
  e["dialogue"][0]["actions"][0]["args"] = deep;  // dialogue, 0, actions, 0, args: 5 levels more
  const EpisodeCheck c = check(e.dump());
  EXPECT_EQ(c.status, EpisodeStatus::kInvalid);
  ASSERT_EQ(c.violations.size(), 1u) << all(c);
  EXPECT_EQ(c.violations[0].rule, "json-depth");
  EXPECT_EQ(c.violations[0].json_path.rfind("/dialogue/0/actions/0/args/k/k/", 0), 0u);
}

// Just within the limit, the whole check (valijson, rules, facts) runs on it: it descends only
// as deep as the schema, so the args' depth does not matter to it.
TEST_F(EpisodeJsonShapeTest, DeepArgsWithinTheLimitAreAValidEpisode) {
  json e = a3::test::make_episode();
  json deep = 1;
  for (int i = 0; i < kMaxEpisodeDepth - 5; ++i) deep = json{{"k", deep}};  // args is the 5th level
  e["dialogue"][0]["actions"][0]["args"] = deep;
  const EpisodeCheck c = check(e.dump());
  EXPECT_EQ(c.status, EpisodeStatus::kValid) << all(c);
}

TEST_F(EpisodeJsonShapeTest, NestingAtTheLimitIsNotADepthProblem) {
  JsonShapeChecker checker(3);
  rapidjson::Document d;
  Violations v;
  d.Parse(R"({"a": [{"b": 1}], "c": [[2]]})");
  EXPECT_FALSE(checker.check(d, v));
  d.Parse(R"({"a": [{"b": 1}], "c": [[[2]]]})");
  EXPECT_TRUE(checker.check(d, v));
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].json_path, "/c/0/0");
}

TEST_F(EpisodeJsonShapeTest, DuplicateKeysAreInvalidWithTheObjectsPath) {
  std::string text = a3::test::make_episode().dump();
  const std::string success = "\"success\":true";
  ASSERT_NE(text.find(success), std::string::npos);
  text.replace(text.find(success), success.size(), "\"success\":false,\"success\":true");
  EpisodeCheck c = check(text);
  EXPECT_EQ(c.status, EpisodeStatus::kInvalid);
  ASSERT_EQ(c.violations.size(), 1u) << all(c);
  EXPECT_EQ(c.violations[0].json_path, "");
  EXPECT_EQ(c.violations[0].rule, "json-duplicate-key");
  EXPECT_NE(c.violations[0].message.find("duplicate key \"success\""), std::string::npos);

  // Deeper, and in an object with many members (the sorted path).
  json e = a3::test::make_episode();
  for (int i = 0; i < 40; ++i) e["dialogue"][3]["net"]["extra" + std::to_string(i)] = i;
  std::string deep = e.dump();
  const std::string lat = "\"lat_ms\":";
  const std::size_t at = deep.find(lat, deep.find("\"extra39\""));
  ASSERT_NE(at, std::string::npos);
  deep.insert(at, "\"extra7\":0,\"extra7\":1,");
  c = check(deep);
  EXPECT_EQ(c.status, EpisodeStatus::kInvalid);
  ASSERT_EQ(c.violations.size(), 1u) << all(c);  // reported once although it appears three times
  EXPECT_EQ(c.violations[0].json_path.rfind("/dialogue/", 0), 0u) << all(c);
  EXPECT_NE(c.violations[0].json_path.find("/net"), std::string::npos) << all(c);
  EXPECT_NE(c.violations[0].message.find("\"extra7\""), std::string::npos);
}

TEST_F(EpisodeJsonShapeTest, KeysNeedingEscapesInThePointerAreEscaped) {
  JsonShapeChecker checker;
  rapidjson::Document d;
  Violations v;
  d.Parse(R"({"a/b": [0, {"m~n": {"k": 1, "k": 2}}]})");
  EXPECT_TRUE(checker.check(d, v));
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].json_path, "/a~1b/1/m~0n");
}

// A small object (compared pair by pair, after a mask of length and end bytes): each repeated
// key once, in the order of second occurrences, and keys alike in length and ends are not
// mistaken for each other.
TEST_F(EpisodeJsonShapeTest, EachRepeatedKeyOfASmallObjectIsReportedOnce) {
  JsonShapeChecker checker;
  rapidjson::Document d;
  Violations v;
  d.Parse(R"({"o": {"kk": 1, "jx": 2, "kk": 3, "kk": 4, "jx": 5, "kak": 6, "kbk": 7, "": 8, "": 9}})");
  EXPECT_TRUE(checker.check(d, v));
  ASSERT_EQ(v.size(), 3u);
  EXPECT_NE(v[0].message.find("duplicate key \"kk\""), std::string::npos) << v[0].message;
  EXPECT_NE(v[1].message.find("duplicate key \"jx\""), std::string::npos) << v[1].message;
  EXPECT_NE(v[2].message.find("duplicate key \"\""), std::string::npos) << v[2].message;
  EXPECT_EQ(v[0].json_path, "/o");
}

TEST_F(EpisodeJsonShapeTest, TheSameKeyInSiblingObjectsIsFine) {
  const EpisodeCheck c = check(a3::test::make_episode().dump());
  EXPECT_EQ(c.status, EpisodeStatus::kValid) << all(c);
}

}  // namespace
}  // namespace a3::eval
