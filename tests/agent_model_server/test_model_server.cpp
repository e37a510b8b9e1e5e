// ModelServer on loopback: request validation, /v1/models, latency applied, fault injection,
// the required key, concurrency, stopping, and the LLM client (agent/llm) against it end to end.
#include <gtest/gtest.h>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <future>
#include <thread>
#include <vector>

#include "agent/llm/llm_client.hpp"
#include "agent/model_server/model_server.hpp"
#include "agent/model_server/reply_file_responder.hpp"

// After the project headers: httplib pulls in <resolv.h>, whose _res macro breaks Eigen.
#include <httplib.h>

namespace {

namespace ms = a3::agent::model_server;
namespace llm = a3::agent::llm;
using nlohmann::json;
using SteadyClock = std::chrono::steady_clock;

// A responder that reports a recorded latency, as the corpus responder does.
class RecordedLatencyResponder final : public ms::ModelResponder {
 public:
  explicit RecordedLatencyResponder(double latency_s) : latency_s_(latency_s) {}
  std::string name() const override { return "recorded-test"; }
  ms::ResponderReply respond(const json& request) override {
    if (request["messages"].back()["content"] == "refuse") throw std::invalid_argument("this request cannot be answered");
    if (request["messages"].back()["content"] == "crash") throw std::runtime_error("disk on fire");
    ms::ResponderReply r;
    r.content = "ok";
    r.latency_s = latency_s_;
    r.usage = {{"prompt_tokens", 100}, {"completion_tokens", 20}, {"total_tokens", 120}, {"cost", 0.5}};
    return r;
  }

 private:
  double latency_s_;
};

struct Served {
  explicit Served(ms::ModelServerOptions o, std::unique_ptr<ms::ModelResponder> responder = nullptr) {
    o.host = "127.0.0.1";
    o.port = 0;
    o.quiet = true;
    if (!responder) responder = std::make_unique<ms::ReplyFileResponder>(std::vector<std::string>{R"({"intent":"hold"})"});
    server = std::make_unique<ms::ModelServer>(std::move(responder), o);
    server->start();
  }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", server->port());
    c.set_read_timeout(30, 0);
    return c;
  }
  httplib::Result post(const std::string& body, const httplib::Headers& headers = {}) const {
    auto c = client();
    return c.Post("/v1/chat/completions", headers, body, "application/json");
  }
  std::unique_ptr<ms::ModelServer> server;
};

const std::string kGoodRequest = R"({"model":"m","messages":[{"role":"user","content":"hello there"}]})";

std::string error_message(const httplib::Result& r) {
  const json body = json::parse(r->body, nullptr, false);
  if (!body.is_object() || !body.contains("error") || !body["error"].contains("message")) return "(no error object)";
  return body["error"]["message"].get<std::string>();
}

double seconds_since(SteadyClock::time_point t0) {
  return std::chrono::duration<double>(SteadyClock::now() - t0).count();
}

TEST(ModelServer, AnswersInTheOpenAiShape) {
  Served s({});
  const auto r = s.post(kGoodRequest);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const json body = json::parse(r->body);
  EXPECT_EQ(body["object"], "chat.completion");
  EXPECT_EQ(body["model"], "m");
  EXPECT_TRUE(body["id"].is_string());
  EXPECT_TRUE(body["created"].is_number_integer());
  EXPECT_EQ(body["choices"][0]["index"], 0);
  EXPECT_EQ(body["choices"][0]["message"]["role"], "assistant");
  EXPECT_EQ(body["choices"][0]["message"]["content"], R"({"intent":"hold"})");
  EXPECT_EQ(body["choices"][0]["finish_reason"], "stop");
  EXPECT_EQ(body["usage"]["prompt_tokens"], 3);  // "hello there": 11 characters
  EXPECT_EQ(body["usage"]["completion_tokens"], 5);
  EXPECT_EQ(body["usage"]["total_tokens"], 8);
  const ms::ModelServerStats stats = s.server->stats();
  EXPECT_EQ(stats.requests, 1u);
  EXPECT_EQ(stats.answered, 1u);
  EXPECT_EQ(stats.prompt_tokens, 3);
}

