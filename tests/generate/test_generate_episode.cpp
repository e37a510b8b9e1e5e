// One generated episode (rigs/generate/generate_episode.hpp) against a scripted chat: the attempt
// ladder with stricter instructions, validation, `_meta` key for key as the public corpus, usage
// summed over attempts, failure stubs, and endpoint failures that stop the run.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "eval/episode_schema.hpp"
#include "eval/json_schema_validator.hpp"
#include "eval/scoring_profile.hpp"
#include "rigs/generate/generate_episode.hpp"
#include "rigs/generate/generate_scenarios.hpp"
#include "rigs/scenario/scenario.hpp"
#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using a3::agent::llm::ChatMessage;
using a3::agent::llm::LlmCallResult;
using nlohmann::ordered_json;

std::vector<std::string> keys_of(const ordered_json& object) {
  std::vector<std::string> keys;
  for (auto it = object.begin(); it != object.end(); ++it) keys.push_back(it.key());
  return keys;
}

LlmCallResult answer(const std::string& content, int64_t total_tokens) {
  LlmCallResult r;
  r.ok = true;
  r.http_status = 200;
  r.content = content;
  r.usage.prompt_tokens = total_tokens / 2;
  r.usage.completion_tokens = total_tokens - total_tokens / 2;
  r.usage.total_tokens = total_tokens;
  return r;
}

// A chat answering from a list, recording the messages it was sent.
struct ScriptedChat {
  std::vector<LlmCallResult> replies;
  std::vector<std::vector<ChatMessage>> sent;
  a3::rigs::GenerateChat function() {
    return [this](const std::vector<ChatMessage>& messages) {
      sent.push_back(messages);
      return replies.at(sent.size() - 1);
    };
  }
};

class GenerateEpisode : public ::testing::Test {
 protected:
  void SetUp() override {
    const fs::path folder = a3::test::shared_dir() / "alphabench/eval_runs/openai/chatgpt-4o-latest/uav";
    if (!fs::exists(folder)) GTEST_SKIP() << a3::test::shared_missing_message(folder);
    std::ifstream in(folder / "sc-0004-ep-00.json");
    std::stringstream ss;
    ss << in.rdbuf();
    recorded_ = ordered_json::parse(ss.str());
    episode_ = recorded_;
    episode_.erase("_meta");
    scenario_.number = 4;
    scenario_.source = "test";
    scenario_.initial_state = recorded_["initial_state"];
  }
  a3::eval::EpisodeCheck check(const ordered_json& doc) { return reader_.check_text(doc.dump()); }

  const a3::eval::JsonSchemaValidator validator_{a3::eval::episode_schema_json(), a3::eval::kEpisodeSchemaName};
  const a3::eval::ScoringProfile profile_ = a3::eval::release_profile();
  a3::eval::EpisodeReader reader_{validator_, profile_};
  ordered_json recorded_, episode_;
  a3::rigs::GenerateScenario scenario_;
};

TEST_F(GenerateEpisode, ValidFirstReplyGetsTheCorpusMetaKeyForKey) {
  ScriptedChat chat;
  chat.replies = {answer("Here it is:\n```json\n" + episode_.dump(2) + "\n```", 4205)};
  const auto out = a3::rigs::generate_episode(chat.function(), reader_, scenario_, 42, "openai/chatgpt-4o-latest");
  EXPECT_FALSE(out.generation_failed);
  EXPECT_EQ(out.attempts_used, 1);
  const ordered_json& meta = out.document["_meta"];
  EXPECT_EQ(keys_of(meta), keys_of(recorded_["_meta"]));
  EXPECT_EQ(keys_of(meta), (std::vector<std::string>{"seed", "ts", "ts_iso", "gen_time_s", "attempts_used",
                                                     "generation_failed", "usage"}));
  EXPECT_EQ(meta["seed"], 42);
  EXPECT_EQ(meta["attempts_used"], 1);
  EXPECT_EQ(meta["generation_failed"], false);
  EXPECT_EQ(meta["usage"]["total_tokens"], 4205);
  EXPECT_GE(meta["gen_time_s"].get<double>(), 0.0);
  EXPECT_EQ(meta["ts_iso"].get<std::string>().size(), 20u);  // 2025-12-01T12:13:28Z
  EXPECT_EQ(keys_of(out.document), keys_of(recorded_));
  EXPECT_EQ(check(out.document).status, a3::eval::EpisodeStatus::kValid);
  // The user message carries the tags the corpus responder reads, and the initial_state.
  ASSERT_EQ(chat.sent.size(), 1u);
  const std::string& user = chat.sent[0].at(1).content;
  EXPECT_NE(user.find("scenario_id: sc-0004\nepisode_seed: 42\nattempt: 1 of 3\n"), std::string::npos) << user;
  EXPECT_NE(user.find("\"alt_bounds\""), std::string::npos);
}

