// The OpenAI-compatible chat-completions client: libcurl easy handle reused across calls
// (keep-alive), retries with backoff, response reading, key hygiene.
#include "agent/llm/llm_client.hpp"

#include <curl/curl.h>
#include <pthread.h>
#include <signal.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <optional>
#include <string_view>
#include <stdexcept>
#include <thread>

#include "agent/llm/http_chat_completion.hpp"
#include "agent/llm/http_retry.hpp"
#include "agent/llm/sse_stream.hpp"

namespace a3::agent::llm {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v == nullptr ? std::string() : std::string(v);
}

std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

std::string read_key_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument("A3_LLM_API_KEY_FILE: cannot read " + path);
  std::string line;
  std::getline(in, line);
  line = trim(line);
  if (line.empty()) throw std::invalid_argument("A3_LLM_API_KEY_FILE: the first line of " + path + " is empty");
  return line;
}

void check_key(const std::string& key, const char* source) {
  for (char c : key) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      throw std::invalid_argument(std::string(source) + ": the API key contains a control character or line break");
    }
  }
}

std::string size_text(std::size_t bytes) {
  if (bytes >= (1u << 20) && bytes % (1u << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

// libcurl is told not to touch signals (CURLOPT_NOSIGNAL, needed with threads), so a write to a
// connection the peer closed could raise SIGPIPE and end the program. The signal is blocked in
// this thread for the transfer and a pending one is discarded after it.
class SigpipeBlock {
 public:
  SigpipeBlock() {
    sigemptyset(&pipe_);
    sigaddset(&pipe_, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipe_, &old_);
  }
  ~SigpipeBlock() {
    sigset_t pending;
    sigemptyset(&pending);
    if (sigpending(&pending) == 0 && sigismember(&pending, SIGPIPE) == 1 && sigismember(&old_, SIGPIPE) == 0) {
      const timespec zero{0, 0};
      sigtimedwait(&pipe_, nullptr, &zero);
    }
    pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  SigpipeBlock(const SigpipeBlock&) = delete;
  SigpipeBlock& operator=(const SigpipeBlock&) = delete;

 private:
  sigset_t pipe_;
  sigset_t old_;
};

void init_curl_once() {
  static std::once_flag once;
  std::call_once(once, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });
}

// What one HTTP exchange produced. A streamed answer (requested, and sent as
// text/event-stream) is assembled as it arrives instead of kept as a body.
struct Exchange {
  CURLcode code = CURLE_OK;
  std::string curl_error;
  long http_status = 0;
  std::string body;
  std::string retry_after;
  bool body_too_large = false;
  std::size_t max_bytes = 0;
  std::size_t bytes = 0;
  bool stream_requested = false;
  bool streaming = false;
  SseLineParser sse;
  ChatStreamAssembler assembler;
  std::string stream_problem;
  Clock::time_point start;
  std::optional<double> ttft_s, ttlt_s;
};

void on_stream_event(Exchange& ex, const std::string& data) {
  if (!ex.stream_problem.empty()) return;
  bool token = false;
  ex.stream_problem = ex.assembler.add(data, token);
  if (!token) return;
  const double t = seconds_since(ex.start);
  if (!ex.ttft_s) ex.ttft_s = t;
  ex.ttlt_s = t;
}

std::size_t on_body(char* data, std::size_t size, std::size_t count, void* user) {
  auto* ex = static_cast<Exchange*>(user);
  const std::size_t n = size * count;
  if (ex->bytes + n > ex->max_bytes) {
    ex->body_too_large = true;
    return 0;  // makes curl stop with CURLE_WRITE_ERROR
  }
  ex->bytes += n;
  if (!ex->streaming) {
    ex->body.append(data, n);
    return n;
  }
  ex->sse.feed(std::string_view(data, n), [ex](const std::string& event) { on_stream_event(*ex, event); });
  return ex->stream_problem.empty() ? n : 0;
}

std::size_t on_header(char* data, std::size_t size, std::size_t count, void* user) {
  auto* ex = static_cast<Exchange*>(user);
  const std::size_t n = size * count;
  const std::string line(data, n);
  if (starts_with(line, "HTTP/")) {  // a new response (after 100 Continue, redirects)
    ex->retry_after.clear();
    ex->streaming = false;
  }
  const auto colon = line.find(':');
  if (colon == std::string::npos) return n;
  const std::string name = lower(line.substr(0, colon));
  if (name == "retry-after") ex->retry_after = trim(line.substr(colon + 1));
  if (name == "content-type") {
    ex->streaming = ex->stream_requested && starts_with(lower(trim(line.substr(colon + 1))), "text/event-stream");
  }
  return n;
}

curl_slist* request_headers(const std::string& key, bool stream) {
  curl_slist* headers = nullptr;
  headers = curl_slist_append(headers, "Content-Type: application/json");
  headers = curl_slist_append(headers, stream ? "Accept: text/event-stream, application/json" : "Accept: application/json");
  headers = curl_slist_append(headers, "Expect:");
  if (!key.empty()) headers = curl_slist_append(headers, ("Authorization: Bearer " + key).c_str());
  return headers;
}

// Runs the transfer set up on `curl` through `multi`, polling every 50 ms so that a stop
// (`abort`) ends it within that time: CURLE_ABORTED_BY_CALLBACK then.
CURLcode run_transfer(CURLM* multi, CURL* curl, const std::atomic<bool>& abort) {
  curl_multi_add_handle(multi, curl);
  CURLcode code = CURLE_ABORTED_BY_CALLBACK;
  for (int running = 1; running > 0 && !abort.load();) {
    if (curl_multi_perform(multi, &running) != CURLM_OK) {
      code = CURLE_FAILED_INIT;
      break;
    }
    int queued = 0;
    while (CURLMsg* msg = curl_multi_info_read(multi, &queued)) {
      if (msg->msg == CURLMSG_DONE && msg->easy_handle == curl) code = msg->data.result;
    }
    if (running > 0) curl_multi_poll(multi, nullptr, 0, 50, nullptr);
  }
  curl_multi_remove_handle(multi, curl);
  return code;
}

// One POST of `body` to `url` on the kept-alive handle.
void perform(CURLM* multi, CURL* curl, const std::string& url, const std::string& body, curl_slist* headers,
             const LlmEndpoint& e, const std::atomic<bool>& abort, Exchange& ex) {
  char curl_error[CURL_ERROR_SIZE] = {0};
  curl_easy_reset(curl);  // options only: the connection cache stays (keep-alive)
  curl_easy_setopt(curl, CURLOPT_URL, url.c_str());
  curl_easy_setopt(curl, CURLOPT_POST, 1L);
  curl_easy_setopt(curl, CURLOPT_POSTFIELDS, body.data());
  curl_easy_setopt(curl, CURLOPT_POSTFIELDSIZE_LARGE, static_cast<curl_off_t>(body.size()));
  curl_easy_setopt(curl, CURLOPT_HTTPHEADER, headers);
  curl_easy_setopt(curl, CURLOPT_USERAGENT, "a3rig-llm-client");
  curl_easy_setopt(curl, CURLOPT_ACCEPT_ENCODING, "");
  curl_easy_setopt(curl, CURLOPT_NOSIGNAL, 1L);
  curl_easy_setopt(curl, CURLOPT_TCP_KEEPALIVE, 1L);
  curl_easy_setopt(curl, CURLOPT_CONNECTTIMEOUT_MS, static_cast<long>(e.connect_timeout_s * 1000.0));
  curl_easy_setopt(curl, CURLOPT_TIMEOUT_MS, static_cast<long>(e.total_timeout_s * 1000.0));
  curl_easy_setopt(curl, CURLOPT_MAXFILESIZE_LARGE, static_cast<curl_off_t>(e.max_response_bytes));
  curl_easy_setopt(curl, CURLOPT_WRITEFUNCTION, on_body);
  curl_easy_setopt(curl, CURLOPT_WRITEDATA, &ex);
  curl_easy_setopt(curl, CURLOPT_HEADERFUNCTION, on_header);
  curl_easy_setopt(curl, CURLOPT_HEADERDATA, &ex);
  curl_easy_setopt(curl, CURLOPT_ERRORBUFFER, curl_error);
  ex.start = Clock::now();
  {
    const SigpipeBlock no_sigpipe;
    ex.code = run_transfer(multi, curl, abort);
  }
  ex.curl_error = curl_error;
  curl_easy_getinfo(curl, CURLINFO_RESPONSE_CODE, &ex.http_status);
  curl_easy_setopt(curl, CURLOPT_ERRORBUFFER, nullptr);
}

// A 2xx answer read into `out`; "" or what is wrong with it.
std::string read_answer(Exchange& ex, const std::string& url, ChatResponse& out) {
  if (!ex.streaming) {
    std::string error;
    return parse_chat_response(ex.body, url, out, error) ? "" : error;
  }
  const std::string problem = ex.assembler.finish(out);
  return problem.empty() ? "" : "response from " + url + ": " + problem;
}

// Everything the model wrote, with the key taken out (a model never sees it; should it appear).
void redact_answer(ChatResponse& r, const std::string& key) {
  r.content = redact(std::move(r.content), key);
  for (auto& c : r.tool_calls) c.arguments = redact(std::move(c.arguments), key);
}

std::string call_error(const std::string& url, const std::vector<LlmAttempt>& attempts, const std::string& final_error) {
  if (attempts.size() <= 1) return "POST " + url + ": " + final_error;
  std::string error = "POST " + url + " failed after " + std::to_string(attempts.size()) + " attempts:";
  for (std::size_t i = 0; i < attempts.size(); ++i) {
    error += " #" + std::to_string(i + 1) + " " + (attempts[i].error.empty() ? std::string("ok") : attempts[i].error) + ";";
  }
  error.pop_back();
  return error;
}

std::string describe_curl_error(const Exchange& ex, const LlmEndpoint& e) {
  switch (ex.code) {
    case CURLE_ABORTED_BY_CALLBACK:
      return "interrupted: the run was stopped after " + std::to_string(seconds_since(ex.start)) +
             " s of this attempt";
    case CURLE_OPERATION_TIMEDOUT:
      return "timed out (connect timeout " + std::to_string(e.connect_timeout_s) + " s, total timeout " +
             std::to_string(e.total_timeout_s) + " s): " + ex.curl_error;
    case CURLE_COULDNT_CONNECT:
      return "connection failed: " + ex.curl_error;
    default:
      return std::string(curl_easy_strerror(ex.code)) + (ex.curl_error.empty() ? "" : ": " + ex.curl_error);
  }
}

}  // namespace

// ---- usage ----

LlmUsage& LlmUsage::operator+=(const LlmUsage& other) {
  prompt_tokens += other.prompt_tokens;
  completion_tokens += other.completion_tokens;
  total_tokens += other.total_tokens;
  if (other.cost_usd) cost_usd = cost_usd.value_or(0.0) + *other.cost_usd;
  if (!raw.is_object()) raw = nlohmann::json::object();
  add_usage_fields(raw, other.raw);
  raw["prompt_tokens"] = prompt_tokens;
  raw["completion_tokens"] = completion_tokens;
  raw["total_tokens"] = total_tokens;
  if (cost_usd) raw["cost"] = *cost_usd;
  return *this;
}

nlohmann::json LlmUsage::to_json() const {
  nlohmann::json out = raw.is_object() ? raw : nlohmann::json::object();
  out["prompt_tokens"] = prompt_tokens;
  out["completion_tokens"] = completion_tokens;
  out["total_tokens"] = total_tokens;
  if (cost_usd) out["cost"] = *cost_usd;
  return out;
}

// ---- endpoint ----

std::string redact(std::string text, const std::string& secret) {
  if (secret.empty()) return text;
  static const std::string kMark = "[redacted]";
  for (std::size_t pos = text.find(secret); pos != std::string::npos; pos = text.find(secret, pos + kMark.size())) {
    text.replace(pos, secret.size(), kMark);
  }
  return text;
}

std::string provider_from_base_url(const std::string& base_url) {
  std::string rest = base_url;
  if (const auto scheme = rest.find("://"); scheme != std::string::npos) rest = rest.substr(scheme + 3);
  rest = rest.substr(0, rest.find_first_of("/?#"));
  if (const auto at = rest.rfind('@'); at != std::string::npos) rest = rest.substr(at + 1);
  std::string host;
  if (!rest.empty() && rest[0] == '[') {
    host = rest.substr(1, rest.find(']') == std::string::npos ? std::string::npos : rest.find(']') - 1);
  } else {
    host = rest.substr(0, rest.find(':'));
  }
  host = lower(host);
  auto is_or_under = [&](const std::string& domain) {
    return host == domain || (host.size() > domain.size() && host.compare(host.size() - domain.size() - 1,
                                                                          std::string::npos, "." + domain) == 0);
  };
  if (is_or_under("api.openai.com")) return "openai";
  if (is_or_under("openrouter.ai")) return "openrouter";
  if (is_or_under("api.anthropic.com")) return "anthropic";
  if (is_or_under("generativelanguage.googleapis.com")) return "google";
  if (host == "localhost" || host == "::1" || starts_with(host, "127.")) return "local";
  return host;
}

LlmEndpoint endpoint_from_environment(const std::string& base_url_flag, const std::string& model_flag) {
  LlmEndpoint e;
  e.base_url = !base_url_flag.empty() ? base_url_flag : env("A3_LLM_BASE_URL");
  if (e.base_url.empty()) {
    throw std::invalid_argument(
        "no LLM endpoint: set A3_LLM_BASE_URL or --llm-base-url (e.g. https://api.openai.com/v1, "
        "https://openrouter.ai/api/v1, http://localhost:8000/v1 for vLLM)");
  }
  while (e.base_url.size() > 1 && e.base_url.back() == '/') e.base_url.pop_back();
  if (!starts_with(lower(e.base_url), "http://") && !starts_with(lower(e.base_url), "https://")) {
    throw std::invalid_argument("LLM base URL '" + e.base_url + "' must start with http:// or https://");
  }
  e.model = !model_flag.empty() ? model_flag : env("A3_LLM_MODEL");
  if (e.model.empty()) throw std::invalid_argument("no LLM model: set A3_LLM_MODEL or --llm-model (e.g. gpt-4.1-mini)");
  e.provider = env("A3_LLM_PROVIDER");
  if (e.provider.empty()) e.provider = provider_from_base_url(e.base_url);

  if (const std::string key = trim(env("A3_LLM_API_KEY")); !key.empty()) {
    check_key(key, "A3_LLM_API_KEY");
    e.api_key = key;
  } else if (const std::string file = env("A3_LLM_API_KEY_FILE"); !file.empty()) {
    e.api_key = read_key_file(file);
    check_key(e.api_key, "A3_LLM_API_KEY_FILE");
  } else if (const std::string openai = trim(env("OPENAI_API_KEY")); !openai.empty()) {
    check_key(openai, "OPENAI_API_KEY");
    e.api_key = openai;
  }
  return e;
}

// ---- client ----

LlmClient::LlmClient(LlmEndpoint endpoint) : endpoint_(std::move(endpoint)) {
  while (endpoint_.base_url.size() > 1 && endpoint_.base_url.back() == '/') endpoint_.base_url.pop_back();
  const std::string url = lower(endpoint_.base_url);
  if (!starts_with(url, "http://") && !starts_with(url, "https://")) {
    throw std::invalid_argument("LLM base URL '" + endpoint_.base_url + "' must start with http:// or https://");
  }
  if (endpoint_.model.empty()) throw std::invalid_argument("LLM endpoint " + endpoint_.base_url + ": no model");
  if (!(endpoint_.connect_timeout_s > 0.0) || !(endpoint_.total_timeout_s > 0.0)) {
    throw std::invalid_argument("LLM endpoint: connect and total timeouts must be > 0 s");
  }
  if (endpoint_.max_retries < 0) throw std::invalid_argument("LLM endpoint: max_retries must be >= 0");
  if (endpoint_.backoff_initial_s < 0.0 || endpoint_.backoff_max_s < 0.0) {
    throw std::invalid_argument("LLM endpoint: backoff times must be >= 0 s");
  }
  if (endpoint_.max_response_bytes == 0) throw std::invalid_argument("LLM endpoint: max_response_bytes must be > 0");
  check_key(endpoint_.api_key, "LLM endpoint");
  if (endpoint_.provider.empty()) endpoint_.provider = provider_from_base_url(endpoint_.base_url);
  sleep_ = [this](double s) { wait_unless_aborted(s); };
  init_curl_once();
  curl_ = curl_easy_init();
  multi_ = curl_multi_init();
  if (curl_ == nullptr || multi_ == nullptr) throw std::runtime_error("libcurl: curl_easy_init/curl_multi_init failed");
}

LlmClient::~LlmClient() {
  if (curl_ != nullptr) curl_easy_cleanup(static_cast<CURL*>(curl_));
  if (multi_ != nullptr) curl_multi_cleanup(static_cast<CURLM*>(multi_));
}

void LlmClient::abort_calls() {
  {
    const std::lock_guard<std::mutex> lock(abort_mutex_);
    aborted_ = true;
  }
  abort_wake_.notify_all();
}

void LlmClient::wait_unless_aborted(double seconds) {
  std::unique_lock<std::mutex> lock(abort_mutex_);
  abort_wake_.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return aborted_.load(); });
}