// {body, a piece of the message, the `param` OpenAI's error object must name ("" : null)}.
struct BadCase {
  std::string body, expected, param;
};

std::string with_user(const std::string& extra) {
  return R"({"model":"m","messages":[{"role":"user","content":"x"}])" + extra + "}";
}

const std::string kTool = R"({"type":"function","function":{"name":"hover","parameters":{"type":"object"}}})";

TEST(ModelServer, RejectsBadRequestsWith400NamingTheProblemAndTheField) {
  Served s({});
  const std::vector<BadCase> cases = {
      {"{not json", "not JSON", ""},
      {"[1,2]", "must be a JSON object", ""},
      {R"({"messages":[{"role":"user","content":"x"}]})", "'model' is required", "model"},
      {R"({"model":7,"messages":[{"role":"user","content":"x"}]})", "'model' must be a non-empty string", "model"},
      {R"({"model":"m"})", "'messages' is required", "messages"},
      {R"({"model":"m","messages":"hello"})", "'messages' must be a non-empty array", "messages"},
      {R"({"model":"m","messages":[]})", "'messages' must be a non-empty array", "messages"},
      {R"({"model":"m","messages":["hello"]})", "messages[0] must be an object", "messages[0]"},
      {R"({"model":"m","messages":[{"content":"x"}]})", "messages[0].role must be a string", "messages[0].role"},
      {R"({"model":"m","messages":[{"role":"user","content":"x"},{"role":"robot","content":"x"}]})",
       "messages[1].role must be one of", "messages[1].role"},
      {R"({"model":"m","messages":[{"role":"user"}]})", "messages[0].content is required", "messages[0].content"},
      {R"({"model":"m","messages":[{"role":"user","content":42}]})", "messages[0].content must be a string",
       "messages[0].content"},
      {R"({"model":"m","messages":[{"role":"tool","content":"x"}]})", "tool_call_id", "messages[0].tool_call_id"},
      {with_user(R"(,"temperature":"hot")"), "'temperature'", "temperature"},
      {with_user(R"(,"max_tokens":0)"), "'max_tokens'", "max_tokens"},
      {with_user(R"(,"stream":"yes")"), "'stream' must be a boolean", "stream"},
      {with_user(R"(,"stream_options":{"include_usage":true})"), "only allowed when 'stream' is true", "stream_options"},
      {with_user(R"(,"stream":true,"stream_options":{"include_usage":1})"), "include_usage",
       "stream_options.include_usage"},
      {with_user(R"(,"n":0)"), "'n' must be an integer from 1 to 8", "n"},
      {with_user(R"(,"n":9)"), "'n' must be an integer from 1 to 8", "n"},
      {with_user(R"(,"n":1.5)"), "'n' must be an integer", "n"},
      {with_user(R"(,"logprobs":true)"), "'logprobs': true is not supported", "logprobs"},
      {with_user(R"(,"top_logprobs":2)"), "'top_logprobs' is not supported", "top_logprobs"},
      {with_user(R"(,"audio":{"voice":"alloy","format":"wav"})"), "'audio' output is not supported", "audio"},
      {with_user(R"(,"modalities":["text","audio"])"), "'modalities' may only hold", "modalities"},
      {with_user(R"(,"functions":[{"name":"f"}])"), "use 'tools'", "functions"},
      {with_user(R"(,"function_call":"auto")"), "use 'tools'", "function_call"},
      {with_user(R"(,"web_search_options":{})"), "no web search", "web_search_options"},
      {with_user(R"(,"response_format":"json")"), "'response_format' must be an object", "response_format"},
      {with_user(R"(,"response_format":{"type":"xml"})"), "must be text, json_object or json_schema",
       "response_format.type"},
      {with_user(R"(,"response_format":{"type":"json_schema"})"), "'response_format.json_schema' must be an object",
       "response_format.json_schema"},
      {with_user(R"(,"response_format":{"type":"json_schema","json_schema":{"schema":{}}})"),
       "json_schema.name' must be a string", "response_format.json_schema.name"},
      {with_user(R"(,"tools":{})"), "'tools' must be an array", "tools"},
      {with_user(R"(,"tools":[{"type":"code_interpreter"}])"), "tools[0].type must be \"function\"", "tools[0].type"},
      {with_user(R"(,"tools":[{"type":"function","function":{"name":"has space"}}])"), "tools[0].function.name must match",
       "tools[0].function.name"},
      {with_user(R"(,"tools":[{"type":"function","function":{"name":"f","parameters":[]}}])"),
       "tools[0].function.parameters must be a JSON Schema object", "tools[0].function.parameters"},
      {with_user(R"(,"tool_choice":"auto")"), "only allowed when 'tools' are given", "tool_choice"},
      {with_user(R"(,"tools":[)" + kTool + R"(],"tool_choice":"always")"), "'tool_choice' must be none, auto, required",
       "tool_choice"},
      {with_user(R"(,"tools":[)" + kTool + R"(],"tool_choice":{"type":"function","function":{"name":"land"}})"),
       "names function 'land', which is not among 'tools'", "tool_choice"},
      {with_user(R"(,"tools":[)" + kTool + R"(],"parallel_tool_calls":"yes")"), "'parallel_tool_calls' must be a boolean",
       "parallel_tool_calls"},
  };
  for (const auto& c : cases) {
    const auto r = s.post(c.body);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400) << c.body;
    EXPECT_NE(error_message(r).find(c.expected), std::string::npos) << c.body << " -> " << r->body;
    const json error = json::parse(r->body)["error"];
    EXPECT_EQ(error["type"], "invalid_request_error") << c.body;
    EXPECT_EQ(error["param"], c.param.empty() ? json() : json(c.param)) << c.body;
    EXPECT_TRUE(error["code"].is_string() || error["code"].is_null()) << c.body;
  }
  EXPECT_EQ(s.server->stats().bad_requests, cases.size());
  EXPECT_EQ(s.server->stats().answered, 0u);
  // Content as text parts, a null assistant content and assistant tool calls are valid.
  const auto parts = s.post(
      R"({"model":"m","messages":[{"role":"assistant","content":null},{"role":"user","content":[{"type":"text","text":"hi"}]},)"
      R"({"role":"assistant","content":null,"tool_calls":[{"id":"c1","type":"function","function":{"name":"f","arguments":"{}"}}]},)"
      R"({"role":"tool","tool_call_id":"c1","content":"done"}]})");
  EXPECT_EQ(parts->status, 200) << parts->body;
}

