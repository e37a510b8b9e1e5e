// The llm agent's turn: prompt, call, read, retry.
#include "agent/llm/llm_agent.hpp"

#include <stdexcept>

#include "agent/llm/json_extract.hpp"
#include "agent/llm/llm_reply.hpp"
#include "agent/llm/native_reply.hpp"
#include "common/clock.hpp"

namespace a3::agent::llm {
namespace {

std::string utf8_prefix(const std::string& text, std::size_t max_bytes) {
  if (text.size() <= max_bytes) return text;
  std::size_t n = max_bytes;
  while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n;
  return text.substr(0, n) + " [cut]";
}

double seconds_since(int64_t start_ns) {
  return static_cast<double>(common::WallClock::monotonic_now_ns() - start_ns) * 1e-9;
}

// What every attempt records, whatever its outcome.
nlohmann::json attempt_entry(int attempt, const LlmCallResult& call, ToolMode mode) {
  nlohmann::json entry = {{"attempt", attempt},
                          {"tool_mode", to_string(mode)},
                          {"wall_time_s", call.wall_time_s},
                          {"http_status", call.http_status},
                          {"http_attempts", call.http_attempts},
                          {"usage", call.usage.to_json()}};
  if (call.streamed) entry["streamed"] = true;
  if (call.ttft_s) entry["ttft_s"] = *call.ttft_s;
  if (call.ttlt_s) entry["ttlt_s"] = *call.ttlt_s;
  return entry;
}

std::string joined(const std::vector<std::string>& problems) {
  std::string out;
  for (const auto& p : problems) out += (out.empty() ? "" : "; ") + p;
  return out;
}

}  // namespace

LlmAgent::LlmAgent(std::unique_ptr<LlmClient> client, const ToolCatalog& tools, LlmAgentOptions options)
    : client_(std::move(client)), tools_(tools), options_(options) {
  if (!client_) throw std::invalid_argument("LlmAgent: no client");
  secret_ = client_->endpoint().api_key;
  LlmClient* c = client_.get();
  chat_ = [c](const ChatRequest& request) { return c->send(request); };
  if (options_.max_attempts < 1) throw std::invalid_argument("LlmAgent: max_attempts must be >= 1");
}

LlmAgent::LlmAgent(ChatFunction chat, std::string secret, const ToolCatalog& tools, LlmAgentOptions options)
    : chat_(std::move(chat)), secret_(std::move(secret)), tools_(tools), options_(options) {
  if (!chat_) throw std::invalid_argument("LlmAgent: no chat function");
  if (options_.max_attempts < 1) throw std::invalid_argument("LlmAgent: max_attempts must be >= 1");
}

void LlmAgent::stop_deciding() {
  stopped_ = true;
  if (client_) client_->abort_calls();
}

ChatRequest LlmAgent::request(const AgentContext& c, int attempt, const FailedAttempt* failure) const {
  if (options_.mode == ToolMode::kNative) return native_request(c, tools_, calls_, attempt, failure, options_.dialogue);
  return ChatRequest{build_turn_messages(c, tools_, attempt, failure, options_.dialogue)};
}

LlmCallResult LlmAgent::call(const ChatRequest& request, bool& threw) {
  threw = false;
  try {
    return chat_(request);
  } catch (const std::exception& e) {
    threw = true;
    LlmCallResult failed;
    failed.error = std::string("the call failed: ") + e.what();
    return failed;
  }
}

LlmAgent::Reading LlmAgent::read(const LlmCallResult& call, int turn_number) const {
  Reading r;
  if (options_.mode == ToolMode::kNative) {
    NativeReply reply = read_native_reply(call, tools_, turn_number);
    r = {reply.intent, reply.text, std::move(reply.actions), std::move(reply.calls), std::move(reply.problems),
         native_reply_text(call)};
  } else {
    ParsedReply reply = parse_reply(call.content, tools_);
    r = {reply.intent, reply.text, std::move(reply.actions), {}, std::move(reply.problems), call.content};
  }
  // The reply goes into the attempt log and the correction prompt: both JSON.
  r.reply = valid_utf8(r.reply);
  if (!call.reply_problem.empty()) r.problems.insert(r.problems.begin(), "reply: " + call.reply_problem);
  // A model never sees the key; should a reply carry it anyway, it is not used or recorded.
  if (!secret_.empty() && r.reply.find(secret_) != std::string::npos) {
    r.problems.push_back("reply: repeats a credential; not used");
  }
  if (!r.problems.empty() && call.finish_reason == "length") {
    r.problems.push_back("reply: cut off at the completion token limit (max_tokens); keep the reply short");
  }
  return r;
}

AgentDecision LlmAgent::decide(const AgentContext& context) {
  const int64_t start_ns = common::WallClock::monotonic_now_ns();
  auto scrub = [this](const std::string& s) { return redact(s, secret_); };
  AgentDecision d;
  d.attempt_log = nlohmann::json::array();
  LlmUsage usage;
  FailedAttempt failure;
  bool done = false;
  int attempt = 0;
  bool interrupted = false;
  bool break_ladder = false;
  while (!done && !interrupted && !break_ladder && attempt < options_.max_attempts) {
    ++attempt;
    bool threw = false;
    const LlmCallResult result = call(request(context, attempt, attempt > 1 ? &failure : nullptr), threw);
    usage += result.usage;
    nlohmann::json entry = attempt_entry(attempt, result, options_.mode);
    if (!result.model.empty()) entry["model"] = scrub(result.model);
    if (!result.ok && (result.interrupted || stopped_)) {
      interrupted = true;
      entry["outcome"] = "interrupted";
      entry["endpoint_failure"] = false;
      entry["problems"] = {scrub(result.error.empty() ? "interrupted: the run was stopped" : result.error)};
    } else if (!result.ok) {
      const std::string error = scrub(result.error.empty() ? "the call failed (no reason given)" : result.error);
      entry["outcome"] = "call_failed";
      entry["endpoint_failure"] = !threw && is_endpoint_failure(result);
      entry["problems"] = {error};
      failure = {"", {error}};
      // No HTTP answer at all (refused, timed out, reset) after the client's own retries: a
      // stricter prompt cannot help, and two more attempts would hold a silent endpoint for
      // 2 x (1 + --llm-retries) x --llm-timeout more.
      if (!threw && result.http_status == 0) break_ladder = true;
    } else if (Reading r = read(result, context.turn_number); r.problems.empty()) {
      entry["outcome"] = "ok";
      d.intent = scrub(r.intent);
      d.text = scrub(r.text);
      d.actions = std::move(r.actions);
      if (options_.mode == ToolMode::kNative) calls_[context.turn_number] = std::move(r.calls);
      done = true;
    } else {
      std::vector<std::string> problems;
      for (const auto& p : r.problems) problems.push_back(scrub(p));
      entry["outcome"] = "invalid_reply";
      entry["problems"] = problems;
      entry["reply"] = scrub(utf8_prefix(r.reply, options_.recorded_reply_chars));
      failure = {scrub(r.reply), problems};
    }
    d.attempt_log.push_back(std::move(entry));
  }
  d.attempts = attempt;
  d.usage = usage.to_json();
  if (interrupted) {
    d.error = "interrupted: the run was stopped during attempt " + std::to_string(attempt) + " of the turn, after " +
              std::to_string(seconds_since(start_ns)) + " s";
    d.intent.clear();
    d.text.clear();
    d.actions = nlohmann::json::array();
  } else if (!done) {
    d.error = "no usable reply after " + std::to_string(attempt) + " attempt" + (attempt == 1 ? "" : "s") + ": " +
              joined(failure.problems);
    d.intent.clear();
    d.text.clear();
    d.actions = nlohmann::json::array();
  }
  d.latency_s = seconds_since(start_ns);
  return d;
}

}  // namespace a3::agent::llm
