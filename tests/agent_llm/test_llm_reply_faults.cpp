// Hostile model replies: args nested 60,000 deep, bytes that are not UTF-8, duplicate keys. Each
// is a bad reply that goes through the correction ladder (never a crash, never node_failed), and
// the attempt log keeps the reply with invalid bytes replaced by U+FFFD, so the episode validates.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <thread>

#include "agent/llm/llm_agent.hpp"
#include "agent/llm/llm_reply.hpp"
#include "agent/tool_catalog.hpp"
#include "common/json_text.hpp"
#include "tests/agent_llm/llm_test_support.hpp"
#include "tests/agent_llm/scripted_server.hpp"
#include "tests/rigs/rig_test_support.hpp"

// After the project headers: httplib.h (with OpenSSL) before Eigen breaks Eigen's declarations.
#include <httplib.h>

namespace a3 {
namespace {

using namespace agent::llm;
using agent::CallAsAction;
using agent::ToolCatalog;

const char* kValid =
    R"({"intent": "preflight_check", "text": "Checking the vehicle.", "actions": [{"type": "mcp", "name": "read_telemetry", "args": {}}]})";
const std::string kReplacement = "\xEF\xBF\xBD";  // U+FFFD

// A chat-completions body whose content holds raw bytes that are not UTF-8 (0xff, a cut 0xc3).
std::string body_with_invalid_utf8() {
  return R"({"id": "x", "object": "chat.completion", "model": "fake-model", "choices": [{"index": 0, )"
         R"("message": {"role": "assistant", "content": "{\"intent\": \"take)" + std::string("\xff\xc3") +
         R"(off\", \"actions\": []}"}, )"
         R"("finish_reason": "stop"}], "usage": {"prompt_tokens": 100, "completion_tokens": 20, "total_tokens": 120}})";
}

std::string nested_args(int depth) {
  std::string args;
  for (int i = 0; i < depth; ++i) args += "{\"a\":";
  args += "1" + std::string(depth, '}');
  return R"({"intent": "x", "actions": [{"type": "mcp", "name": "read_telemetry", "args": )" + args + "}]}";
}

TEST(LlmReplyFaults, ArgsNested60000DeepAreRefusedNamingTheDepth) {
  ParsedReply r;
  ASSERT_NO_FATAL_FAILURE(r = parse_reply(nested_args(60000), ToolCatalog::builtin()));
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.problems_text().find("nested deeper than the limit of 128"), std::string::npos) << r.problems_text();
  EXPECT_NE(r.problems_text().find("/actions/0/args/a/a"), std::string::npos) << r.problems_text();
  EXPECT_TRUE(r.actions.empty());
}

TEST(LlmReplyFaults, InvalidUtf8AndDuplicateKeysInARepliesTextAreProblemsWithTheirPlace) {
  const ParsedReply bad = parse_reply("{\"intent\": \"x\xff\", \"actions\": []}", ToolCatalog::builtin());
  EXPECT_NE(bad.problems_text().find("byte 13: invalid UTF-8"), std::string::npos) << bad.problems_text();
  const ParsedReply twice = parse_reply(R"({"intent": "a", "intent": "b", "actions": []})", ToolCatalog::builtin());
  EXPECT_NE(twice.problems_text().find("duplicate key \"intent\""), std::string::npos) << twice.problems_text();
}

TEST(LlmReplyFaults, ToolCallArgumentsNestedTooDeepAreARefusedCall) {
  std::string deep;
  for (int i = 0; i < 60000; ++i) deep += "[";
  const CallAsAction a = ToolCatalog::builtin().action_from_call("read_telemetry", nlohmann::json(deep));
  EXPECT_NE(a.problem.find("nested deeper than the limit"), std::string::npos) << a.problem;
}

struct Fixture : ::testing::Test {
  test::PlayedContext played = test::play_scripted("survey-field", 0);
  agent::AgentContext context = played.context(1, test::normal_net());
  test::FakeChatServer server;

  std::unique_ptr<LlmAgent> agent() const {
    LlmEndpoint e;
    e.base_url = server.base_url();
    e.model = "fake-model";
    e.api_key = "sk-test";
    e.max_retries = 0;
    e.total_timeout_s = 20.0;
    return std::make_unique<LlmAgent>(std::make_unique<LlmClient>(e));
  }
};