TEST(ModelServer, ResponderRefusalsAre400AndFailuresAre500) {
  Served s({}, std::make_unique<RecordedLatencyResponder>(0.0));
  const auto refused = s.post(R"({"model":"m","messages":[{"role":"user","content":"refuse"}]})");
  EXPECT_EQ(refused->status, 400);
  EXPECT_EQ(error_message(refused), "this request cannot be answered");
  const auto crashed = s.post(R"({"model":"m","messages":[{"role":"user","content":"crash"}]})");
  EXPECT_EQ(crashed->status, 500);
  EXPECT_NE(error_message(crashed).find("disk on fire"), std::string::npos);
  EXPECT_EQ(s.server->stats().responder_errors, 1u);
}

TEST(ModelServer, ListsModelsAndAnswersUnknownRoutesWithAJsonError) {
  ms::ModelServerOptions o;
  o.model_ids = {"openai/gpt-4.1-mini", "local/scripted"};
  Served s(o);
  auto c = s.client();
  const auto models = c.Get("/v1/models");
  ASSERT_TRUE(models);
  ASSERT_EQ(models->status, 200);
  const json body = json::parse(models->body);
  EXPECT_EQ(body["object"], "list");
  ASSERT_EQ(body["data"].size(), 2u);
  EXPECT_EQ(body["data"][0]["id"], "openai/gpt-4.1-mini");
  EXPECT_EQ(body["data"][1]["object"], "model");

  const auto missing = c.Get("/v1/completions");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
  EXPECT_NE(error_message(missing).find("no route for GET /v1/completions"), std::string::npos) << missing->body;

  Served plain({});
  const auto default_models = plain.client().Get("/v1/models");
  EXPECT_EQ(json::parse(default_models->body)["data"][0]["id"], "reply-file");
}

