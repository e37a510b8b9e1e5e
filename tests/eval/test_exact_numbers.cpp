// Numbers in episodes are read correctly rounded, into the value type RapidJSON would choose,
// and a zero significand with an exponent (0E120) is zero: RapidJSON 1.1.0's full-precision
// mode read it as -1.8e162 (found by fuzz/fuzz_episode).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "eval/episode_reader.hpp"
#include "eval/episode_schema.hpp"
#include "eval/exact_numbers.hpp"
#include "tests/eval/episode_builder.hpp"

namespace a3::eval {
namespace {

uint64_t bits(double d) {
  uint64_t b;
  std::memcpy(&b, &d, sizeof b);
  return b;
}

// Same type flags and the same value, bit for bit.
void expect_same_number(const rapidjson::Value& ours, const rapidjson::Value& theirs,
                        const std::string& token) {
  SCOPED_TRACE(token);
  EXPECT_EQ(ours.IsInt(), theirs.IsInt());
  EXPECT_EQ(ours.IsUint(), theirs.IsUint());
  EXPECT_EQ(ours.IsInt64(), theirs.IsInt64());
  EXPECT_EQ(ours.IsUint64(), theirs.IsUint64());
  EXPECT_EQ(ours.IsDouble(), theirs.IsDouble());
  if (theirs.IsDouble()) {
    EXPECT_EQ(bits(ours.GetDouble()), bits(theirs.GetDouble()));
  } else if (theirs.IsInt64()) {
    EXPECT_EQ(ours.GetInt64(), theirs.GetInt64());
  } else {
    EXPECT_EQ(ours.GetUint64(), theirs.GetUint64());
  }
}

void expect_like_rapidjson(const std::string& token) {
  std::string ours_text = "[" + token + "]", theirs_text = ours_text;
  rapidjson::Document ours, theirs;
  ExactNumberParser parser;
  const auto result = parser.parse_insitu(ours, ours_text.data());
  theirs.ParseInsitu<rapidjson::kParseFullPrecisionFlag>(theirs_text.data());
  ASSERT_EQ(result.Code(), theirs.GetParseError()) << token;
  if (!result.IsError()) expect_same_number(ours[0], theirs[0], token);
}

// Near a double's limits RapidJSON 1.1.0 is wrong too (1.8e308 → nan, -5.6e308 → 1.2e-308):
// there the reference is glibc's strtod, correctly rounded, and an overflow is refused.
void expect_like_strtod(const std::string& token) {
  SCOPED_TRACE(token);
  std::string text = "[" + token + "]";
  rapidjson::Document ours;
  ExactNumberParser parser;
  const auto result = parser.parse_insitu(ours, text.data());
  const double reference = std::strtod(token.c_str(), nullptr);
  if (std::isinf(reference)) {
    EXPECT_EQ(result.Code(), rapidjson::kParseErrorNumberTooBig);
    return;
  }
  ASSERT_FALSE(result.IsError());
  ASSERT_TRUE(ours[0].IsDouble());
  EXPECT_EQ(bits(ours[0].GetDouble()), bits(reference));
}

TEST(ExactNumbers, IntegersTakeTheNarrowestTypeRapidJsonChooses) {
  for (const char* token :
       {"0", "-0", "1", "-1", "2147483647", "2147483648", "-2147483648", "-2147483649",
        "4294967295", "4294967296", "9223372036854775807", "9223372036854775808",
        "-9223372036854775808", "-9223372036854775809", "18446744073709551615",
        "18446744073709551616", "123456789012345678901234567890"}) {
    expect_like_rapidjson(token);
  }
}

TEST(ExactNumbers, DecimalsAreCorrectlyRoundedLikeFullPrecisionRapidJson) {
  for (const char* token :
       {"0.1", "-0.0", "0.0", "1e5", "1E+5", "1.5e-5", "2.2250738585072014e-308",
        "4.9e-324", "1e-320", "1.7976931348623157e308", "0.30000000000000004",
        "9007199254740993", "9007199254740993.0", "123.456e-7", "1e-400", "-1e-400",
        "0.000001", "100000000000000000000000.5", "1e309"}) {
    expect_like_rapidjson(token);
  }
}

TEST(ExactNumbers, NumbersNearADoublesLimitsAreCorrectlyRoundedOrRefused) {
  for (const char* token : {"1.7976931348623157e308", "1.79769313486231581e308", "1.8e308",
                            "-2e308", "1e309", "-5563338987231754765555e287", "2e-324",
                            "2.4703282292062328e-324", "-1e-400"}) {
    expect_like_strtod(token);
  }
}

TEST(ExactNumbers, RandomDecimalsAgreeWithFullPrecisionRapidJson) {
  std::mt19937_64 random(20261125);
  std::uniform_int_distribution<int> digit(0, 9), length(1, 25), exponent(-300, 280);
  for (int n = 0; n < 20000; ++n) {
    std::string token = (n % 3 == 0) ? "-" : "";
    token += static_cast<char>('1' + digit(random) % 9);  // a nonzero significand
    const int digits = length(random);
    for (int i = 0; i < digits; ++i) {
      if (i == digits / 2 && n % 2 == 0) token += '.';
      token += static_cast<char>('0' + digit(random));
    }
    if (n % 4 != 0) token += "e" + std::to_string(exponent(random) % (n % 5 == 0 ? 20 : 290));
    expect_like_rapidjson(token);
    if (token.find_first_of(".e") != std::string::npos) expect_like_strtod(token);
    if (HasFailure()) return;
  }
}

// Decimals of at most 15 digits without an exponent take a shortcut (one division): it must
// give strtod's correctly rounded double, bit for bit, at every length and point position; 16
// digits and more take the general path.
TEST(ExactNumbers, ShortDecimalsAgreeWithStrtodBitForBit) {
  for (const char* token : {"0.0", "-0.0", "0.1", "-0.35", "240.0", "0.000000000000001",
                            "999999999999999.0", "99999999999999.9", "0.999999999999999",
                            "9999999999999999.9", "0.30000000000000004", "1.000000000000000"}) {
    expect_like_strtod(token);
  }
  std::mt19937_64 random(20261127);
  std::uniform_int_distribution<int> digit(0, 9), length(1, 17);
  for (int n = 0; n < 200000; ++n) {
    const int digits = length(random);
    std::uniform_int_distribution<int> point_at(1, digits);
    const int point = point_at(random);
    std::string token = (n % 2 == 0) ? "-" : "";
    for (int i = 0; i < digits; ++i) {
      // JSON allows one leading zero only: the integer part is "0" or starts with 1-9.
      const bool leading = i == 0 && point > 1;
      token += static_cast<char>(leading ? '1' + digit(random) % 9 : '0' + digit(random));
      if (i + 1 == point && point < digits) token += '.';
    }
    if (token.find('.') == std::string::npos) token += ".5";
    expect_like_strtod(token);
    if (HasFailure()) return;
  }
}

TEST(ExactNumbers, AZeroSignificandWithAnExponentIsZero) {
  for (const char* token : {"0E120", "0e-120", "0.000E120", "0.0e5", "0E400", "-0E120"}) {
    SCOPED_TRACE(token);
    const auto number = parse_json_number(token);
    ASSERT_TRUE(number);
    EXPECT_EQ(number->kind, JsonNumber::Kind::kDouble);
    EXPECT_EQ(number->double_value, 0.0);
    EXPECT_EQ(std::signbit(number->double_value), token[0] == '-');
  }
}

TEST(ExactNumbers, ANumberTooBigForADoubleIsASyntaxErrorAtItsStart) {
  std::string text = "[1, 1e400]";
  rapidjson::Document document;
  ExactNumberParser parser;
  const auto result = parser.parse_insitu(document, text.data());
  EXPECT_EQ(result.Code(), rapidjson::kParseErrorNumberTooBig);
  EXPECT_EQ(result.Offset(), 4u);
}

TEST(ExactNumbers, OtherSyntaxErrorsKeepRapidJsonsCodeAndOffset) {
  for (const char* text : {"[0E120.0]", "{\"a\": 1.}", "[1, 2", "[-]", "{\"a\" 1}"}) {
    SCOPED_TRACE(text);
    std::string ours_text = text, theirs_text = text;
    rapidjson::Document ours, theirs;
    ExactNumberParser parser;
    const auto result = parser.parse_insitu(ours, ours_text.data());
    theirs.ParseInsitu<rapidjson::kParseFullPrecisionFlag>(theirs_text.data());
    EXPECT_EQ(result.Code(), theirs.GetParseError());
    EXPECT_EQ(result.Offset(), theirs.GetErrorOffset());
  }
}

TEST(ExactNumbers, AnEpisodeWithZeroTimesAnExponentScoresZeroNotGarbage) {
  const ScoringProfile profile = release_profile();
  const JsonSchemaValidator validator{episode_schema_json(), kEpisodeSchemaName};
  EpisodeReader reader{validator, profile};
  std::string text = a3::test::make_episode().dump();
  const std::string gen_time = "\"gen_time_s\":10.0";
  ASSERT_NE(text.find(gen_time), std::string::npos);
  text.replace(text.find(gen_time), gen_time.size(), "\"gen_time_s\":0E120");
  const EpisodeCheck check = reader.check_text(text);
  ASSERT_EQ(check.status, EpisodeStatus::kValid);
  EXPECT_EQ(check.facts.gen_time_s, 0.0);
}

}  // namespace
}  // namespace a3::eval
