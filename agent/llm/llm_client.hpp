// An OpenAI-compatible chat-completions client over libcurl (HTTPS or HTTP): one call is one
// POST {base_url}/chat/completions. Retries with exponential backoff on HTTP 429/5xx and
// network errors, honouring Retry-After; connect and total timeouts; token usage (and cost,
// where the provider reports it) and wall time per call. Requests may carry OpenAI `tools` and
// `tool_choice`; answers may be tool calls (content null). With LlmEndpoint::stream the answer
// comes as server-sent events (stream: true, stream_options.include_usage), assembled as they
// arrive, with the time to the first and to the last token. A parameter the provider refuses
// with a 400/422 naming it (response_format, tool_choice, stream_options dropped; max_tokens
// sent as max_completion_tokens) is adjusted once and remembered for the client's life
// (request_fallbacks.hpp). The API key is sent only in the
// Authorization header: it never appears in errors, logs, or anything this client returns.
#pragma once

#include <nlohmann/json.hpp>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "agent/llm/request_fallbacks.hpp"

namespace a3::agent::llm {

struct LlmEndpoint {
  std::string base_url;     // e.g. https://api.openai.com/v1, http://127.0.0.1:8088/v1
  std::string model;        // e.g. gpt-4.1-mini
  std::string api_key;      // may be empty (local servers); never printed
  double temperature = 0.0;
  int max_tokens = 4096;    // completion cap per call
  bool json_output = true;  // response_format {"type":"json_object"}
  double connect_timeout_s = 10.0;
  double total_timeout_s = 180.0;  // per HTTP attempt
  int max_retries = 4;             // on 429/5xx/network errors, after the first try
  double backoff_initial_s = 1.0;  // doubled per retry, capped; Retry-After overrides
  double backoff_max_s = 30.0;
  std::string provider;            // "openai", "openrouter", ... (for output layout); derived from base_url if empty
  std::size_t max_response_bytes = 16u << 20;  // a longer answer is an error
  bool stream = false;             // stream: true (server-sent events), time to first/last token
};

// Reads A3_LLM_BASE_URL, A3_LLM_MODEL, A3_LLM_PROVIDER (optional), and the key from
// A3_LLM_API_KEY, else the first line of the file named by A3_LLM_API_KEY_FILE, else
// OPENAI_API_KEY (none: no Authorization header). Flags given explicitly override (empty strings
// mean "not given"); the key has no flag, on purpose: a command line shows in process listings.
// Throws std::invalid_argument naming what is missing or wrong (never the key itself).
LlmEndpoint endpoint_from_environment(const std::string& base_url_flag, const std::string& model_flag);

// "openai" (api.openai.com), "openrouter" (openrouter.ai), "anthropic" (api.anthropic.com),
// "google" (generativelanguage.googleapis.com), "local" (localhost, 127.0.0.1, ::1), else the
// URL's host name.
std::string provider_from_base_url(const std::string& base_url);

// One function call of an assistant message (OpenAI `tool_calls[i]`).
struct ToolCall {
  std::string id;         // as the model gave it (e.g. "call_abc"); a tool message answers it by id
  std::string name;       // function.name
  std::string arguments;  // function.arguments: the JSON text as the model wrote it
};

struct ChatMessage {
  std::string role;  // system | user | assistant | tool
  std::string content;  // an assistant message with tool_calls may have none ("": sent as null)
  std::vector<ToolCall> tool_calls = {};  // assistant: the calls it made
  std::string tool_call_id = {};          // tool: the call this message is the result of
};

// One chat-completions request: the messages and, for tool calling, the OpenAI `tools` array
// (null: none) and `tool_choice` ("": not sent; "auto", "required", "none").
struct ChatRequest {
  std::vector<ChatMessage> messages;
  nlohmann::json tools = nullptr;
  std::string tool_choice = {};
};

struct LlmUsage {
  int64_t prompt_tokens = 0;
  int64_t completion_tokens = 0;
  int64_t total_tokens = 0;
  std::optional<double> cost_usd;   // when the provider reports it (OpenRouter: usage.cost)
  nlohmann::json raw = nlohmann::json::object();  // the provider's usage object as sent
  LlmUsage& operator+=(const LlmUsage& other);    // sums tokens and cost (raw: the sum's fields)
  nlohmann::json to_json() const;                 // raw with the summed fields, as the corpus records it
};

// One HTTP attempt of a call, for the error message and the record of what happened.
struct LlmAttempt {
  int http_status = 0;        // 0: no HTTP answer (network error)
  std::string error;          // empty when the attempt got a usable answer; key redacted
  double duration_s = 0.0;    // the request itself
  double backoff_s = 0.0;     // waited after it before the next attempt
  std::optional<double> ttft_s;  // streamed: request start to the first token
  std::optional<double> ttlt_s;  // streamed: request start to the last token
};

struct LlmCallResult {
  bool ok = false;
  std::string content;        // choices[0].message.content ("" when null)
  std::string reply_problem;  // ok, but the reply had to be repaired to be read (invalid UTF-8)
  std::vector<ToolCall> tool_calls;  // choices[0].message.tool_calls, in order
  std::string finish_reason;  // choices[0].finish_reason
  std::string model;          // as the server reports it
  LlmUsage usage;
  double wall_time_s = 0.0;   // first request to last byte, retries and backoff included
  int http_status = 0;        // of the last HTTP attempt (0: none completed)
  int http_attempts = 0;      // 1 + retries made
  std::vector<LlmAttempt> attempts;
  std::string error;          // when !ok: what went wrong, key redacted
  bool streamed = false;      // the answer came as server-sent events
  std::optional<double> ttft_s;  // streamed: of the usable attempt, request start to first token
  std::optional<double> ttlt_s;  // streamed: ... to the last token
  bool interrupted = false;   // LlmClient::abort_calls() ended it (not the endpoint's failure)
};

// Whether a failed call is the endpoint's fault rather than the request's (never an interrupted
// one): no HTTP answer
// (unreachable, timeout, cut), 401, 403, 404, 408, 429 or 5xx (after the client's retries).
// `a3rig generate` stops on it; `a3rig run` ends endpoint_failed on it (rigs/run/llm_run.hpp).
bool is_endpoint_failure(const LlmCallResult& result);

class LlmClient {
 public:
  // Throws std::invalid_argument for an unusable endpoint (no http(s) base URL, no model,
  // non-positive timeouts, negative retries). Fills endpoint.provider when empty.
  explicit LlmClient(LlmEndpoint endpoint);
  ~LlmClient();
  LlmClient(const LlmClient&) = delete;
  LlmClient& operator=(const LlmClient&) = delete;