TEST(ModelServer, RefusesAForeignHostOrOriginWith403InTheOpenAiShape) {
  Served s({});
  const std::string port = std::to_string(s.server->port());
  const auto rebound = s.post(kGoodRequest, {{"Host", "attacker.example:" + port}});
  ASSERT_TRUE(rebound);
  EXPECT_EQ(rebound->status, 403);
  EXPECT_NE(error_message(rebound).find("attacker.example"), std::string::npos) << rebound->body;
  EXPECT_EQ(json::parse(rebound->body)["error"]["type"], "permission_error");
  const auto page = s.post(kGoodRequest, {{"Origin", "https://attacker.example"}});
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 403);
  EXPECT_NE(error_message(page).find("--allow-origin"), std::string::npos) << page->body;
  const auto own_page = s.post(kGoodRequest, {{"Origin", "http://127.0.0.1:" + port}});
  ASSERT_TRUE(own_page);
  EXPECT_EQ(own_page->status, 200) << own_page->body;
  EXPECT_EQ(s.post(kGoodRequest, {{"Host", "localhost:" + port}})->status, 200);
  EXPECT_EQ(s.server->stats().bad_requests, 2u);
}

TEST(ModelServer, AnOriginGivenWithAllowOriginGetsCorsHeaders) {
  ms::ModelServerOptions o;
  o.http_origins.allowed_origins = {"http://localhost:5173"};
  Served s(o);
  auto c = s.client();
  const auto preflight =
      c.Options("/v1/chat/completions", {{"Origin", "http://localhost:5173"}, {"Access-Control-Request-Method", "POST"}});
  ASSERT_TRUE(preflight);
  EXPECT_EQ(preflight->status, 204);
  EXPECT_NE(preflight->get_header_value("Access-Control-Allow-Headers").find("Authorization"), std::string::npos);
  const auto answered = s.post(kGoodRequest, {{"Origin", "http://localhost:5173"}});
  ASSERT_TRUE(answered);
  EXPECT_EQ(answered->status, 200);
  EXPECT_EQ(answered->get_header_value("Access-Control-Allow-Origin"), "http://localhost:5173");
  const auto other = s.post(kGoodRequest, {{"Origin", "http://localhost:5174"}});
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 403);
  EXPECT_FALSE(other->has_header("Access-Control-Allow-Origin"));
}

TEST(ModelServer, AppliesAFixedLatency) {
  ms::ModelServerOptions o;
  o.latency = "fixed:0.3";
  Served s(o);
  const auto t0 = SteadyClock::now();
  const auto r = s.post(kGoodRequest);
  const double took_s = seconds_since(t0);
  ASSERT_EQ(r->status, 200);
  EXPECT_GE(took_s, 0.3);
  EXPECT_DOUBLE_EQ(s.server->stats().latency_applied_s, 0.3);
}

TEST(ModelServer, TimeScaleScalesTheRecordedLatency) {
  ms::ModelServerOptions o;
  o.latency = "recorded";
  o.time_scale = 0.1;
  Served s(o, std::make_unique<RecordedLatencyResponder>(4.0));
  const auto t0 = SteadyClock::now();
  const auto r = s.post(kGoodRequest);
  const double took_s = seconds_since(t0);
  ASSERT_EQ(r->status, 200);
  EXPECT_GE(took_s, 0.4);
  EXPECT_LT(took_s, 3.5);  // not the unscaled 4 s
  EXPECT_DOUBLE_EQ(s.server->stats().latency_applied_s, 0.4);
  // The responder's usage goes out as it gave it.
  const json usage = json::parse(r->body)["usage"];
  EXPECT_EQ(usage["prompt_tokens"], 100);
  EXPECT_EQ(usage["cost"], 0.5);
}

