// The OpenAI-compatible HTTP server behind `a3rig serve-model` (cpp-httplib): POST
// /v1/chat/completions answered by a ModelResponder after a latency drawn from a LatencyModel,
// GET /v1/models and GET /v1/models/{id}. Requests are validated (chat_request.hpp: 400 naming
// the field; request_body.hpp: 415 for bodies that are not JSON), optionally authenticated
// (401), and may be failed on purpose (fault injection for testing clients: a fail rate, the
// first N requests, a concurrency limit), with Retry-After. Every error is OpenAI's error object
// (openai_error.hpp). The reply honours n (the responder is asked once per choice), tools /
// tool_choice and response_format (reply_shaping.hpp), and stream: true (server-sent events of
// chat.completion.chunk objects, completion_json.hpp, then "data: [DONE]"). Streaming latency:
// the latency model's draw is the total time; the first chunk (the headers and the role delta)
// comes after kFirstChunkShare of it, and the remaining chunks are spread evenly over the rest,
// the last one at the full draw. stop() ends waiting answers and streams at once.
// Each connection is served on a thread of its own, up to options.http_limits.max_connections (503
// beyond); a request's head and body must arrive within their deadlines (408), its body must come
// with a Content-Length (411; 400 malformed; 413 too large), its Host must be this server's and
// its Origin, if any, this server's or one in options.http_origins (403): agent/http/guarded_server.hpp. The
// responder is called under a lock (responders need not be thread-safe), the latency waits are not.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "agent/http/http_limits.hpp"
#include "agent/http/origin_policy.hpp"
#include "agent/model_server/latency_model.hpp"
#include "agent/model_server/model_responder.hpp"
#include "common/rng.hpp"

#include "agent/model_server/chat_request.hpp"
#include "agent/model_server/completion_json.hpp"
#include "agent/model_server/openai_error.hpp"

namespace httplib {
class ContentReader;
struct Request;
struct Response;
}  // namespace httplib

namespace a3::agent::http {
class GuardedServer;
}  // namespace a3::agent::http

namespace a3::agent::model_server {

struct ModelServerOptions {
  std::string host = "127.0.0.1";
  int port = 8088;                   // 0: any free port (ModelServer::port() says which)
  std::string latency = "recorded";  // see latency_model.hpp
  double time_scale = 1.0;           // multiplies every latency
  uint64_t seed = 42;                // latency draws and the fail-rate's draws
  double fail_rate = 0.0;            // probability that a chat request fails on purpose
  int fail_first = 0;                // the first N chat requests fail on purpose
  int fail_status = 429;             // status of those failures: 429, 500, 502, 503 or 504
  double retry_after_s = 1.0;        // Retry-After sent with them and with busy refusals (0: none)
  int max_concurrency = 0;           // chat requests answered at once; beyond: 429 (0: no limit)
  std::string require_key_env;       // an environment variable holding the key clients must send
  std::vector<std::string> model_ids;  // GET /v1/models lists these (default: the responder's name)
  http::HttpLimits http_limits;      // connections at once (a thread each), head and body deadlines
  http::OriginPolicy http_origins;   // browser pages allowed besides the server's own; more host names
  bool quiet = false;                // no line per request
  std::size_t max_request_bytes = 32u << 20;
};

struct ModelServerStats {
  uint64_t requests = 0;           // every HTTP request
  uint64_t answered = 0;           // chat completions answered with 200
  uint64_t bad_requests = 0;       // 400, 404, 408, 411, 413, 415
  uint64_t unauthorized = 0;       // 401
  uint64_t injected_failures = 0;  // --fail-rate / --fail-first
  uint64_t refused_busy = 0;       // --max-concurrency (429), --max-connections (503)
  uint64_t responder_errors = 0;   // 500: the responder failed
  double latency_applied_s = 0.0;  // sum over answered requests
  int64_t prompt_tokens = 0;
  int64_t completion_tokens = 0;
};

// Tokens estimated from characters, ~4 characters per token (what OpenAI's tokenizers average on
// English text), rounded up: for replies whose responder does not count tokens.
int64_t estimate_tokens(std::size_t characters);
// Characters (UTF-8 code points) of a chat-completions request's prompt: every message's content
// and tool calls, and the `tools` definitions (as JSON text).
std::size_t prompt_characters(const nlohmann::json& request);

// Share of the latency before a stream's first chunk (the rest spreads the other chunks).
constexpr double kFirstChunkShare = 0.5;

class ModelServer {
 public:
  using LogLine = std::function<void(const std::string&)>;

