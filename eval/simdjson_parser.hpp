// The fast path of episode parsing: simdjson (Debian's libsimdjson, SIMD throughout: UTF-8
// validation, structure and numbers) parses the text, and the RapidJSON document the rest of
// scoring reads is built from its result. The document is exactly the one ExactNumberParser
// builds from the same text: the same values, the same number kinds (int, unsigned, int64,
// uint64, double, each correctly rounded by both), the same strings and member order.
//
// It only ever says "parsed" or "not parsed". Anything simdjson refuses (a syntax error, a
// number beyond uint64, an exponent of three digits or more, a magnitude of 1e300 or more,
// nesting deeper than kMaxSimdjsonDepth, a text larger than kMaxSimdjsonTextBytes, a
// byte-order mark, a lone low surrogate \udc00 that RapidJSON takes) goes to the reference, whose verdict and messages count. What
// simdjson accepts is valid UTF-8 without NUL bytes and valid JSON for RapidJSON too
// (tests/eval/test_simdjson_parser.cpp checks both parsers on the public corpus, edits of it,
// number and string edge cases, and the episode fuzz corpus; fuzz/fuzz_episode on every input).
#pragma once

#include "eval/rapidjson.hpp"

#include <cstddef>
#include <string_view>
#include <vector>

#include <simdjson.h>

namespace a3::eval {

// Bytes the text's buffer must hold readable beyond its end.
inline constexpr std::size_t kSimdjsonPaddingBytes = simdjson::SIMDJSON_PADDING;
// Larger texts go to the reference parser: simdjson keeps about 14 bytes per byte of the
// largest text it has parsed (its tape and structural indexes), per reader, and episodes are
// 5-50 kB; at most 3.5 MiB a thread.
inline constexpr std::size_t kMaxSimdjsonTextBytes = 256u << 10;
// Below kMaxEpisodeDepth (json_shape.hpp), so what simdjson accepts is never too deep; deeper
// documents go to the reference parser, which reports them.
inline constexpr std::size_t kMaxSimdjsonDepth = 200;

class SimdjsonParser {
 public:
  SimdjsonParser();

  // Parses `text` (followed by kSimdjsonPaddingBytes readable bytes) into `document`. Strings
  // point into this parser's memory: the document is valid until the next parse. Returns false,
  // with `document` unspecified, when simdjson does not accept the text.
  bool parse(rapidjson::Document& document, std::string_view text);

  // Whether the last document parsed has an object repeating a key (then the shape check,
  // json_shape.hpp, finds and reports it; without one that check has nothing to report).
  bool has_duplicate_key() const { return has_duplicate_key_; }

 private:
  // Inlined into emit_array's and emit_object's loops: a scalar costs no call.
  template <class Handler>
  [[gnu::always_inline]] bool emit(simdjson::dom::element element, Handler& handler);
  template <class Handler>
  bool emit_array(simdjson::dom::array array, Handler& handler);
  template <class Handler>
  bool emit_object(simdjson::dom::object object, Handler& handler);
  // Whether the object has a key twice; called only when two keys share a bucket.
  bool repeats_a_key(simdjson::dom::object object);

  simdjson::dom::parser parser_;
  std::vector<std::string_view> keys_;  // one object's keys, for repeats_a_key
  bool has_duplicate_key_ = false;
  bool usable_ = false;  // simdjson's memory allocated with kMaxSimdjsonDepth
};

}  // namespace a3::eval
