// ModelServer as an OpenAI-compatible server over HTTP: the error object everywhere (string or
// null code, param), bodies that are not JSON, GET /v1/models/{id}, n, response_format,
// tools / tool_choice with a responder that knows nothing of tools, and stream: true (events,
// pieces, tool call deltas, usage, the latency split, stop ending a stream).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <future>
#include <mutex>
#include <thread>

#include "agent/model_server/model_server.hpp"
#include "agent/model_server/reply_file_responder.hpp"
#include "agent/model_server/schema_instance.hpp"

// After the project headers: httplib pulls in <resolv.h>, whose _res macro breaks Eigen.
#include <httplib.h>

namespace {

namespace ms = a3::agent::model_server;
using nlohmann::json;
using SteadyClock = std::chrono::steady_clock;

struct Served {
  explicit Served(ms::ModelServerOptions o = {}, std::vector<std::string> replies = {"plain words"}) {
    o.host = "127.0.0.1";
    o.port = 0;
    o.quiet = true;
    server = std::make_unique<ms::ModelServer>(std::make_unique<ms::ReplyFileResponder>(replies), o);
    server->start();
  }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", server->port());
    c.set_read_timeout(30, 0);
    return c;
  }
  httplib::Result post(const json& body, const std::string& content_type = "application/json") const {
    auto c = client();
    return c.Post("/v1/chat/completions", body.dump(), content_type.c_str());
  }
  std::unique_ptr<ms::ModelServer> server;
};

json chat(json extra = json::object()) {
  json body = {{"model", "m"}, {"messages", {{{"role", "user"}, {"content", "hello"}}}}};
  body.update(extra);
  return body;
}

json tool(const std::string& name, const json& parameters) {
  return {{"type", "function"}, {"function", {{"name", name}, {"parameters", parameters}}}};
}

const json kAltitudeSchema = json::parse(R"({"type":"object","properties":{
  "altitude_m":{"type":"number","minimum":5,"maximum":120},"mode":{"type":"string","enum":["gentle","fast"]},
  "tags":{"type":"array","items":{"type":"string"},"minItems":2}},"required":["altitude_m","mode","tags"]})");

// The events of a text/event-stream body: the JSON of every "data:" line, and whether [DONE] ended it.
std::vector<json> events_of(const std::string& body, bool& done) {
  std::vector<json> out;
  done = false;
  std::size_t start = 0;
  while (start < body.size()) {
    const std::size_t end = body.find("\n\n", start);
    const std::string event = body.substr(start, end == std::string::npos ? std::string::npos : end - start);
    start = end == std::string::npos ? body.size() : end + 2;
    if (event.rfind("data: ", 0) != 0) continue;
    const std::string data = event.substr(6);
    if (data == "[DONE]") {
      done = true;
    } else {
      out.push_back(json::parse(data));
    }
  }
  return out;
}

TEST(OpenAiCompat, EveryErrorHasTheOpenAiShapeWithAStringOrNullCode) {
  ::setenv("A3_COMPAT_TEST_KEY", "sekrit", 1);
  ms::ModelServerOptions o;
  o.require_key_env = "A3_COMPAT_TEST_KEY";
  o.fail_first = 1;
  o.fail_status = 503;
  Served s(o);
  auto c = s.client();
  const auto unauthorized = c.Post("/v1/chat/completions", chat().dump(), "application/json");
  c.set_bearer_token_auth("sekrit");
  const auto injected = c.Post("/v1/chat/completions", chat().dump(), "application/json");
  const auto bad = c.Post("/v1/chat/completions", chat({{"n", 20}}).dump(), "application/json");
  const auto missing = c.Get("/v1/models/no-such-model");
  const auto no_route = c.Get("/v1/engines");
  struct Expect {
    const httplib::Result& r;
    int status;
    const char* type;
    json param, code;
  };
  for (const auto& e : std::vector<Expect>{
           {unauthorized, 401, "authentication_error", nullptr, "invalid_api_key"},
           {injected, 503, "server_error", nullptr, nullptr},
           {bad, 400, "invalid_request_error", "n", "invalid_value"},
           {missing, 404, "invalid_request_error", "model", "model_not_found"},
           {no_route, 404, "invalid_request_error", nullptr, nullptr},
       }) {
    ASSERT_TRUE(e.r);
    EXPECT_EQ(e.r->status, e.status) << e.r->body;
    const json body = json::parse(e.r->body);
    ASSERT_TRUE(body["error"].is_object()) << e.r->body;
    const json& error = body["error"];
    EXPECT_TRUE(error["message"].is_string() && !error["message"].get<std::string>().empty());
    EXPECT_EQ(error["type"], e.type) << e.r->body;
    EXPECT_EQ(error["param"], e.param) << e.r->body;
    EXPECT_EQ(error["code"], e.code) << e.r->body;
    EXPECT_TRUE(error.contains("param") && error.contains("code"));
  }
}