  // Throws std::invalid_argument for bad options (latency spec, fail status, rates, a key
  // variable that is not set). `log` gets the per-request lines (default: stderr).
  ModelServer(std::unique_ptr<ModelResponder> responder, ModelServerOptions options, LogLine log = {});
  ~ModelServer();
  ModelServer(const ModelServer&) = delete;
  ModelServer& operator=(const ModelServer&) = delete;

  // Binds and serves from a thread of its own. Throws std::runtime_error when the address
  // cannot be bound.
  void start();
  // Stops listening; requests waiting out their latency are answered 503 at once. Idempotent.
  void stop();

  int port() const { return port_; }
  std::string base_url() const;  // http://HOST:PORT/v1
  ModelServerStats stats() const;
  const LatencyModel& latency_model() const { return latency_; }
  const std::string& responder_name() const { return responder_name_; }

 private:
  void handle_chat(const httplib::Request& req, httplib::Response& res, const httplib::ContentReader& reader);
  void handle_models(httplib::Response& res);
  void handle_model(const httplib::Request& req, httplib::Response& res);
  // The OpenAI error for a request refused before its route (408, 411, 400, 413, 503).
  void send_refusal(const httplib::Request& req, httplib::Response& res, const http::HttpRefusal& refusal);
  // The OpenAI error for what httplib answered on its own (404 no route, 400 unreadable).
  void send_unrouted(const httplib::Request& req, httplib::Response& res);
  // The bearer key of the request being handled on this thread, checked on its exact bytes.
  bool authorized() const;
  // The 401 / 413 / 415 / 400 that refuses the request, else nothing (`request` is filled).
  std::optional<ApiError> admit_chat(const httplib::Request& req, const httplib::ContentReader& reader,
                                     nlohmann::json& request);
  // Numbers the chat request (`index`) and draws whether it fails on purpose.
  std::optional<ApiError> injected_failure(uint64_t& index);
  // A chat request on its way: what was asked, the replies, when it came.
  struct ChatAnswer {
    nlohmann::json request;
    ChatOptions options;
    uint64_t index = 0;
    std::vector<ResponderReply> choices;
    nlohmann::json usage;
    std::chrono::steady_clock::time_point started;
  };
  // Busy, refused (admit_chat) or failed on purpose: answered with the error, false.
  bool admitted(const httplib::Request& req, httplib::Response& res, const httplib::ContentReader& reader,
                int in_flight, nlohmann::json& request, uint64_t& index);
  // answer(), its exceptions answered as 400 / 500: false.
  bool answered(const nlohmann::json& request, const ChatOptions& options, uint64_t index, httplib::Response& res,
                std::vector<ResponderReply>& choices, nlohmann::json& usage);
  // Waits out the latency (the first share of it for a stream) and sends the answer.
  void deliver(const ChatAnswer& answer, httplib::Response& res);
  void record_answer(const ChatAnswer& answer, double latency_s);
  // One reply per choice, shaped to the options, with the usage of them all in `usage`.
  std::vector<ResponderReply> answer(const nlohmann::json& request, const ChatOptions& options, uint64_t index,
                                     nlohmann::json& usage);
  // Answers `error`, counts the request (and `counter`), logs "<what> <status> <message>".
  void send_error(httplib::Response& res, const ApiError& error, double retry_after_s, const std::string& what,
                  uint64_t ModelServerStats::*counter = nullptr);
  // Sets the chunked provider that sends `chunks` as events, `gap_s` apart, then [DONE].
  void send_stream(httplib::Response& res, std::vector<nlohmann::json> chunks, double gap_s);
  bool wait_or_stop(double seconds);  // false when stopping
  void log(const std::string& line);

  std::unique_ptr<ModelResponder> responder_;
  std::string responder_name_;
  ModelServerOptions options_;
  LatencyModel latency_;
  LogLine log_;
  std::string required_key_;
  std::unique_ptr<http::GuardedServer> http_;
  std::thread thread_;
  int port_ = 0;

  std::mutex responder_mutex_;
  mutable std::mutex mutex_;  // stats, the random streams, the request counter
  ModelServerStats stats_;
  common::Rng latency_rng_;
  common::Rng fault_rng_;
  uint64_t chat_requests_ = 0;
  std::atomic<int> in_flight_{0};

  std::mutex stop_mutex_;
  std::condition_variable stop_cv_;
  bool stopping_ = false;
  std::mutex log_mutex_;
};

}  // namespace a3::agent::model_server