TEST_F(GenerateEpisode, RetriesWithStricterInstructionsAndSumsUsage) {
  ordered_json bad_roles = episode_;
  bad_roles["dialogue"][1]["speaker"] = "system";
  ScriptedChat chat;
  chat.replies = {answer("I cannot write JSON today.", 100), answer(bad_roles.dump(), 3000),
                  answer(episode_.dump(), 4000)};
  const auto out = a3::rigs::generate_episode(chat.function(), reader_, scenario_, 77, "openai/x");
  EXPECT_FALSE(out.generation_failed);
  EXPECT_EQ(out.attempts_used, 3);
  EXPECT_EQ(out.document["_meta"]["attempts_used"], 3);
  EXPECT_EQ(out.document["_meta"]["seed"], 77);
  EXPECT_EQ(out.document["_meta"]["usage"]["total_tokens"], 7100);
  ASSERT_EQ(out.attempt_errors.size(), 2u);
  EXPECT_NE(out.attempt_errors[0].find("no JSON object"), std::string::npos) << out.attempt_errors[0];
  EXPECT_NE(out.attempt_errors[1].find("/dialogue/1/speaker"), std::string::npos) << out.attempt_errors[1];
  // Attempt 2 restricts the roles and says what was wrong; attempt 3 also restricts the format.
  ASSERT_EQ(chat.sent.size(), 3u);
  EXPECT_EQ(chat.sent[0][0].content.find("strictly alternating"), std::string::npos);
  EXPECT_NE(chat.sent[1][0].content.find("strictly alternating"), std::string::npos);
  EXPECT_NE(chat.sent[1][1].content.find("no JSON object"), std::string::npos);
  EXPECT_NE(chat.sent[1][1].content.find("attempt: 2 of 3"), std::string::npos);
  EXPECT_EQ(chat.sent[1][0].content.find("JSON object only"), std::string::npos);
  EXPECT_NE(chat.sent[2][0].content.find("JSON object only"), std::string::npos);
  EXPECT_NE(chat.sent[2][1].content.find("/dialogue/1/speaker"), std::string::npos);
  EXPECT_NE(chat.sent[2][1].content.find("last attempt"), std::string::npos);
}

