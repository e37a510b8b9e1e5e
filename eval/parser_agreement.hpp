// The check that scoring's two parsers agree (simdjson_parser.hpp, the fast path, and
// exact_numbers.hpp, the reference): whenever simdjson accepts a text, the reference's checks
// accept it too (UTF-8, no NUL byte, JSON, depth), both build the identical document (types,
// number kinds, every double's bits, strings, member order), and the fast path's duplicate-key
// answer is the shape check's. Used by tests/eval/test_simdjson_parser.cpp and by the episode
// fuzz target on every input.
#pragma once

#include "eval/rapidjson.hpp"

#include <optional>
#include <string>
#include <string_view>

namespace a3::eval {

struct ParserAgreement {
  bool fast_accepted = false;               // simdjson parsed the text
  std::optional<std::string> disagreement;  // what differs, when something does
};

ParserAgreement compare_parsers(std::string_view text);

// The same type, number kind and bits, string bytes, and members in the same order.
bool identical_json(const rapidjson::Value& a, const rapidjson::Value& b);

}  // namespace a3::eval
