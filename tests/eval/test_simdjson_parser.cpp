// Scoring's fast parser (simdjson, eval/simdjson_parser.hpp) against the reference parser
// (RapidJSON with exact numbers): the same document, bit for bit, for every text simdjson
// accepts (numbers at every edge of their kinds, strings and escapes, nesting, duplicate keys,
// the public episodes and thousands of byte-level edits of them, the episode fuzz corpus), and
// the cases it refuses go to the reference. Public episodes are read from $A3_SHARED_DIR.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "eval/episode_reader.hpp"
#include "eval/episode_schema.hpp"
#include "eval/parser_agreement.hpp"
#include "eval/simdjson_parser.hpp"
#include "tests/eval/schema_agreement.hpp"
#include "tests/test_support.hpp"

namespace a3::eval {
namespace {

namespace fs = std::filesystem;

// Both parsers agree and simdjson accepted the text (so the fast path really was compared).
void expect_accepted_alike(const std::string& text) {
  const ParserAgreement result = compare_parsers(text);
  EXPECT_TRUE(result.fast_accepted) << text;
  EXPECT_FALSE(result.disagreement) << text << ": " << result.disagreement.value_or("");
}

// Both parsers agree, whichever of them parsed the text.
void expect_alike(const std::string& text) {
  const ParserAgreement result = compare_parsers(text);
  EXPECT_FALSE(result.disagreement) << text << ": " << result.disagreement.value_or("");
}

void expect_refused(const std::string& text) {
  EXPECT_FALSE(compare_parsers(text).fast_accepted) << text;
}

std::string nested_arrays(int depth) { return std::string(depth, '[') + std::string(depth, ']'); }

TEST(SimdjsonParser, IntegersTakeTheReferenceKinds) {
  for (const char* token :
       {"0", "-0", "1", "-1", "2147483647", "2147483648", "-2147483648", "-2147483649",
        "4294967295", "4294967296", "9223372036854775807", "9223372036854775808",
        "-9223372036854775808", "18446744073709551615"}) {
    expect_accepted_alike(std::string("[") + token + "]");
    expect_accepted_alike(std::string("{\"n\":") + token + "}");
  }
}

TEST(SimdjsonParser, IntegersBeyondUint64GoToTheReference) {
  for (const char* token : {"18446744073709551616", "-9223372036854775809", "123456789012345678901234567890"}) {
    expect_refused(std::string("[") + token + "]");
  }
}

TEST(SimdjsonParser, DecimalsAreTheSameDoublesBitForBit) {
  for (const char* token :
       {"0.0", "-0.0", "1.0", "0.1", "-0.35", "240.0", "1e2", "1E2", "1e-2", "-1.5e+3", "1e-99",
        "9.99e99", "9007199254740993.0", "1.00000000000000011102230246251565404236316680908203125",
        "0.30000000000000004", "123456789012345678901234567890.5", "3.141592653589793238462643383279",
        "0.000000000000000000000000000000000000000000000000000000000000000001"}) {
    expect_accepted_alike(std::string("[") + token + "]");
  }
  // Long exponents and huge magnitudes are the reference's (LongExponentsGoToTheReference).
  for (const char* token : {"0e120", "0E-120", "1e-400", "-1e-400", "4.9e-324", "5e-324",
                            "2.2250738585072014e-308", "1.7976931348623157e308"}) {
    expect_alike(std::string("[") + token + "]");
  }
  // Random doubles written shortest-exact and with 17 digits, and random short decimals.
  std::mt19937_64 random(20261127);
  std::uniform_int_distribution<uint64_t> any_bits;
  std::uniform_int_distribution<int> digits(0, 999999), places(0, 6);
  for (int i = 0; i < 3000; ++i) {
    uint64_t bits = any_bits(random);
    double value;
    std::memcpy(&value, &bits, sizeof value);
    if (!std::isfinite(value)) continue;
    char text[96];
    // The width is at most 7 (places), which GCC at -O1 cannot see: the output fits in 96.
    const int width = std::min(places(random) + 1, 7);
    if (std::snprintf(text, sizeof text, "[%.17g,%g,%d.%0*d]", value, value, digits(random), width,
                      digits(random) % 10) >= static_cast<int>(sizeof text)) {
      continue;
    }
    const ParserAgreement result = compare_parsers(text);
    EXPECT_FALSE(result.disagreement) << text << ": " << result.disagreement.value_or("");
    // Doubles in [1e-99, 1e99] have short exponents: simdjson takes them.
    if (std::fabs(value) > 1e-99 && std::fabs(value) < 1e99) {
      EXPECT_TRUE(result.fast_accepted) << text;
    }
  }
}

TEST(SimdjsonParser, NumbersBeyondADoubleGoToTheReference) {
  expect_refused("[1e309]");
  expect_refused("[-1.8e308]");
  expect_refused("[1e300]");  // a magnitude of 1e300 or more: near RapidJSON's own limits
  expect_refused("[1" + std::string(305, '0') + ".5]");
}

// RapidJSON refuses 0e400 ("Number too big") where simdjson reads 0: a long exponent anywhere,
// at every position against the 16-byte blocks of the scan, sends the text to the reference.
TEST(SimdjsonParser, LongExponentsGoToTheReference) {
  for (int pad = 0; pad < 40; ++pad) {
    const std::string spaces(static_cast<std::size_t>(pad), ' ');
    for (const char* token : {"0e400", "0E+400", "1e-400", "2e100", "0e0000001"}) {
      expect_refused("[" + spaces + token + "]");
    }
    expect_accepted_alike("[" + spaces + "1e99, 1e-99, 0.5E+12]");
  }
  // Conservative: a digit, an 'e' and three digits inside a string count too.
  expect_refused(R"(["build 3e100"])");
  expect_accepted_alike(R"(["elevation 3 e100", "e100"])");
}

TEST(SimdjsonParser, StringsAndEscapesAlike) {
  for (const char* text :
       {R"(["", "a", "\"", "\\", "\/", "\b\f\n\r\t", "\u0041\u00e9\u20ac"])",
        R"(["\u0000", "a\u0000b", "\ud83d\ude00", "\uD83D\uDE00"])", "[\"\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80\"]",
        R"({"\u0000":1, "k\u00e9y":2, "":3})", "[\"\x7f\"]", "[1.5e3e]"}) {
    const ParserAgreement result = compare_parsers(text);
    EXPECT_FALSE(result.disagreement) << text << ": " << result.disagreement.value_or("");
  }
  expect_accepted_alike(R"(["\u0000", "a\u0000b", "\ud83d\ude00"])");
}