TEST_F(GenerateEpisode, AllAttemptsFailingWritesAStubLikeTheCorpus) {
  ordered_json bad_net = episode_;
  bad_net["dialogue"][0]["net"]["edge_load"] = "low";
  ScriptedChat chat;
  chat.replies = {answer(bad_net.dump(), 10), answer(bad_net.dump(), 10), answer(bad_net.dump(), 10)};
  const auto out = a3::rigs::generate_episode(chat.function(), reader_, scenario_, 42, "google/gemini-3-pro-preview");
  EXPECT_TRUE(out.generation_failed);
  EXPECT_EQ(out.attempts_used, 3);
  const ordered_json& doc = out.document;
  EXPECT_EQ(keys_of(doc), (std::vector<std::string>{"initial_state", "dialogue", "final_state", "success", "_meta"}));
  EXPECT_EQ(keys_of(doc["_meta"]), (std::vector<std::string>{"model", "error", "ts", "generation_failed"}));
  EXPECT_EQ(doc["_meta"]["model"], "google/gemini-3-pro-preview");
  EXPECT_EQ(doc["_meta"]["generation_failed"], true);
  const std::string error = doc["_meta"]["error"];
  EXPECT_EQ(error.rfind("Episode generation failed after 3 attempts: ", 0), 0u) << error;
  EXPECT_NE(error.find("/dialogue/0/net/edge_load"), std::string::npos) << error;
  EXPECT_TRUE(doc["dialogue"].empty());
  EXPECT_EQ(doc["final_state"], scenario_.initial_state);
  EXPECT_EQ(doc["success"], false);
  EXPECT_EQ(check(doc).status, a3::eval::EpisodeStatus::kFailureStub);
}

TEST_F(GenerateEpisode, ARefusedRequestIsAFailedAttemptButAnUnreachableEndpointStopsTheRun) {
  LlmCallResult refused;
  refused.http_status = 400;
  refused.error = "HTTP 400: context length exceeded";
  ScriptedChat chat;
  chat.replies = {refused, answer(episode_.dump(), 10)};
  const auto out = a3::rigs::generate_episode(chat.function(), reader_, scenario_, 42, "m/x");
  EXPECT_FALSE(out.generation_failed);
  EXPECT_EQ(out.attempts_used, 2);
  ASSERT_EQ(out.attempt_errors.size(), 1u);
  EXPECT_NE(out.attempt_errors[0].find("context length exceeded"), std::string::npos);

  for (int status : {0, 401, 429, 503}) {
    LlmCallResult down;
    down.http_status = status;
    down.error = "HTTP " + std::to_string(status);
    ScriptedChat failing;
    failing.replies = {down};
    try {
      a3::rigs::generate_episode(failing.function(), reader_, scenario_, 42, "m/x");
      FAIL() << "status " << status << " did not stop the run";
    } catch (const a3::rigs::GenerateEndpointError& e) {
      EXPECT_NE(std::string(e.what()).find("sc-0004 seed 42"), std::string::npos) << e.what();
    }
  }
}

TEST(GenerateScenarios, ReadsACorpusFolderBuiltInsAndNamesBadArguments) {
  A3_REQUIRE_SHARED(folder, "alphabench/eval_runs/openai/chatgpt-4o-latest/uav");
  const auto scenarios = a3::rigs::load_generate_scenarios({folder.string()});
  ASSERT_EQ(scenarios.size(), 50u);
  EXPECT_EQ(scenarios.front().number, 0);
  EXPECT_EQ(scenarios.back().number, 49);
  std::ifstream in(folder / "sc-0013-ep-00.json");
  EXPECT_EQ(scenarios[13].initial_state.dump(), nlohmann::ordered_json::parse(in)["initial_state"].dump());

  const auto names = a3::rigs::builtin_scenario_names();
  ASSERT_FALSE(names.empty());
  const auto mixed = a3::rigs::load_generate_scenarios({(folder / "sc-0002-ep-00.json").string(), names.front()});
  ASSERT_EQ(mixed.size(), 2u);
  EXPECT_EQ(mixed[0].number, 0);  // the built-in takes the first free number
  EXPECT_FALSE(mixed[0].mission.empty());
  EXPECT_EQ(mixed[1].number, 2);

  try {
    a3::rigs::load_generate_scenarios({"no-such-scenario"});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--scenarios no-such-scenario: not a folder, a file, nor a built-in"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(a3::rigs::load_generate_scenarios({folder.string(), folder.string()}), std::invalid_argument);
  EXPECT_THROW(a3::rigs::load_generate_scenarios({folder.parent_path().string()}), std::invalid_argument);
}

}  // namespace
