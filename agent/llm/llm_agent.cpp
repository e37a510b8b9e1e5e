// The llm agent's turn: prompt, call, parse, retry.
#include "agent/llm/llm_agent.hpp"

#include <stdexcept>

#include "agent/llm/llm_reply.hpp"
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

}  // namespace

LlmAgent::LlmAgent(std::unique_ptr<LlmClient> client, const ToolCatalog& tools, LlmAgentOptions options)
    : client_(std::move(client)), tools_(tools), options_(options) {
  if (!client_) throw std::invalid_argument("LlmAgent: no client");
  secret_ = client_->endpoint().api_key;
  LlmClient* c = client_.get();
  chat_ = [c](const std::vector<ChatMessage>& messages) { return c->chat(messages); };
  if (options_.max_attempts < 1) throw std::invalid_argument("LlmAgent: max_attempts must be >= 1");
}

LlmAgent::LlmAgent(ChatFunction chat, std::string secret, const ToolCatalog& tools, LlmAgentOptions options)
    : chat_(std::move(chat)), secret_(std::move(secret)), tools_(tools), options_(options) {
  if (!chat_) throw std::invalid_argument("LlmAgent: no chat function");
  if (options_.max_attempts < 1) throw std::invalid_argument("LlmAgent: max_attempts must be >= 1");
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
  while (!done && attempt < options_.max_attempts) {
    ++attempt;
    nlohmann::json entry = {{"attempt", attempt}};
    LlmCallResult call;
    try {
      call = chat_(build_turn_messages(context, tools_, attempt, attempt > 1 ? &failure : nullptr, options_.dialogue));
    } catch (const std::exception& e) {
      call = LlmCallResult{};
      call.error = std::string("the call failed: ") + e.what();
    }
    usage += call.usage;
    entry["wall_time_s"] = call.wall_time_s;
    entry["http_status"] = call.http_status;
    entry["http_attempts"] = call.http_attempts;
    entry["usage"] = call.usage.to_json();
    if (!call.model.empty()) entry["model"] = scrub(call.model);
    if (!call.ok) {
      const std::string error = scrub(call.error.empty() ? "the call failed (no reason given)" : call.error);
      entry["outcome"] = "call_failed";
      entry["problems"] = {error};
      failure = {"", {error}};
    } else {
      ParsedReply reply = parse_reply(call.content, tools_);
      // A model never sees the key; should a reply carry it anyway, it is not used or recorded.
      if (!secret_.empty() && call.content.find(secret_) != std::string::npos) {
        reply.problems.push_back("reply: repeats a credential; not used");
      }
      if (reply.ok()) {
        entry["outcome"] = "ok";
        d.intent = reply.intent;
        d.text = reply.text;
        d.actions = std::move(reply.actions);
        done = true;
      } else {
        if (call.finish_reason == "length") {
          reply.problems.push_back("reply: cut off at the completion token limit (max_tokens); keep the reply short");
        }
        std::vector<std::string> problems;
        for (const auto& p : reply.problems) problems.push_back(scrub(p));
        entry["outcome"] = "invalid_reply";
        entry["problems"] = problems;
        entry["reply"] = scrub(utf8_prefix(call.content, options_.recorded_reply_chars));
        failure = {scrub(call.content), problems};
      }
    }
    d.attempt_log.push_back(std::move(entry));
  }
  d.attempts = attempt;
  d.usage = usage.to_json();
  if (!done) {
    std::string last;
    for (const auto& p : failure.problems) last += (last.empty() ? "" : "; ") + p;
    d.error = "no usable reply after " + std::to_string(attempt) + " attempt" + (attempt == 1 ? "" : "s") + ": " + last;
    d.intent.clear();
    d.text.clear();
    d.actions = nlohmann::json::array();
  }
  d.latency_s = seconds_since(start_ns);
  return d;
}

}  // namespace a3::agent::llm
