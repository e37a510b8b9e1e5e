// simdjson's document replayed as the SAX events RapidJSON's reader would have sent, into a
// RapidJSON document: one walk, strings referenced rather than copied.
#include "eval/simdjson_parser.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "eval/json_shape.hpp"
#include "eval/key_bucket.hpp"

namespace a3::eval {
namespace {

// The first document's room; simdjson grows it (up to kMaxSimdjsonTextBytes) as texts need.
constexpr std::size_t kInitialCapacityBytes = 32u << 10;

// An integer as ExactNumberParser sends it: the narrowest of int, unsigned, int64, uint64.
template <class Handler>
bool emit_integer(int64_t value, Handler& handler) {
  if (value < 0) {
    if (value >= std::numeric_limits<int32_t>::min()) return handler.Int(static_cast<int>(value));
    return handler.Int64(value);
  }
  const auto magnitude = static_cast<uint64_t>(value);
  if (magnitude <= std::numeric_limits<uint32_t>::max()) {
    return handler.Uint(static_cast<unsigned>(magnitude));
  }
  return handler.Uint64(magnitude);
}

// RapidJSON refuses a positive exponent above 308 plus the fraction's digits ("Number too big",
// even for 0e400) and a significand that would pass 1.8e308 while being read; simdjson reads
// 0e400 as 0. Such texts go to the reference: those with an exponent of three digits or more
// (found here) and those holding a number of magnitude 1e300 or more (found while emitting).
constexpr double kLargestFastMagnitude = 1e300;
constexpr int kLongExponentDigits = 3;

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Whether the exponent marker at text[at] is followed by an optional sign and three digits or
// more.
bool long_exponent_at(std::string_view text, std::size_t at) {
  std::size_t i = at + 1;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  int digits = 0;
  while (i < text.size() && is_digit(text[i]) && digits < kLongExponentDigits) ++i, ++digits;
  return digits >= kLongExponentDigits;
}

// Every 'e' or 'E' right after a digit, checked; 16 bytes at a time where SSE2 is there.
bool has_long_exponent(std::string_view text) {
  std::size_t i = 0;
#if defined(__SSE2__)
  const __m128i lower_e = _mm_set1_epi8('e'), case_bit = _mm_set1_epi8(0x20);
  const __m128i zero = _mm_set1_epi8('0'), nine = _mm_set1_epi8(9);
  unsigned previous_digit = 0;  // whether the byte before this block is a digit
  for (; i + 16 <= text.size(); i += 16) {
    const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(text.data() + i));
    const auto e_bits = static_cast<unsigned>(
        _mm_movemask_epi8(_mm_cmpeq_epi8(_mm_or_si128(bytes, case_bit), lower_e)));
    const __m128i offset = _mm_sub_epi8(bytes, zero);
    const auto digit_bits = static_cast<unsigned>(
        _mm_movemask_epi8(_mm_cmpeq_epi8(_mm_min_epu8(offset, nine), offset)));
    unsigned candidates = e_bits & ((digit_bits << 1) | previous_digit);
    previous_digit = (digit_bits >> 15) & 1u;
    for (; candidates != 0; candidates &= candidates - 1) {
      if (long_exponent_at(text, i + static_cast<std::size_t>(__builtin_ctz(candidates)))) return true;
    }
  }
#endif
  for (; i < text.size(); ++i) {
    if ((text[i] | 0x20) == 'e' && i > 0 && is_digit(text[i - 1]) && long_exponent_at(text, i)) return true;
  }
  return false;
}

rapidjson::SizeType length_of(std::string_view text) {
  return static_cast<rapidjson::SizeType>(text.size());
}

}  // namespace

SimdjsonParser::SimdjsonParser() : parser_(kMaxSimdjsonTextBytes) {
  // Without this allocation simdjson would later allocate with its own depth limit (1024), which
  // the shape check's being skipped relies on not happening: every text then goes to RapidJSON.
  usable_ = parser_.allocate(kInitialCapacityBytes, kMaxSimdjsonDepth) == simdjson::SUCCESS &&
            parser_.max_depth() == kMaxSimdjsonDepth;
}

bool SimdjsonParser::parse(rapidjson::Document& document, std::string_view text) {
  simdjson::dom::element root;
  if (!usable_ || has_long_exponent(text)) return false;
  if (parser_.parse(text.data(), text.size(), false).get(root) != simdjson::SUCCESS) return false;
  has_duplicate_key_ = false;
  bool built = false;
  auto generate = [&](rapidjson::Document& target) {
    built = emit(root, target);
    return built;
  };
  document.Populate(generate);
  return built;
}

template <class Handler>
inline bool SimdjsonParser::emit(simdjson::dom::element element, Handler& handler) {
  using Type = simdjson::dom::element_type;
  switch (element.type()) {
    case Type::NULL_VALUE: return handler.Null();
    case Type::BOOL: return handler.Bool(element.get_bool().value_unsafe());
    case Type::INT64: return emit_integer(element.get_int64().value_unsafe(), handler);
    case Type::UINT64: return handler.Uint64(element.get_uint64().value_unsafe());
    case Type::DOUBLE: {
      const double value = element.get_double().value_unsafe();
      return std::fabs(value) < kLargestFastMagnitude && handler.Double(value);
    }
    case Type::STRING: {
      const std::string_view text = element.get_string().value_unsafe();  // a view: no copy
      return handler.String(text.data(), length_of(text), false);
    }
    case Type::ARRAY: return emit_array(element.get_array().value_unsafe(), handler);
    case Type::OBJECT: return emit_object(element.get_object().value_unsafe(), handler);
  }
  return false;
}

template <class Handler>
bool SimdjsonParser::emit_array(simdjson::dom::array array, Handler& handler) {
  if (!handler.StartArray()) return false;
  rapidjson::SizeType count = 0;
  for (simdjson::dom::element child : array) {
    if (!emit(child, handler)) return false;
    ++count;
  }
  return handler.EndArray(count);
}

template <class Handler>
bool SimdjsonParser::emit_object(simdjson::dom::object object, Handler& handler) {
  if (!handler.StartObject()) return false;
  rapidjson::SizeType count = 0;
  uint64_t buckets_seen = 0;  // key_bucket.hpp: a key in a bucket already seen may repeat one
  bool may_repeat = false;
  for (simdjson::dom::key_value_pair field : object) {
    if (!handler.Key(field.key.data(), length_of(field.key), false)) return false;
    const uint64_t bucket = key_bucket_bit(field.key);
    may_repeat |= (buckets_seen & bucket) != 0;
    buckets_seen |= bucket;
    if (!emit(field.value, handler)) return false;
    ++count;
  }
  if (may_repeat && !has_duplicate_key_) has_duplicate_key_ = repeats_a_key(object);
  return handler.EndObject(count);
}

bool SimdjsonParser::repeats_a_key(simdjson::dom::object object) {
  keys_.clear();
  for (simdjson::dom::key_value_pair field : object) keys_.push_back(field.key);
  return has_repeated_key(keys_.data(), keys_.size());
}

}  // namespace a3::eval
