// One episode of `a3rig generate` (SPEC-alpha3.md §4): up to 3 attempts, each a chat call whose
// reply must be one JSON object that, with its `_meta`, passes the episode validator (the one
// `a3rig validate` and `a3rig score` use); stricter instructions after a failed attempt;
// wall-clock time from the first attempt to the valid reply or the last failure; token usage
// summed over the attempts. `_meta` mirrors the public corpus key for key:
//   episode:      seed, ts, ts_iso, gen_time_s, attempts_used, generation_failed (false), usage
//   failure stub: model, error, ts, generation_failed (true)   (dialogue empty, final_state =
//                 initial_state, success false)
// ts is the Unix time in whole seconds when generation ended (as in the corpus), ts_iso the same
// in UTC.
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "agent/llm/llm_client.hpp"
#include "eval/episode_reader.hpp"
#include "rigs/generate/generate_prompt.hpp"

namespace a3::rigs {

// One chat call (an LlmClient's chat, or a test double).
using GenerateChat = std::function<agent::llm::LlmCallResult(const std::vector<agent::llm::ChatMessage>&)>;

// The endpoint failed in a way no retry of this episode can fix (unreachable after the client's
// retries, 401/403/404, 429 or 5xx after them): the run stops, nothing is written for the
// episode, and a later run resumes from it.
class GenerateEndpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct GeneratedEpisode {
  nlohmann::ordered_json document;   // what to write
  bool generation_failed = false;    // a failure stub
  int attempts_used = 0;
  double gen_time_s = 0.0;
  agent::llm::LlmUsage usage;        // summed over the attempts
  std::vector<std::string> attempt_errors;  // why each failed attempt failed (one line each)
};

// `model_label` is the stub's _meta.model ("provider/model"). Throws GenerateEndpointError as
// above.
GeneratedEpisode generate_episode(const GenerateChat& chat, eval::EpisodeReader& reader,
                                  const GenerateScenario& scenario, int64_t seed, const std::string& model_label);

// The reply's JSON object: the whole content, else its first {...} that parses as an object
// (prose or a markdown fence around it). Keys keep the model's order. Returns a discarded value
// and sets `problem` when there is none.
nlohmann::ordered_json episode_object_from_reply(const std::string& content, std::string& problem);

// Whether a failed call is the endpoint's fault (GenerateEndpointError) rather than this
// request's (a failed attempt): no HTTP answer, 401, 403, 404, 408, 429 or 5xx.
bool is_endpoint_failure(const agent::llm::LlmCallResult& result);

}  // namespace a3::rigs