TEST(ModelServer, ModelLatencyUsesTheProfilesMean) {
  ms::ModelServerOptions o;
  o.latency = "model:ChatGPT-4o";
  o.time_scale = 0.001;  // the profile's seconds become milliseconds
  o.seed = 3;
  Served s(o);
  const int n = 40;
  for (int i = 0; i < n; ++i) ASSERT_EQ(s.post(kGoodRequest)->status, 200);
  const double expected_mean_s = *s.server->latency_model().mean_s();
  EXPECT_NEAR(expected_mean_s, 10.58 / 6.0 * 0.001, 1e-9);
  // Lognormal, sigma 0.5: the mean of 40 draws is within 25 % of the profile's mean.
  EXPECT_NEAR(s.server->stats().latency_applied_s / n, expected_mean_s, 0.25 * expected_mean_s);
}

TEST(ModelServer, FailRateOneFailsEveryRequestWith429AndRetryAfter) {
  ms::ModelServerOptions o;
  o.fail_rate = 1.0;
  o.retry_after_s = 3.0;
  Served s(o);
  for (int i = 0; i < 3; ++i) {
    const auto r = s.post(kGoodRequest);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 429);
    EXPECT_EQ(r->get_header_value("Retry-After"), "3");
    EXPECT_EQ(json::parse(r->body)["error"]["type"], "rate_limit_error");
  }
  EXPECT_EQ(s.server->stats().injected_failures, 3u);
}

TEST(ModelServer, FailFirstFailsOnlyTheFirstRequestsWithTheChosenStatus) {
  ms::ModelServerOptions o;
  o.fail_first = 2;
  o.fail_status = 503;
  Served s(o);
  EXPECT_EQ(s.post(kGoodRequest)->status, 503);
  EXPECT_EQ(s.post(kGoodRequest)->status, 503);
  EXPECT_EQ(s.post(kGoodRequest)->status, 200);
}

TEST(ModelServer, FailRateDrawsAreSeeded) {
  auto pattern = [](uint64_t seed) {
    ms::ModelServerOptions o;
    o.fail_rate = 0.5;
    o.seed = seed;
    Served s(o);
    std::string out;
    for (int i = 0; i < 24; ++i) out += s.post(kGoodRequest)->status == 200 ? '.' : 'x';
    return out;
  };
  const std::string a = pattern(11);
  EXPECT_EQ(a, pattern(11));
  EXPECT_NE(a, pattern(12));
  EXPECT_NE(a.find('x'), std::string::npos);
  EXPECT_NE(a.find('.'), std::string::npos);
}

TEST(ModelServer, RejectsBadOptions) {
  auto make = [](ms::ModelServerOptions o) {
    return ms::ModelServer(std::make_unique<ms::ReplyFileResponder>(std::vector<std::string>{"x"}), o);
  };
  ms::ModelServerOptions o;
  o.fail_status = 404;
  EXPECT_THROW(make(o), std::invalid_argument);
  o = {};
  o.fail_rate = 1.5;
  EXPECT_THROW(make(o), std::invalid_argument);
  o = {};
  o.latency = "soon";
  EXPECT_THROW(make(o), std::invalid_argument);
  o = {};
  o.require_key_env = "A3_TEST_KEY_THAT_IS_NOT_SET";
  ::unsetenv("A3_TEST_KEY_THAT_IS_NOT_SET");
  EXPECT_THROW(make(o), std::invalid_argument);
}

TEST(ModelServer, CannotListenOnAPortInUse) {
  Served first({});
  ms::ModelServerOptions o;
  o.port = first.server->port();
  o.quiet = true;
  ms::ModelServer second(std::make_unique<ms::ReplyFileResponder>(std::vector<std::string>{"x"}), o);
  EXPECT_THROW(second.start(), std::runtime_error);
}

