// Finding JSON objects in free text (a model's reply, a prompt): the top-level balanced
// {...} spans, scanned with JSON string and escape rules, so that prose, markdown fences or
// braces inside strings around an object do not confuse it.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace a3::agent::llm {

struct TextSpan {
  std::size_t begin = 0;  // index of '{'
  std::size_t end = 0;    // one past the matching '}' (== text.size() + 1 when unclosed)
  bool closed = true;
};

// The outermost {...} spans of `text` in order (not nested ones). A final span that never
// closes is returned with closed = false.
std::vector<TextSpan> top_level_object_spans(const std::string& text);

struct ExtractedObject {
  std::optional<nlohmann::json> object;  // the first span that parses as a JSON object
  std::string error;                     // why nothing was found (names the position)
};

// `text` with every byte that is not part of a well-formed UTF-8 sequence replaced by U+FFFD, so
// that it can go into JSON (messages quoting a model's bytes, a reply kept in an attempt log).
std::string valid_utf8(const std::string& text);

// The whole text if it is a JSON object; else the first top-level span that parses as one.
// Parsed with common/json_text's limits: nesting deeper than 128, duplicate keys and invalid
// UTF-8 are refused with their place.
ExtractedObject extract_json_object(const std::string& text);

}  // namespace a3::agent::llm