  // Never throws for HTTP, network or response-format problems: they come back as !ok.
  // One client is one connection: use one per thread.
  LlmCallResult chat(const std::vector<ChatMessage>& messages);
  // The same with tools, tool_choice (chat(messages) is send({messages})).
  LlmCallResult send(const ChatRequest& request);

  const LlmEndpoint& endpoint() const { return endpoint_; }
  // True once the server rejected response_format: later calls go without it.
  bool response_format_dropped() const { return refused_.response_format; }
  // What the server refused so far (kept for later calls).
  const RefusedParameters& refused_parameters() const { return refused_; }
  // Replaces sleeping between retries (tests); receives the backoff in seconds.
  void set_sleep_for_tests(std::function<void(double)> sleep);
  // From any thread (Ctrl-C): the call in flight ends within 50 ms as interrupted (no retry,
  // a backoff wait wakes), and every later call returns interrupted at once. Sticky.
  void abort_calls();

 private:
  void wait_unless_aborted(double seconds);

  LlmEndpoint endpoint_;
  std::function<void(double)> sleep_;
  void* curl_ = nullptr;   // CURL*, reused across calls (keep-alive)
  void* multi_ = nullptr;  // CURLM*: runs each transfer so that a stop can end it
  std::atomic<bool> aborted_{false};
  std::mutex abort_mutex_;
  std::condition_variable abort_wake_;
  RefusedParameters refused_;
};

// Replaces every occurrence of `secret` (if non-empty) in `text` with "[redacted]".
std::string redact(std::string text, const std::string& secret);

}  // namespace a3::agent::llm
