// The corpus responder replays recorded α³-Bench episodes: the right episode for a scenario and
// seed (by tag or by initial_state), its recorded latency and usage, recorded retries as failed
// attempts whose shares sum to the recorded figures, failure stubs as non-JSON at every attempt,
// and clear refusals.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "agent/model_server/corpus_responder.hpp"
#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
namespace ms = a3::agent::model_server;
using nlohmann::json;
using nlohmann::ordered_json;

ordered_json read_episode(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ordered_json::parse(ss.str());
}

json request_with(const std::string& user_text) {
  return {{"model", "openai/chatgpt-4o-latest"},
          {"messages", json::array({{{"role", "system"}, {"content", "You write episodes."}},
                                    {{"role", "user"}, {"content", user_text}}})}};
}

json tagged(int scenario, int64_t seed, int attempt) {
  char id[16];
  std::snprintf(id, sizeof id, "sc-%04d", scenario);
  return request_with(std::string("scenario_id: ") + id + "\nepisode_seed: " + std::to_string(seed) +
                      "\nattempt: " + std::to_string(attempt) + " of 3\n\nWrite the episode.");
}

TEST(CorpusResponder, AnswersTheRecordedEpisodeWithItsLatencyAndUsage) {
  A3_REQUIRE_SHARED(folder, "alphabench/eval_runs/openai/chatgpt-4o-latest/uav");
  const auto responder = ms::make_corpus_responder({folder.string()});
  EXPECT_EQ(responder->episode_count(), 50u);
  EXPECT_EQ(responder->failure_stub_count(), 0u);

  const ordered_json recorded = read_episode(folder / "sc-0007-ep-00.json");
  const ms::ResponderReply reply = responder->respond(tagged(7, 42, 1));
  ordered_json expected = recorded;
  expected.erase("_meta");
  EXPECT_EQ(ordered_json::parse(reply.content), expected);
  EXPECT_EQ(reply.content.find("_meta"), std::string::npos);
  // Keys in the recorded order, so the written file reads like the recorded one.
  EXPECT_EQ(reply.content.rfind("{\"initial_state\":", 0), 0u) << reply.content.substr(0, 40);
  ASSERT_TRUE(reply.latency_s.has_value());
  EXPECT_DOUBLE_EQ(*reply.latency_s, recorded["_meta"]["gen_time_s"].get<double>());
  EXPECT_EQ(reply.usage["total_tokens"], recorded["_meta"]["usage"]["total_tokens"]);
  EXPECT_EQ(reply.usage["prompt_tokens"], recorded["_meta"]["usage"]["prompt_tokens"]);
  EXPECT_EQ(reply.usage["cost"], recorded["_meta"]["usage"]["cost"]);
}

TEST(CorpusResponder, MatchesByInitialStateWhenTheRequestNamesNoScenario) {
  A3_REQUIRE_SHARED(folder, "alphabench/eval_runs/openai/chatgpt-4o-latest/uav");
  const auto responder = ms::make_corpus_responder({folder.string()});
  const ordered_json recorded = read_episode(folder / "sc-0031-ep-00.json");
  const json request =
      request_with("Write an episode from this initial_state:\n```json\n" + recorded["initial_state"].dump(2) + "\n```");
  const ms::RecordedEpisode& e = responder->match(request);
  EXPECT_EQ(e.scenario, 31);
  EXPECT_EQ(e.seed, 42);
  EXPECT_THROW(responder->respond(request_with("Write any episode.")), std::invalid_argument);
}

TEST(CorpusResponder, RefusesScenariosAndSeedsItHasNot) {
  A3_REQUIRE_SHARED(folder, "alphabench/eval_runs/openai/chatgpt-4o-latest/uav");
  const auto responder = ms::make_corpus_responder({folder.string()});
  try {
    responder->respond(tagged(777, 42, 1));
    FAIL() << "no error for a scenario the corpus has not";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sc-0777"), std::string::npos) << e.what();
  }
  try {
    responder->respond(tagged(3, 77, 1));
    FAIL() << "no error for a seed the corpus has not";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("episode_seed 77 (it has seed(s) 42)"), std::string::npos) << e.what();
  }
  EXPECT_THROW(responder->respond(request_with("scenario_id: sc-abc\n")), std::invalid_argument);
  EXPECT_THROW(responder->respond(request_with("scenario_id: sc-0001\nattempt: zero\n")), std::invalid_argument);
}

