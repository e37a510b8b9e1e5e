// Parses episode text in place into a RapidJSON document with every number correctly rounded.
// RapidJSON 1.1.0's full-precision mode (kParseFullPrecisionFlag) reads a zero significand with
// an exponent as garbage: 0E120 becomes -1.8e162, 0E-120 4.4e304 (its DiyFp path takes
// __builtin_clzll(0), which is undefined; found by fuzz/fuzz_episode). Without that flag it
// rounds some numbers differently from Python, and scores must be bit-exact. So numbers come
// out of the reader as text (kParseNumbersAsStringsFlag) and are converted here with
// std::from_chars, into the value type RapidJSON itself would choose. One deliberate difference:
// RapidJSON reads 1.8e308 as infinity but refuses 1e309; every number beyond a double's range is
// refused here ("Number too big to be stored in double"), so no episode carries an infinity.
#pragma once

#include "eval/rapidjson.hpp"

#include <cstdint>
#include <optional>
#include <string_view>

#include <rapidjson/reader.h>

namespace a3::eval {

// A JSON number token as RapidJSON would store it: the narrowest of int, unsigned, int64,
// uint64 for integers that fit, else a double.
struct JsonNumber {
  enum class Kind { kInt, kUint, kInt64, kUint64, kDouble } kind = Kind::kInt;
  int64_t int_value = 0;     // kInt, kInt64
  uint64_t uint_value = 0;   // kUint, kUint64
  double double_value = 0;   // kDouble
};

// nullopt when the number's magnitude is too large for a double (RapidJSON: "Number too big").
// `token` is a valid JSON number (the reader has checked its grammar).
std::optional<JsonNumber> parse_json_number(std::string_view token);

class ExactNumberParser {
 public:
  // Parses NUL-terminated `text` in place (it is rewritten) into `document`, iteratively.
  // Errors are those of RapidJSON, offsets into `text`.
  rapidjson::ParseResult parse_insitu(rapidjson::Document& document, char* text);

  // The fast path: the same document as parse_insitu, parsed recursively (faster than
  // iteratively), for text nested at most kMaxRecursiveDepth deep (as deep as episodes may be). Returns false on any
  // error and on deeper nesting; `text` is then rewritten and the caller parses the original
  // text again with parse_insitu, whose errors and offsets are the reference.
  bool parse_insitu_shallow(rapidjson::Document& document, char* text);
  static constexpr int kMaxRecursiveDepth = 256;

 private:
  rapidjson::Reader reader_;  // keeps its stack between documents
};

}  // namespace a3::eval
