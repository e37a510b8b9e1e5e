// An OpenAI-compatible chat-completions client over libcurl (HTTPS or HTTP): one call is one
// POST {base_url}/chat/completions. Retries with exponential backoff on HTTP 429/5xx and
// network errors, honouring Retry-After; connect and total timeouts; token usage (and cost,
// where the provider reports it) and wall time per call. The API key is sent only in the
// Authorization header: it never appears in errors, logs, or anything this client returns.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

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

struct ChatMessage {
  std::string role;  // system | user | assistant
  std::string content;
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
};

struct LlmCallResult {
  bool ok = false;
  std::string content;        // choices[0].message.content
  std::string finish_reason;  // choices[0].finish_reason
  std::string model;          // as the server reports it
  LlmUsage usage;
  double wall_time_s = 0.0;   // first request to last byte, retries and backoff included
  int http_status = 0;        // of the last HTTP attempt (0: none completed)
  int http_attempts = 0;      // 1 + retries made
  std::vector<LlmAttempt> attempts;
  std::string error;          // when !ok: what went wrong, key redacted
};

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

  const LlmEndpoint& endpoint() const { return endpoint_; }
  // True once the server rejected response_format: later calls go without it.
  bool response_format_dropped() const { return response_format_rejected_; }
  // Replaces sleeping between retries (tests); receives the backoff in seconds.
  void set_sleep_for_tests(std::function<void(double)> sleep);

 private:
  LlmEndpoint endpoint_;
  std::function<void(double)> sleep_;
  void* curl_ = nullptr;  // CURL*, reused across calls (keep-alive)
  bool response_format_rejected_ = false;
};

// Replaces every occurrence of `secret` (if non-empty) in `text` with "[redacted]".
std::string redact(std::string text, const std::string& secret);

}  // namespace a3::agent::llm