TEST(OpenAiCompat, BusyRefusalsAreRateLimitErrorsWithTheirCode) {
  ms::ModelServerOptions o;
  o.fail_first = 1;
  o.fail_status = 429;
  o.retry_after_s = 2.0;
  Served s(o);
  const auto r = s.post(chat());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 429);
  EXPECT_EQ(r->get_header_value("Retry-After"), "2");
  EXPECT_EQ(json::parse(r->body)["error"]["code"], "rate_limit_exceeded");
}

TEST(OpenAiCompat, BodiesThatAreNotJsonGet415SayingTheBodyMustBeJson) {
  Served s;
  auto c = s.client();
  const std::string form = "model=m&messages=" + std::string(9000, 'x');
  const auto form_r = c.Post("/v1/chat/completions", form, "application/x-www-form-urlencoded");
  ASSERT_TRUE(form_r);
  EXPECT_EQ(form_r->status, 415) << form_r->body;
  const std::string message = json::parse(form_r->body)["error"]["message"];
  EXPECT_NE(message.find("must be application/json"), std::string::npos) << message;
  EXPECT_EQ(message.find("larger than"), std::string::npos) << message;
  EXPECT_EQ(json::parse(form_r->body)["error"]["code"], "unsupported_media_type");

  auto c2 = s.client();
  const auto multipart = c2.Post("/v1/chat/completions", httplib::MultipartFormDataItems{{"model", "m", "", ""}});
  ASSERT_TRUE(multipart);
  EXPECT_EQ(multipart->status, 415) << multipart->body;

  const auto text = s.client().Post("/v1/chat/completions", "hello model", "text/plain");
  ASSERT_TRUE(text);
  EXPECT_EQ(text->status, 415) << text->body;
  EXPECT_NE(text->body.find("must be application/json"), std::string::npos);

  // JSON under another or no media type, and application/json with parameters, are taken.
  EXPECT_EQ(s.post(chat(), "text/plain")->status, 200);
  EXPECT_EQ(s.post(chat(), "application/json; charset=utf-8")->status, 200);
  EXPECT_EQ(s.post(chat(), "Application/JSON;charset=UTF-8")->status, 200);
  EXPECT_EQ(s.post(chat(), "")->status, 200);
  // A JSON media type whose body does not parse is a 400, not a 415.
  const auto broken = s.client().Post("/v1/chat/completions", "{\"model\":", "application/json");
  EXPECT_EQ(broken->status, 400);
  EXPECT_EQ(s.server->stats().bad_requests, 4u);
}

TEST(OpenAiCompat, ABodyOverTheLimitIs413NamingTheLimit) {
  ms::ModelServerOptions o;
  o.max_request_bytes = 1000;
  Served s(o);
  const auto r = s.post(chat({{"messages", {{{"role", "user"}, {"content", std::string(5000, 'x')}}}}}));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 413);
  const json error = json::parse(r->body)["error"];
  EXPECT_NE(error["message"].get<std::string>().find("larger than 1000 bytes"), std::string::npos) << r->body;
  EXPECT_EQ(error["code"], "request_too_large");
}

