// The attempt ladder of one generated episode, its validation and its `_meta`.
#include "rigs/generate/generate_episode.hpp"

#include <chrono>
#include <ctime>

#include "agent/llm/json_extract.hpp"
#include "common/json_text.hpp"

namespace a3::rigs {
namespace {

using nlohmann::ordered_json;
constexpr std::size_t kQuotedReplyChars = 120;

int64_t unix_time_s() {
  return static_cast<int64_t>(
      std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch()).count());
}

std::string iso_utc(int64_t unix_s) {
  const std::time_t t = static_cast<std::time_t>(unix_s);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string quote_start(const std::string& text) {
  std::string start = agent::llm::valid_utf8(text.substr(0, kQuotedReplyChars));
  for (char& c : start) {
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  }
  return "\"" + start + (text.size() > kQuotedReplyChars ? "..." : "") + "\"";
}

ordered_json episode_meta(int64_t seed, double gen_time_s, int attempts, const agent::llm::LlmUsage& usage) {
  const int64_t ts = unix_time_s();
  ordered_json meta;
  meta["seed"] = seed;
  meta["ts"] = ts;
  meta["ts_iso"] = iso_utc(ts);
  meta["gen_time_s"] = gen_time_s;
  meta["attempts_used"] = attempts;
  meta["generation_failed"] = false;
  meta["usage"] = ordered_json::parse(common::dump_json_text(usage.to_json()));  // our own value: text is JSON
  return meta;
}

}  // namespace

bool is_endpoint_failure(const agent::llm::LlmCallResult& result) { return agent::llm::is_endpoint_failure(result); }

ordered_json episode_object_from_reply(const std::string& content, std::string& problem) {
  std::string first_problem;
  const auto object_in = [&](std::string_view text) -> std::optional<ordered_json> {
    try {
      ordered_json j = common::parse_ordered_json_text(text, "the reply's JSON object");
      if (j.is_object()) return j;
    } catch (const common::InputError& e) {
      if (first_problem.empty()) first_problem = e.what();
    }
    return std::nullopt;
  };
  if (auto whole = object_in(content)) return std::move(*whole);
  first_problem.clear();  // prose around an object is no problem; the spans' are
  for (const auto& span : agent::llm::top_level_object_spans(content)) {
    if (!span.closed) continue;
    if (auto part = object_in(std::string_view(content).substr(span.begin, span.end - span.begin))) return std::move(*part);
  }
  problem = content.empty() ? "the reply is empty"
            : !first_problem.empty() ? first_problem + " (the reply starts " + quote_start(content) + ")"
                                     : "the reply holds no JSON object: " + quote_start(content);
  return ordered_json(ordered_json::value_t::discarded);
}

GeneratedEpisode generate_episode(const GenerateChat& chat, eval::EpisodeReader& reader,
                                  const GenerateScenario& scenario, int64_t seed, const std::string& model_label) {
  GeneratedEpisode out;
  GenerateFailure previous;
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed_s = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  for (int attempt = 1; attempt <= kGenerateMaxAttempts; ++attempt) {
    out.attempts_used = attempt;
    const agent::llm::LlmCallResult call = chat(generate_messages(scenario, seed, attempt, previous));
    out.usage += call.usage;
    previous.problems.clear();
    if (!call.ok) {
      if (agent::llm::is_endpoint_failure(call)) {
        throw GenerateEndpointError(scenario_id(scenario.number) + " seed " + std::to_string(seed) + ": " +
                                    call.error);
      }
      previous.problems.push_back("the model call failed: " + call.error);
    } else {
      std::string problem;
      ordered_json episode = episode_object_from_reply(call.content, problem);
      if (episode.is_discarded()) {
        previous.problems.push_back(problem);
      } else {
        episode.erase("_meta");  // ours, not the model's
        episode["_meta"] = episode_meta(seed, elapsed_s(), attempt, out.usage);
        const std::string text = episode.dump(-1, ' ', false, ordered_json::error_handler_t::replace);
        const eval::EpisodeCheck check = reader.check_text(text);
        if (check.status == eval::EpisodeStatus::kValid) {
          out.gen_time_s = episode["_meta"]["gen_time_s"].get<double>();
          out.document = std::move(episode);
          return out;
        }
        for (const auto& v : check.violations) previous.problems.push_back(eval::to_string(v));
        if (previous.problems.empty()) previous.problems.push_back("the episode is not valid");
      }
    }
    std::string line = previous.problems.front();
    if (previous.problems.size() > 1) line += " (+" + std::to_string(previous.problems.size() - 1) + " more)";
    out.attempt_errors.push_back("attempt " + std::to_string(attempt) + ": " + line);
  }
  out.generation_failed = true;
  out.gen_time_s = elapsed_s();
  ordered_json stub;
  stub["initial_state"] = scenario.initial_state;
  stub["dialogue"] = ordered_json::array();
  stub["final_state"] = scenario.initial_state;
  stub["success"] = false;
  ordered_json meta;
  meta["model"] = model_label;
  meta["error"] = "Episode generation failed after " + std::to_string(kGenerateMaxAttempts) +
                  " attempts: " + previous.problems.front();
  meta["ts"] = unix_time_s();
  meta["generation_failed"] = true;
  stub["_meta"] = std::move(meta);
  out.document = std::move(stub);
  return out;
}

}  // namespace a3::rigs
