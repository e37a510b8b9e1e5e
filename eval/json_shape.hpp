// Checks of a parsed document that JSON itself does not make: nesting no deeper than a limit
// (so nothing after the parser recurses on the data's depth) and no duplicate keys (a3rig and
// Python's json would read different values from `"success": false, "success": true`).
// One iterative pass over the document; one checker per thread (it keeps scratch memory).
#pragma once

#include "eval/rapidjson.hpp"

#include <string>
#include <string_view>
#include <vector>

#include "common/json_text.hpp"
#include "eval/violation.hpp"

namespace a3::eval {

// Episodes a3rig writes nest about 10 deep plus what a model put into an action's args (at
// most 128, the limit of common/json_text); real α³-Bench episodes nest 9 deep.
inline constexpr int kMaxEpisodeDepth = 256;

// The same bound for nlohmann readers of episodes and their parts (sweep cells, generate's
// resume, the recorder's turns).
inline common::JsonLimits episode_json_limits() {
  common::JsonLimits limits;
  limits.max_depth = kMaxEpisodeDepth;
  return limits;
}

// Appends to `repeated` (when not null) each key that keys[0..count) holds more than once, once
// each; returns whether there is one (at the first found when `repeated` is null). Reorders
// the keys.
bool find_repeated_keys(std::string_view* keys, std::size_t count,
                        std::vector<std::string_view>* repeated);
inline bool has_repeated_key(std::string_view* keys, std::size_t count) {
  return find_repeated_keys(keys, count, nullptr);
}

class JsonShapeChecker {
 public:
  explicit JsonShapeChecker(int max_depth = kMaxEpisodeDepth) : max_depth_(max_depth) {}

  // Appends a "json-depth" violation (at the first value nested too deep; its contents are not
  // looked into) and a "json-duplicate-key" violation per duplicated key (path: the object).
  // Returns whether it appended any.
  bool check(const rapidjson::Value& root, Violations& out);

 private:
  struct Frame {
    const rapidjson::Value* container;
    rapidjson::SizeType next;  // index of the next element or member to visit
  };
  void check_keys(const rapidjson::Value& object, Violations& out);
  // JSON pointer of the value the walk last stepped into ("" for the root).
  std::string current_path() const;

  int max_depth_;
  std::vector<Frame> stack_;
  std::vector<std::string_view> keys_;
  std::vector<std::string_view> repeated_;
};

}  // namespace a3::eval