TEST(OpenAiCompat, RetrievesAModelByIdAndRefusesUnknownIds) {
  ms::ModelServerOptions o;
  o.model_ids = {"scripted", "openai/gpt-4.1-mini"};
  Served s(o);
  auto c = s.client();
  const auto r = c.Get("/v1/models/openai/gpt-4.1-mini");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(json::parse(r->body), json({{"id", "openai/gpt-4.1-mini"}, {"object", "model"}, {"created", 0},
                                        {"owned_by", "a3rig"}}));
  const auto unknown = c.Get("/v1/models/gpt-5");
  EXPECT_EQ(unknown->status, 404);
  EXPECT_NE(unknown->body.find("'gpt-5' does not exist"), std::string::npos) << unknown->body;
}

TEST(OpenAiCompat, NChoicesAreAnsweredWithTheirIndexes) {
  Served s({}, {"first", "second", "third"});
  const auto r = s.post(chat({{"n", 3}}));
  ASSERT_EQ(r->status, 200) << r->body;
  const json body = json::parse(r->body);
  ASSERT_EQ(body["choices"].size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(body["choices"][i]["index"], i);
    EXPECT_EQ(body["choices"][i]["finish_reason"], "stop");
  }
  EXPECT_EQ(body["choices"][0]["message"]["content"], "first");
  EXPECT_EQ(body["choices"][2]["message"]["content"], "third");
  EXPECT_EQ(body["usage"]["completion_tokens"], 2 + 2 + 2);  // ~4 characters a token, each
}

TEST(OpenAiCompat, JsonObjectFormatWrapsContentThatIsNotAnObject) {
  Served s({}, {"plain words", R"({"already":"an object"})"});
  const auto wrapped = s.post(chat({{"response_format", {{"type", "json_object"}}}}));
  ASSERT_EQ(wrapped->status, 200) << wrapped->body;
  const std::string content = json::parse(wrapped->body)["choices"][0]["message"]["content"];
  EXPECT_EQ(json::parse(content), json({{"text", "plain words"}}));
  const auto kept = s.post(chat({{"response_format", {{"type", "json_object"}}}}));
  EXPECT_EQ(json::parse(kept->body)["choices"][0]["message"]["content"], R"({"already":"an object"})");
  const auto text = s.post(chat({{"response_format", {{"type", "text"}}}}));
  EXPECT_EQ(json::parse(text->body)["choices"][0]["message"]["content"], "plain words");
}

TEST(OpenAiCompat, JsonSchemaFormatKeepsConformingContentAndGeneratesTheRest) {
  const json schema = json::parse(R"({"type":"object","properties":{"intent":{"type":"string"}},"required":["intent"]})");
  const json format = {{"type", "json_schema"}, {"json_schema", {{"name", "turn"}, {"schema", schema}, {"strict", true}}}};
  Served s({}, {R"({"intent":"hold"})", "plain words"});
  const auto kept = s.post(chat({{"response_format", format}}));
  ASSERT_EQ(kept->status, 200) << kept->body;
  EXPECT_EQ(json::parse(kept->body)["choices"][0]["message"]["content"], R"({"intent":"hold"})");
  const auto generated = s.post(chat({{"response_format", format}}));
  const json content = json::parse(json::parse(generated->body)["choices"][0]["message"]["content"].get<std::string>());
  EXPECT_EQ(ms::schema_problems(schema, content), "") << content;
  EXPECT_TRUE(content["intent"].is_string());
}

