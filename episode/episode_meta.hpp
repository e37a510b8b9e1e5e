// `_meta` of an episode (SPEC-alpha3.md §1): how it was generated. Every field optional, as in
// the corpus; a field that is present with the wrong type is an InputError naming it.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace a3::episode {

struct EpisodeMeta {
  bool present = false;                 // the episode has a `_meta` object
  bool generation_failed = false;       // a failure stub: every generation attempt failed
  std::optional<std::string> error;     // a stub's recorded error
  std::optional<int64_t> seed;          // the episode seed (a number; a fraction is truncated)
  std::optional<double> gen_time_s;     // the model's wall time for the episode, s
  std::optional<double> attempts_used;  // generation attempts (SPEC §3)
  std::optional<nlohmann::json> usage;  // token counts and cost, as recorded (an object)

  // A count of `usage` (prompt_tokens, completion_tokens, total_tokens), rounded; 0 if absent.
  int64_t usage_count(const char* key) const;
};

// A token count of a `usage` object, rounded to an integer; 0 when absent or not a number.
int64_t usage_count(const nlohmann::json& usage, const char* key);

// Reads `meta` (the `_meta` value); `where` is e.g. "ep.json: /_meta". Throws common::InputError.
EpisodeMeta read_episode_meta(const nlohmann::ordered_json& meta, const std::string& where);

}  // namespace a3::episode
