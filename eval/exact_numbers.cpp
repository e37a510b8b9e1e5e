#include "eval/exact_numbers.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <locale.h>
#include <string>

namespace a3::eval {
namespace {

constexpr unsigned kRecursiveReaderFlags =
    rapidjson::kParseInsituFlag | rapidjson::kParseNumbersAsStringsFlag;
constexpr unsigned kReaderFlags = kRecursiveReaderFlags | rapidjson::kParseIterativeFlag;

bool is_integer_token(std::string_view token) {
  return token.find_first_of(".eE") == std::string_view::npos;
}

// from_chars reports out_of_range for both overflow and underflow without a value: strtod in
// the C locale tells them apart (underflow rounds to ±0, as RapidJSON does).
std::optional<double> out_of_range_double(std::string_view token) {
  static const locale_t c_locale = newlocale(LC_ALL_MASK, "C", locale_t{});
  const std::string copy(token);
  const double value = strtod_l(copy.c_str(), nullptr, c_locale);
  if (std::isinf(value)) return std::nullopt;
  return value;
}

// Clinger's fast path, for the decimals episodes are made of ("240.0", "-0.35"): with at most
// 15 digits and no exponent, the token is m / 10^k with m < 2^53 and 10^k (k <= 15) exact
// doubles, and one IEEE division rounds correctly: the double from_chars gives, sooner.
std::optional<double> short_decimal(std::string_view token) {
  static constexpr double kPowersOf10[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                           1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  constexpr int kMaxDigits = 15;
  const bool negative = !token.empty() && token.front() == '-';
  uint64_t mantissa = 0;
  int digits = 0, fraction_digits = 0;
  bool point = false;
  for (std::size_t i = negative ? 1 : 0; i < token.size(); ++i) {
    const char c = token[i];
    if (c == '.' && !point) {
      point = true;
      continue;
    }
    if (c < '0' || c > '9' || ++digits > kMaxDigits) return std::nullopt;  // an exponent, or long
    mantissa = mantissa * 10 + static_cast<uint64_t>(c - '0');
    fraction_digits += point ? 1 : 0;
  }
  if (digits == 0) return std::nullopt;
  const double value = static_cast<double>(mantissa) / kPowersOf10[fraction_digits];
  return negative ? -value : value;
}

std::optional<JsonNumber> parse_double(std::string_view token) {
  JsonNumber number;
  number.kind = JsonNumber::Kind::kDouble;
  if (const auto value = short_decimal(token)) {
    number.double_value = *value;
    return number;
  }
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(),
                                            number.double_value);
  if (error == std::errc::result_out_of_range) {
    const auto value = out_of_range_double(token);
    if (!value) return std::nullopt;
    number.double_value = *value;
  }
  return number;
}

std::optional<JsonNumber> parse_integer(std::string_view token) {
  const char* first = token.data();
  const char* last = token.data() + token.size();
  JsonNumber number;
  if (token.front() == '-') {
    if (std::from_chars(first, last, number.int_value).ec != std::errc{}) return parse_double(token);
    const bool fits_int = number.int_value >= std::numeric_limits<int32_t>::min();
    number.kind = fits_int ? JsonNumber::Kind::kInt : JsonNumber::Kind::kInt64;
    return number;
  }
  if (std::from_chars(first, last, number.uint_value).ec != std::errc{}) return parse_double(token);
  const bool fits_uint = number.uint_value <= std::numeric_limits<uint32_t>::max();
  number.kind = fits_uint ? JsonNumber::Kind::kUint : JsonNumber::Kind::kUint64;
  return number;
}

// Forwards SAX events to the document, converting number text itself.
class ExactNumberHandler {
 public:
  // max_depth: nesting beyond it stops the parse (the recursive reader's stack is bounded).
  ExactNumberHandler(rapidjson::Document& document, const char* text,
                     int max_depth = std::numeric_limits<int>::max())
      : document_(document), text_(text), max_depth_(max_depth) {}

  bool Null() { return document_.Null(); }
  bool Bool(bool b) { return document_.Bool(b); }
  bool Int(int i) { return document_.Int(i); }
  bool Uint(unsigned u) { return document_.Uint(u); }
  bool Int64(int64_t i) { return document_.Int64(i); }
  bool Uint64(uint64_t u) { return document_.Uint64(u); }
  bool Double(double d) { return document_.Double(d); }
  bool String(const char* s, rapidjson::SizeType n, bool copy) { return document_.String(s, n, copy); }
  bool Key(const char* s, rapidjson::SizeType n, bool copy) { return document_.Key(s, n, copy); }
  bool StartObject() { return ++depth_ <= max_depth_ && document_.StartObject(); }
  bool EndObject(rapidjson::SizeType n) {
    --depth_;
    return document_.EndObject(n);
  }
  bool StartArray() { return ++depth_ <= max_depth_ && document_.StartArray(); }
  bool EndArray(rapidjson::SizeType n) {
    --depth_;
    return document_.EndArray(n);
  }

  bool RawNumber(const char* s, rapidjson::SizeType n, bool) {
    const auto number = parse_json_number(std::string_view(s, n));
    if (!number) {
      too_big_offset_ = static_cast<std::size_t>(s - text_);
      return false;
    }
    switch (number->kind) {
      case JsonNumber::Kind::kInt: return document_.Int(static_cast<int>(number->int_value));
      case JsonNumber::Kind::kUint: return document_.Uint(static_cast<unsigned>(number->uint_value));
      case JsonNumber::Kind::kInt64: return document_.Int64(number->int_value);
      case JsonNumber::Kind::kUint64: return document_.Uint64(number->uint_value);
      case JsonNumber::Kind::kDouble: return document_.Double(number->double_value);
    }
    return false;
  }

  std::optional<std::size_t> too_big_offset() const { return too_big_offset_; }

 private:
  rapidjson::Document& document_;
  const char* text_;
  int max_depth_;
  int depth_ = 0;
  std::optional<std::size_t> too_big_offset_;
};

}  // namespace

std::optional<JsonNumber> parse_json_number(std::string_view token) {
  if (token.empty()) return std::nullopt;
  return is_integer_token(token) ? parse_integer(token) : parse_double(token);
}

rapidjson::ParseResult ExactNumberParser::parse_insitu(rapidjson::Document& document, char* text) {
  rapidjson::InsituStringStream stream(text);
  rapidjson::ParseResult result;
  std::optional<std::size_t> too_big;
  auto generate = [&](rapidjson::Document& target) {
    ExactNumberHandler handler(target, text);
    result = reader_.Parse<kReaderFlags>(stream, handler);
    too_big = handler.too_big_offset();
    return !result.IsError();
  };
  document.Populate(generate);
  if (too_big) result.Set(rapidjson::kParseErrorNumberTooBig, *too_big);
  return result;
}

bool ExactNumberParser::parse_insitu_shallow(rapidjson::Document& document, char* text) {
  rapidjson::InsituStringStream stream(text);
  bool parsed = false;
  auto generate = [&](rapidjson::Document& target) {
    ExactNumberHandler handler(target, text, kMaxRecursiveDepth);
    parsed = !reader_.Parse<kRecursiveReaderFlags>(stream, handler).IsError();
    return parsed;
  };
  document.Populate(generate);
  return parsed;
}

}  // namespace a3::eval