TEST_F(Fixture, InvalidUtf8ReplyIsCorrectedAndKeptWithReplacementCharacters) {
  server.fail(200, body_with_invalid_utf8());
  server.reply(kValid);
  agent::AgentDecision d;
  ASSERT_NO_THROW(d = agent()->decide(context));
  EXPECT_TRUE(d.error.empty()) << d.error;
  EXPECT_EQ(d.attempts, 2);
  EXPECT_EQ(d.intent, "preflight_check");
  ASSERT_EQ(d.attempt_log.size(), 2u);
  EXPECT_EQ(d.attempt_log[0]["outcome"], "invalid_reply");
  const std::string problem = d.attempt_log[0]["problems"][0].get<std::string>();
  EXPECT_NE(problem.find("not valid UTF-8"), std::string::npos) << problem;
  const std::string reply = d.attempt_log[0]["reply"].get<std::string>();
  EXPECT_NE(reply.find("take" + kReplacement + kReplacement + "off"), std::string::npos) << reply;
  EXPECT_NO_THROW(d.attempt_log.dump());  // strict: throws on invalid UTF-8
  EXPECT_EQ(d.attempt_log[1]["outcome"], "ok");
  // The retry's correction names the problem.
  const auto requests = server.requests();
  ASSERT_EQ(requests.size(), 2u);
  EXPECT_NE(requests[1]["messages"].back()["content"].get<std::string>().find("not valid UTF-8"), std::string::npos);
}

// Between the rig and the scripted model: the first request gets a reply that is not UTF-8,
// every later one is passed on to the scripted responder.
class FirstReplyNotUtf8 {
 public:
  explicit FirstReplyNotUtf8(const std::string& upstream_base_url) {
    const std::string host_port = upstream_base_url.substr(std::string("http://").size(),
                                                           upstream_base_url.find("/v1") - std::string("http://").size());
    server_.Post("/v1/chat/completions", [this, host_port](const httplib::Request& req, httplib::Response& res) {
      if (!sent_bad_.exchange(true)) {
        res.set_content(body_with_invalid_utf8(), "application/json");
        return;
      }
      httplib::Client upstream("http://" + host_port);
      upstream.set_read_timeout(30, 0);
      const auto answer = upstream.Post("/v1/chat/completions", req.body, "application/json");
      res.status = answer ? answer->status : 502;
      res.set_content(answer ? answer->body : std::string("{}"), "application/json");
    });
    port_ = server_.bind_to_any_port("127.0.0.1");
    thread_ = std::thread([this] { server_.listen_after_bind(); });
    while (!server_.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ~FirstReplyNotUtf8() {
    server_.stop();
    thread_.join();
  }
  std::string base_url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/v1"; }

 private:
  httplib::Server server_;
  std::thread thread_;
  int port_ = 0;
  std::atomic<bool> sent_bad_{false};
};

TEST(LlmReplyFaultsClosedLoop, AReplyThatIsNotUtf8IsRetriedAndTheEpisodeValidates) {
  ::unsetenv("A3_LLM_API_KEY");
  ::unsetenv("A3_LLM_API_KEY_FILE");
  ::unsetenv("OPENAI_API_KEY");
  ::unsetenv("A3_LLM_PROVIDER");
  test::ScriptedServer scripted("fixed:0.01");
  FirstReplyNotUtf8 proxy(scripted.server.base_url());

  rigs::RunOptions o = test::virtual_run("survey-field", "llm-reply-not-utf8");
  o.agent = "llm";
  o.llm_tools = "json";
  o.llm_base_url = proxy.base_url();
  o.llm_model = "scripted-policy";
  const rigs::RunResult run = test::run(o);

  ASSERT_EQ(run.status, "completed") << common::dump_json_text(run.episode["_rig"], 1).substr(0, 3000);
  const test::Scored score = test::score(run.episode);
  EXPECT_TRUE(score.valid) << score.problems;
  const auto& first_agent_turn = run.episode["_rig"]["turns"][0];
  ASSERT_EQ(first_agent_turn["attempts"], 2);
  EXPECT_EQ(first_agent_turn["attempt_log"][0]["outcome"], "invalid_reply");
  EXPECT_NE(first_agent_turn["attempt_log"][0]["reply"].get<std::string>().find(kReplacement), std::string::npos);
  EXPECT_EQ(first_agent_turn["attempt_log"][1]["outcome"], "ok");
}

}  // namespace
}  // namespace a3