TEST(OpenAiCompat, ToolChoiceRequiredGetsACallWithArgumentsSatisfyingTheSchema) {
  Served s;
  const json tools = json::array({tool("climb", kAltitudeSchema), tool("land", json::object())});
  const auto r = s.post(chat({{"tools", tools}, {"tool_choice", "required"}}));
  ASSERT_EQ(r->status, 200) << r->body;
  const json choice = json::parse(r->body)["choices"][0];
  EXPECT_EQ(choice["finish_reason"], "tool_calls");
  ASSERT_EQ(choice["message"]["tool_calls"].size(), 1u);
  const json call = choice["message"]["tool_calls"][0];
  EXPECT_EQ(call["type"], "function");
  EXPECT_EQ(call["id"].get<std::string>().rfind("call_", 0), 0u) << call;
  EXPECT_EQ(call["function"]["name"], "climb");
  const json args = json::parse(call["function"]["arguments"].get<std::string>());
  EXPECT_EQ(ms::schema_problems(kAltitudeSchema, args), "") << args;

  const auto named = s.post(chat({{"tools", tools}, {"tool_choice", {{"type", "function"}, {"function", {{"name", "land"}}}}}}));
  EXPECT_EQ(json::parse(named->body)["choices"][0]["message"]["tool_calls"][0]["function"]["name"], "land");
  EXPECT_EQ(json::parse(named->body)["choices"][0]["message"]["tool_calls"][0]["function"]["arguments"], "{}");

  // none and auto: this responder has no calls of its own, so plain content.
  for (const char* choice_mode : {"none", "auto"}) {
    const auto plain = s.post(chat({{"tools", tools}, {"tool_choice", choice_mode}}));
    const json message = json::parse(plain->body)["choices"][0]["message"];
    EXPECT_EQ(message["content"], "plain words") << choice_mode;
    EXPECT_FALSE(message.contains("tool_calls")) << choice_mode;
  }
}

TEST(OpenAiCompat, PromptTokensCountTheToolDefinitionsAndEarlierCalls) {
  const json plain = chat();
  json with_tools = chat({{"tools", json::array({tool("climb", kAltitudeSchema)})}});
  EXPECT_EQ(ms::prompt_characters(with_tools), ms::prompt_characters(plain) + with_tools["tools"].dump().size());
  json with_call = plain;
  with_call["messages"].push_back({{"role", "assistant"}, {"content", nullptr},
                                   {"tool_calls", {{{"id", "c"}, {"type", "function"},
                                                    {"function", {{"name", "land"}, {"arguments", "{}"}}}}}}});
  EXPECT_GT(ms::prompt_characters(with_call), ms::prompt_characters(plain) + 20);
}

TEST(OpenAiCompat, StreamSendsRolePiecesFinishReasonUsageAndDone) {
  const std::string reply = "The quick brown drone jumps over the lazy wind turbine, twice.";
  Served s({}, {reply});
  const auto r = s.post(chat({{"stream", true}, {"stream_options", {{"include_usage", true}}}}));
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type").rfind("text/event-stream", 0), 0u);
  bool done = false;
  const auto events = events_of(r->body, done);
  EXPECT_TRUE(done);
  ASSERT_GE(events.size(), 5u);
  EXPECT_EQ(events[0]["object"], "chat.completion.chunk");
  EXPECT_EQ(events[0]["choices"][0]["delta"]["role"], "assistant");
  std::string content;
  int content_chunks = 0;
  for (const auto& e : events) {
    if (e["choices"].empty()) continue;
    const json& d = e["choices"][0]["delta"];
    if (d.contains("content") && !d["content"].get<std::string>().empty()) {
      content += d["content"].get<std::string>();
      ++content_chunks;
    }
  }
  EXPECT_EQ(content, reply);
  EXPECT_GE(content_chunks, 3);
  const json& finish = events[events.size() - 2];
  EXPECT_EQ(finish["choices"][0]["finish_reason"], "stop");
  const json& usage = events.back();
  EXPECT_TRUE(usage["choices"].empty());
  EXPECT_GT(usage["usage"]["total_tokens"].get<int>(), 0);

  const auto without_usage = s.post(chat({{"stream", true}}));
  const auto plain_events = events_of(without_usage->body, done);
  EXPECT_FALSE(plain_events.back()["choices"].empty());
}