TEST(CorpusResponder, ReplaysRecordedRetriesAsFailedAttemptsWhoseSharesSumToTheRecord) {
  A3_REQUIRE_SHARED(folder, "alphabench/eval_runs/openai/gpt-5.1-chat/uav");
  const auto responder = ms::make_corpus_responder({folder.string()});
  // Find an episode recorded with 3 attempts.
  int scenario = -1;
  ordered_json recorded;
  for (int s = 0; s < 50 && scenario < 0; ++s) {
    char name[32];
    std::snprintf(name, sizeof name, "sc-%04d-ep-00.json", s);
    recorded = read_episode(folder / name);
    if (recorded["_meta"].value("attempts_used", 1) == 3) scenario = s;
  }
  ASSERT_GE(scenario, 0) << "gpt-5.1-chat has episodes recorded with 3 attempts";
  const double gen_time_s = recorded["_meta"]["gen_time_s"].get<double>();
  double latency_sum_s = 0.0;
  int64_t tokens_sum = 0;
  for (int attempt = 1; attempt <= 3; ++attempt) {
    const ms::ResponderReply reply = responder->respond(tagged(scenario, 42, attempt));
    const bool is_json = !json::parse(reply.content, nullptr, false).is_discarded();
    EXPECT_EQ(is_json, attempt == 3) << "attempt " << attempt << ": " << reply.content.substr(0, 80);
    ASSERT_TRUE(reply.latency_s.has_value());
    EXPECT_NEAR(*reply.latency_s, gen_time_s / 3, 1e-12);
    latency_sum_s += *reply.latency_s;
    tokens_sum += reply.usage["total_tokens"].get<int64_t>();
  }
  EXPECT_NEAR(latency_sum_s, gen_time_s, 1e-9);
  EXPECT_EQ(tokens_sum, recorded["_meta"]["usage"]["total_tokens"].get<int64_t>());
}

TEST(CorpusResponder, FailureStubsFailEveryAttempt) {
  A3_REQUIRE_SHARED(folder, "alphabench/eval_runs/google/gemini-3-pro-preview/uav");
  const auto responder = ms::make_corpus_responder({folder.string()});
  EXPECT_EQ(responder->episode_count(), 50u);
  EXPECT_EQ(responder->failure_stub_count(), 24u);
  const ordered_json stub = read_episode(folder / "sc-0009-ep-00.json");
  ASSERT_TRUE(stub["_meta"]["generation_failed"].get<bool>());
  // A stub records no seed: ep-00 is the paper's first episode seed, 42.
  for (int attempt = 1; attempt <= 3; ++attempt) {
    const ms::ResponderReply reply = responder->respond(tagged(9, 42, attempt));
    EXPECT_TRUE(json::parse(reply.content, nullptr, false).is_discarded()) << reply.content.substr(0, 80);
    EXPECT_NE(reply.content.find("'low' is not of type 'number'"), std::string::npos) << reply.content;
    EXPECT_FALSE(reply.latency_s.has_value());
  }
}

TEST(CorpusResponder, BadFoldersAreNamed) {
  const fs::path empty = fs::temp_directory_path() / ("a3_corpus_empty_" + std::to_string(::getpid()));
  fs::create_directories(empty);
  std::ofstream(empty / "notes.json") << "{}";
  try {
    ms::make_corpus_responder({empty.string()});
    FAIL() << "no error for a folder without episodes";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(empty.string() + ": no sc-XXXX-ep-YY.json"), std::string::npos) << e.what();
  }
  std::ofstream(empty / "sc-0001-ep-00.json") << "{\"initial_state\": {}, \"_meta\": {\"seed\": 42}}";
  try {
    ms::make_corpus_responder({empty.string()});
    FAIL() << "no error for an episode without a dialogue";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sc-0001-ep-00.json: /dialogue: missing"), std::string::npos) << e.what();
  }
  std::ofstream(empty / "sc-0001-ep-00.json") << "{\"initial_state\": {}, \"dialogue\": [], \"_meta\": {\"seed\": 42}}";
  try {
    ms::make_corpus_responder({empty.string()});
    FAIL() << "no error for an episode without gen_time_s";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sc-0001-ep-00.json: _meta.gen_time_s"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ms::make_corpus_responder({"/nonexistent/a3/corpus"}), std::invalid_argument);
  EXPECT_THROW(ms::make_corpus_responder({""}), std::invalid_argument);
  fs::remove_all(empty);
}

}  // namespace
