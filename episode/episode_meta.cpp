// Reading `_meta`.
#include "episode/episode_meta.hpp"

#include <cmath>

#include "common/json_file.hpp"

namespace a3::episode {
namespace {

using common::InputError;
using Value = nlohmann::ordered_json;

// The finite number at `key`, if present.
std::optional<double> number_at(const Value& meta, const char* key, const std::string& where) {
  const auto it = meta.find(key);
  if (it == meta.end()) return std::nullopt;
  if (!it->is_number() || !std::isfinite(it->get<double>())) {
    throw InputError(where + "/" + key + ": expected a number, got " + std::string(it->type_name()));
  }
  return it->get<double>();
}

}  // namespace

int64_t usage_count(const nlohmann::json& usage, const char* key) {
  const auto it = usage.find(key);
  if (it == usage.end() || !it->is_number()) return 0;
  if (it->is_number_float()) {
    const double x = it->get<double>();
    return std::fabs(x) < 9.2e18 ? static_cast<int64_t>(std::llround(x)) : 0;  // beyond int64: no count
  }
  return it->get<int64_t>();
}

int64_t EpisodeMeta::usage_count(const char* key) const { return usage ? episode::usage_count(*usage, key) : 0; }

EpisodeMeta read_episode_meta(const Value& meta, const std::string& where) {
  EpisodeMeta m;
  m.present = true;
  if (const auto it = meta.find("generation_failed"); it != meta.end()) {
    if (!it->is_boolean()) throw InputError(where + "/generation_failed: expected true or false");
    m.generation_failed = it->get<bool>();
  }
  if (const auto it = meta.find("error"); it != meta.end() && it->is_string()) m.error = it->get<std::string>();
  if (const auto it = meta.find("seed"); it != meta.end()) {
    if (!it->is_number()) throw InputError(where + "/seed: expected a number, got " + std::string(it->type_name()));
    // A fraction is truncated; a float beyond int64's range has no integer seed (and casting it is UB).
    if (it->is_number_float() && !(std::fabs(it->get<double>()) < 9.2e18)) {
      throw InputError(where + "/seed: out of the 64-bit integer range");
    }
    m.seed = it->is_number_float() ? static_cast<int64_t>(it->get<double>()) : it->get<int64_t>();
  }
  m.gen_time_s = number_at(meta, "gen_time_s", where);
  m.attempts_used = number_at(meta, "attempts_used", where);
  if (const auto it = meta.find("usage"); it != meta.end()) {
    if (!it->is_object()) throw InputError(where + "/usage: expected an object, got " + std::string(it->type_name()));
    m.usage = nlohmann::json(*it);
  }
  return m;
}

}  // namespace a3::episode