TEST(OpenAiCompat, StreamedToolCallsCarryIndexIdNameThenArgumentsInPieces) {
  Served s;
  const auto r = s.post(chat({{"stream", true}, {"tools", json::array({tool("climb", kAltitudeSchema)})},
                              {"tool_choice", "required"}}));
  ASSERT_EQ(r->status, 200) << r->body;
  bool done = false;
  const auto events = events_of(r->body, done);
  std::string name, id, arguments;
  int argument_chunks = 0;
  for (const auto& e : events) {
    const json& d = e["choices"][0]["delta"];
    if (!d.contains("tool_calls")) continue;
    const json& call = d["tool_calls"][0];
    EXPECT_EQ(call["index"], 0);
    if (call.contains("id")) {
      id = call["id"];
      name = call["function"]["name"];
      EXPECT_EQ(call["type"], "function");
    } else {
      arguments += call["function"]["arguments"].get<std::string>();
      ++argument_chunks;
    }
  }
  EXPECT_EQ(name, "climb");
  EXPECT_FALSE(id.empty());
  EXPECT_GE(argument_chunks, 2);
  EXPECT_EQ(ms::schema_problems(kAltitudeSchema, json::parse(arguments)), "") << arguments;
  EXPECT_EQ(events.back()["choices"][0]["finish_reason"], "tool_calls");
}

// Arrival times of the first and last event of a streamed request.
struct StreamTimes {
  double first_s = -1.0, last_s = -1.0;
  std::string body;
};

StreamTimes timed_stream(const Served& s, const std::function<void()>& on_first = {}) {
  StreamTimes t;
  const auto t0 = SteadyClock::now();
  httplib::Request req;
  req.method = "POST";
  req.path = "/v1/chat/completions";
  req.body = chat({{"stream", true}}).dump();
  req.set_header("Content-Type", "application/json");
  req.content_receiver = [&](const char* data, std::size_t n, uint64_t, uint64_t) {
    const double now_s = std::chrono::duration<double>(SteadyClock::now() - t0).count();
    if (t.first_s < 0) {
      t.first_s = now_s;
      if (on_first) on_first();
    }
    t.last_s = now_s;
    t.body.append(data, n);
    return true;
  };
  auto c = s.client();
  c.send(req);
  return t;
}

TEST(OpenAiCompat, StreamLatencyIsTheDrawWithTheFirstChunkAfterHalfOfIt) {
  ms::ModelServerOptions o;
  o.latency = "fixed:1.0";
  Served s(o, {std::string(200, 'a')});
  const StreamTimes t = timed_stream(s);
  EXPECT_GE(t.first_s, 1.0 * ms::kFirstChunkShare - 0.02);
  EXPECT_GE(t.last_s, 0.98);
  EXPECT_GT(t.last_s - t.first_s, 0.3);  // the rest is spread, not sent at once
  bool done = false;
  events_of(t.body, done);
  EXPECT_TRUE(done);
}

TEST(OpenAiCompat, StopEndsAStreamWaitingForItsFirstChunkPromptly) {
  ms::ModelServerOptions o;
  o.latency = "fixed:60";
  Served s(o, {std::string(400, 'a')});
  // The first chunk comes after 30 s: stop while a stream waits for it.
  auto pending = std::async(std::launch::async, [&] { return timed_stream(s); });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const auto t0 = SteadyClock::now();
  s.server->stop();
  ASSERT_EQ(pending.wait_for(std::chrono::seconds(10)), std::future_status::ready);
  EXPECT_LT(std::chrono::duration<double>(SteadyClock::now() - t0).count(), 5.0);
}

TEST(OpenAiCompat, StopEndsAStreamBetweenChunksPromptly) {
  ms::ModelServerOptions o;
  o.latency = "fixed:6";  // a one-character reply: role, content, finish; the first at 3 s, then 1.5 s apart
  Served s(o, {"a"});
  std::promise<void> got_first;
  auto pending = std::async(std::launch::async, [&] { return timed_stream(s, [&] { got_first.set_value(); }); });
  ASSERT_EQ(got_first.get_future().wait_for(std::chrono::seconds(60)), std::future_status::ready);
  const auto t0 = SteadyClock::now();
  s.server->stop();
  ASSERT_EQ(pending.wait_for(std::chrono::seconds(10)), std::future_status::ready);
  EXPECT_LT(std::chrono::duration<double>(SteadyClock::now() - t0).count(), 1.0);
  bool done = true;
  events_of(pending.get().body, done);
  EXPECT_FALSE(done);  // cut, not finished
}

}  // namespace