TEST(ModelServer, RequiredKeyIs401WithoutAnd200With) {
  const std::string key = "serve-model-test-key-5b1e";
  ::setenv("A3_TEST_SERVE_KEY", key.c_str(), 1);
  ms::ModelServerOptions o;
  o.require_key_env = "A3_TEST_SERVE_KEY";
  Served s(o);
  const auto none = s.post(kGoodRequest);
  EXPECT_EQ(none->status, 401);
  EXPECT_EQ(json::parse(none->body)["error"]["type"], "authentication_error");
  EXPECT_EQ(none->body.find(key), std::string::npos);
  EXPECT_EQ(s.post(kGoodRequest, {{"Authorization", "Bearer wrong"}})->status, 401);
  EXPECT_EQ(s.post(kGoodRequest, {{"Authorization", key}})->status, 401);  // no "Bearer "
  EXPECT_EQ(s.post(kGoodRequest, {{"Authorization", "Bearer " + key}})->status, 200);
  EXPECT_EQ(s.client().Get("/v1/models")->status, 401);
  EXPECT_EQ(s.server->stats().unauthorized, 4u);
  ::unsetenv("A3_TEST_SERVE_KEY");
}

TEST(ModelServer, TheKeyIsNeverLogged) {
  const std::string key = "serve-model-logged-key-77aa";
  ::setenv("A3_TEST_SERVE_KEY2", key.c_str(), 1);
  ms::ModelServerOptions o;
  o.require_key_env = "A3_TEST_SERVE_KEY2";
  o.port = 0;
  std::vector<std::string> lines;
  std::mutex m;
  ms::ModelServer server(std::make_unique<ms::ReplyFileResponder>(std::vector<std::string>{"x"}), o,
                         [&](const std::string& line) {
                           std::lock_guard<std::mutex> lock(m);
                           lines.push_back(line);
                         });
  server.start();
  httplib::Client c("127.0.0.1", server.port());
  c.Post("/v1/chat/completions", {{"Authorization", "Bearer " + key}}, kGoodRequest, "application/json");
  c.Post("/v1/chat/completions", {{"Authorization", "Bearer " + key + "x"}}, kGoodRequest, "application/json");
  server.stop();
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[0].find("200 model=m prompt_chars=11 latency=0.000s tokens=3+1"), std::string::npos) << lines[0];
  EXPECT_NE(lines[1].find("401"), std::string::npos) << lines[1];
  for (const auto& line : lines) EXPECT_EQ(line.find(key), std::string::npos) << line;
  ::unsetenv("A3_TEST_SERVE_KEY2");
}

TEST(ModelServer, AnswersSeveralClientsAtOnce) {
  ms::ModelServerOptions o;
  o.latency = "fixed:0.5";
  Served s(o);
  const int clients = 6;
  const auto t0 = SteadyClock::now();
  std::vector<std::future<int>> statuses;
  for (int i = 0; i < clients; ++i) {
    statuses.push_back(std::async(std::launch::async, [&] {
      const auto r = s.post(kGoodRequest);
      return r ? r->status : -1;
    }));
  }
  for (auto& f : statuses) EXPECT_EQ(f.get(), 200);
  // One after another would take 3 s.
  EXPECT_LT(seconds_since(t0), 2.5);
  EXPECT_EQ(s.server->stats().answered, static_cast<uint64_t>(clients));
}

TEST(ModelServer, MaxConcurrencyRefusesTheRequestBeyondTheLimit) {
  ms::ModelServerOptions o;
  o.latency = "fixed:1";
  o.max_concurrency = 1;
  Served s(o);
  auto first = std::async(std::launch::async, [&] { return s.post(kGoodRequest)->status; });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the first is waiting out its latency
  const auto second = s.post(kGoodRequest);
  EXPECT_EQ(second->status, 429);
  EXPECT_EQ(second->get_header_value("Retry-After"), "1");
  EXPECT_NE(error_message(second).find("--max-concurrency"), std::string::npos);
  EXPECT_EQ(first.get(), 200);
  EXPECT_EQ(s.post(kGoodRequest)->status, 200);  // free again
  EXPECT_EQ(s.server->stats().refused_busy, 1u);
}