void LlmClient::set_sleep_for_tests(std::function<void(double)> sleep) { sleep_ = std::move(sleep); }

LlmCallResult LlmClient::chat(const std::vector<ChatMessage>& messages) { return send(ChatRequest{messages}); }

bool is_endpoint_failure(const LlmCallResult& result) {
  if (result.ok || result.interrupted) return false;
  const int s = result.http_status;
  return s == 0 || s == 401 || s == 403 || s == 404 || s == 408 || s == 429 || s >= 500;
}

namespace {

// What one attempt came to.
struct Verdict {
  LlmAttempt attempt;
  bool retryable = false;  // worth another try after a backoff
  bool adapted = false;    // a refused parameter was adjusted: ask again at once
};

// A 2xx answer into `result`; "" or what is wrong with it.
std::string take_answer(Exchange& ex, const std::string& url, const std::string& key, LlmCallResult& result) {
  ChatResponse parsed;
  const std::string error = read_answer(ex, url, parsed);
  if (!error.empty()) return error;
  redact_answer(parsed, key);
  result.ok = true;
  result.content = std::move(parsed.content);
  result.reply_problem = std::move(parsed.reply_problem);
  result.tool_calls = std::move(parsed.tool_calls);
  result.finish_reason = std::move(parsed.finish_reason);
  result.model = std::move(parsed.model);
  result.usage = std::move(parsed.usage);
  result.streamed = ex.streaming;
  result.ttft_s = ex.ttft_s;
  result.ttlt_s = ex.ttlt_s;
  return "";
}

// The cases of an attempt: too large, a bad stream, no HTTP answer, an answer (2xx), a refusal
// of a parameter, another HTTP error.
Verdict judge(Exchange& ex, const std::string& url, const LlmEndpoint& endpoint, const SentParameters& sent,
              RefusedParameters& refused, LlmCallResult& result) {
  const std::string& key = endpoint.api_key;
  // Before anything is cut into an excerpt (which could cut a key in two) or returned.
  ex.body = redact(std::move(ex.body), key);
  ex.stream_problem = redact(std::move(ex.stream_problem), key);
  Verdict v;
  LlmAttempt& attempt = v.attempt;
  attempt.duration_s = seconds_since(ex.start);
  attempt.http_status = ex.code == CURLE_OK || !ex.stream_problem.empty() ? static_cast<int>(ex.http_status) : 0;
  attempt.ttft_s = ex.ttft_s;
  attempt.ttlt_s = ex.ttlt_s;
  result.http_attempts += 1;
  if (attempt.http_status != 0) result.http_status = attempt.http_status;

  if (ex.body_too_large || ex.code == CURLE_FILESIZE_EXCEEDED) {
    attempt.error = "response from " + url + " is larger than " + size_text(endpoint.max_response_bytes) +
                    " (max_response_bytes); not read";
  } else if (!ex.stream_problem.empty()) {
    attempt.error = "response from " + url + ": " + ex.stream_problem;
  } else if (ex.code != CURLE_OK) {
    attempt.error = describe_curl_error(ex, endpoint) + (ex.streaming ? " (in the middle of the stream)" : "");
    v.retryable = is_retryable_curl_error(ex.code);
  } else if (ex.http_status >= 200 && ex.http_status < 300) {
    attempt.error = take_answer(ex, url, key, result);
    if (!attempt.error.empty() && ex.streaming) {  // a cut stream is a network failure, not an answer
      attempt.http_status = 0;
      result.http_status = 0;
      v.retryable = true;
    }
  } else {
    attempt.error = "HTTP " + std::to_string(ex.http_status) + ": " + error_text_from_body(ex.body);
    const std::string adapted = adapt_to_refusal(static_cast<int>(ex.http_status), ex.body, sent, refused);
    // The provider does not take a parameter: ask again without it, now and from now on.
    if (!adapted.empty()) attempt.error += " (" + adapted + " and retrying)";
    v.adapted = !adapted.empty();
    v.retryable = is_retryable_http_status(static_cast<int>(ex.http_status));
  }
  attempt.error = redact(attempt.error, key);
  return v;
}

}  // namespace