TEST(SimdjsonParser, WhatSimdjsonRefusesGoesToTheReference) {
  expect_refused("\xEF\xBB\xBF{}");   // a byte-order mark, which RapidJSON reads
  expect_refused(R"(["\udc00"])");    // a lone low surrogate, which RapidJSON takes
  expect_refused("[\"\xc0\x80\"]");    // an overlong form
  expect_refused("[1,]");
  expect_refused(std::string("[\"a\0b\"]", 7));
  expect_refused(std::string(kMaxSimdjsonTextBytes + 1, ' ') + "[]");
}

TEST(SimdjsonParser, NestingBeyondItsLimitGoesToTheReference) {
  expect_accepted_alike(nested_arrays(static_cast<int>(kMaxSimdjsonDepth)));
  expect_refused(nested_arrays(static_cast<int>(kMaxSimdjsonDepth) + 1));
  expect_refused(nested_arrays(kMaxEpisodeDepth + 1));
}

TEST(SimdjsonParser, DuplicateKeysAreFoundAsTheShapeCheckFindsThem) {
  expect_accepted_alike(R"({"a":1,"a":2})");
  expect_accepted_alike(R"({"a":{"b":1,"c":{"d":1,"d":1}},"b":2})");
  expect_accepted_alike(R"([{"a":1},{"a":1},{"x":[{"y":1,"z":2,"y":3}]}])");
  std::string wide = "{", wide_repeated = "{";
  for (int i = 0; i < 40; ++i) {
    wide += (i ? "," : "") + std::string("\"k") + std::to_string(i) + "\":" + std::to_string(i);
  }
  wide_repeated = wide + ",\"k17\":0}";
  wide += "}";
  expect_accepted_alike(wide);
  expect_accepted_alike(wide_repeated);
  SimdjsonParser parser;
  rapidjson::Document document;
  std::string padded = wide_repeated + std::string(kSimdjsonPaddingBytes, ' ');
  ASSERT_TRUE(parser.parse(document, std::string_view(padded.data(), wide_repeated.size())));
  EXPECT_TRUE(parser.has_duplicate_key());
  padded = wide + std::string(kSimdjsonPaddingBytes, ' ');
  ASSERT_TRUE(parser.parse(document, std::string_view(padded.data(), wide.size())));
  EXPECT_FALSE(parser.has_duplicate_key());
}