TEST(ModelServer, StopCutsALatencyWaitShort) {
  ms::ModelServerOptions o;
  o.latency = "fixed:60";
  Served s(o);
  auto pending = std::async(std::launch::async, [&] {
    const auto r = s.post(kGoodRequest);
    return r ? r->status : -1;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const auto t0 = SteadyClock::now();
  s.server->stop();
  EXPECT_LT(seconds_since(t0), 20.0);
  EXPECT_EQ(pending.get(), 503);
}

// ---- the LLM client against the server ----

llm::LlmEndpoint endpoint_of(const ms::ModelServer& server) {
  llm::LlmEndpoint e;
  e.base_url = server.base_url();
  e.model = "local/test";
  e.total_timeout_s = 20.0;
  e.max_retries = 3;
  return e;
}

TEST(ModelServerWithClient, ClientRetriesAnInjected429ThenSucceeds) {
  ms::ModelServerOptions o;
  o.fail_first = 1;
  o.retry_after_s = 1.0;
  Served s(o);
  llm::LlmClient client(endpoint_of(*s.server));
  std::vector<double> sleeps;
  client.set_sleep_for_tests([&](double sec) { sleeps.push_back(sec); });
  const llm::LlmCallResult r = client.chat(std::vector<llm::ChatMessage>{{"system", "You fly drones."}, {"user", "Status?"}});
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.content, R"({"intent":"hold"})");
  EXPECT_EQ(r.http_attempts, 2);
  EXPECT_EQ(r.attempts[0].http_status, 429);
  EXPECT_EQ(sleeps, std::vector<double>({1.0}));
  EXPECT_EQ(r.model, "local/test");
  EXPECT_EQ(r.usage.prompt_tokens, 6);  // 22 characters
  EXPECT_EQ(r.usage.completion_tokens, 5);
  EXPECT_EQ(r.usage.total_tokens, 11);
  EXPECT_EQ(r.finish_reason, "stop");
}

TEST(ModelServerWithClient, ClientGivesUpWhenTheServerKeepsFailing) {
  ms::ModelServerOptions o;
  o.fail_rate = 1.0;
  o.fail_status = 503;
  Served s(o);
  llm::LlmEndpoint e = endpoint_of(*s.server);
  e.max_retries = 2;
  llm::LlmClient client(e);
  client.set_sleep_for_tests([](double) {});
  const llm::LlmCallResult r = client.chat(std::vector<llm::ChatMessage>{{"user", "x"}});
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.http_attempts, 3);
  EXPECT_NE(r.error.find("HTTP 503: injected failure"), std::string::npos) << r.error;
}

TEST(ModelServerWithClient, ClientSeesTheLatencyAndSendsTheKey) {
  const std::string key = "client-server-key-31337";
  ::setenv("A3_TEST_SERVE_KEY3", key.c_str(), 1);
  ms::ModelServerOptions o;
  o.require_key_env = "A3_TEST_SERVE_KEY3";
  o.latency = "fixed:0.25";
  Served s(o);
  llm::LlmEndpoint e = endpoint_of(*s.server);
  llm::LlmClient without_key(e);
  const llm::LlmCallResult refused = without_key.chat(std::vector<llm::ChatMessage>{{"user", "x"}});
  EXPECT_FALSE(refused.ok);
  EXPECT_EQ(refused.http_status, 401);
  e.api_key = key;
  llm::LlmClient client(e);
  const llm::LlmCallResult r = client.chat(std::vector<llm::ChatMessage>{{"user", "x"}});
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_GE(r.wall_time_s, 0.25);
  ::unsetenv("A3_TEST_SERVE_KEY3");
}

}  // namespace