LlmCallResult LlmClient::send(const ChatRequest& request) {
  LlmCallResult result;
  const std::string url = endpoint_.base_url + "/chat/completions";
  const auto start = Clock::now();
  curl_slist* headers = request_headers(endpoint_.api_key, endpoint_.stream);
  int retries_made = 0;
  std::string final_error;
  if (aborted_) {
    curl_slist_free_all(headers);
    result.interrupted = true;
    result.error = "POST " + url + ": interrupted: the run was stopped before the call";
    return result;
  }
  for (;;) {
    const SentParameters sent = parameters_to_send(endpoint_, request, refused_);
    std::string request_body;
    try {
      request_body = chat_request_body(endpoint_, request, sent).dump();
    } catch (const nlohmann::json::exception& e) {  // e.g. a message that is not UTF-8
      final_error = std::string("cannot encode the request: ") + e.what();
      break;
    }
    Exchange ex;
    ex.max_bytes = endpoint_.max_response_bytes;
    ex.stream_requested = endpoint_.stream;
    perform(static_cast<CURLM*>(multi_), static_cast<CURL*>(curl_), url, request_body, headers, endpoint_, aborted_, ex);
    Verdict v = judge(ex, url, endpoint_, sent, refused_, result);
    if (ex.code == CURLE_ABORTED_BY_CALLBACK) {  // a stop is no network error: no retry
      result.interrupted = true;
      v.retryable = false;
    }
    if (v.adapted) {
      result.attempts.push_back(v.attempt);
      continue;
    }
    const bool retry = v.retryable && retries_made < endpoint_.max_retries;
    if (retry) {
      v.attempt.backoff_s = backoff_delay_s(retries_made, endpoint_.backoff_initial_s, endpoint_.backoff_max_s,
                                            parse_retry_after_s(ex.retry_after, std::time(nullptr)));
    }
    result.attempts.push_back(v.attempt);
    if (result.ok) break;
    if (!retry) {
      final_error = v.attempt.error;
      break;
    }
    ++retries_made;
    if (v.attempt.backoff_s > 0.0) sleep_(v.attempt.backoff_s);
    if (aborted_) {
      result.interrupted = true;
      final_error = "interrupted: the run was stopped while waiting to retry";
      break;
    }
  }
  curl_slist_free_all(headers);
  result.wall_time_s = seconds_since(start);
  if (!result.ok) result.error = redact(call_error(url, result.attempts, final_error), endpoint_.api_key);
  return result;
}

}  // namespace a3::agent::llm