// The reader takes the fast path for an episode and still reports a duplicate key, by path.
TEST(SimdjsonParser, TheReaderReportsDuplicateKeysFoundOnTheFastPath) {
  const JsonSchemaValidator validator(episode_schema_json(), kEpisodeSchemaName);
  const ScoringProfile profile = release_profile();
  EpisodeReader reader(validator, profile);
  const EpisodeCheck check = reader.check_text(R"({"dialogue": [{"speaker": "agent", "speaker": "user"}]})");
  ASSERT_EQ(check.status, EpisodeStatus::kInvalid);
  ASSERT_EQ(check.violations.size(), 1u);
  EXPECT_EQ(check.violations[0].rule, "json-duplicate-key");
  EXPECT_EQ(check.violations[0].json_path, "/dialogue/0");
}

// One byte deleted, inserted or replaced, from characters that matter to JSON.
std::string edited(const std::string& text, std::mt19937_64& random) {
  static const std::string kBytes = "{}[],:\"\\0123456789.eE-+ tfnu\xc3\xa9\x80";
  std::string out = text;
  const std::size_t at = std::uniform_int_distribution<std::size_t>(0, out.size() - 1)(random);
  const char byte = kBytes[std::uniform_int_distribution<std::size_t>(0, kBytes.size() - 1)(random)];
  switch (random() % 3) {
    case 0: out.erase(at, 1); break;
    case 1: out.insert(out.begin() + static_cast<std::ptrdiff_t>(at), byte); break;
    default: out[at] = byte; break;
  }
  return out;
}

TEST(SimdjsonParser, EveryPublicEpisodeAndEditsOfIt) {
  A3_REQUIRE_SHARED(corpus, "alphabench");
  std::mt19937_64 random(16);
  int files = 0, edits = 0, edits_accepted = 0;
  for (const fs::path& path : testing::json_files_under(corpus)) {
    const std::string text = testing::read_file(path);
    expect_accepted_alike(text);
    ++files;
    for (int i = 0; i < 100; ++i) {
      const std::string variant = edited(text, random);
      const ParserAgreement result = compare_parsers(variant);
      EXPECT_FALSE(result.disagreement) << path << " edit " << i << ": " << result.disagreement.value_or("");
      ++edits;
      edits_accepted += result.fast_accepted ? 1 : 0;
    }
  }
  std::cout << files << " public episodes, " << edits << " edits (" << edits_accepted
            << " of them JSON that simdjson accepted)\n";
  EXPECT_GE(files, 100);
  EXPECT_GT(edits_accepted, edits / 20);  // the edits reach the documents, not only the syntax
}

TEST(SimdjsonParser, TheEpisodeFuzzCorpus) {
  const fs::path source = a3::test::source_dir();
  int files = 0, accepted = 0;
  for (const fs::path& folder : {source / "fuzz/corpus/episode", source / "tests/data/fuzz/episode"}) {
    ASSERT_TRUE(fs::is_directory(folder)) << folder;
    for (const auto& entry : fs::directory_iterator(folder)) {
      if (!entry.is_regular_file()) continue;
      const ParserAgreement result = compare_parsers(testing::read_file(entry.path()));
      EXPECT_FALSE(result.disagreement) << entry.path() << ": " << result.disagreement.value_or("");
      ++files;
      accepted += result.fast_accepted ? 1 : 0;
    }
  }
  EXPECT_GE(files, 30);
  EXPECT_GT(accepted, 0);
}

}  // namespace
}  // namespace a3::eval
