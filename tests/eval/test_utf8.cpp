// find_invalid_utf8: RFC 3629 validity (no overlong forms, no surrogates, nothing above U+10FFFF)
// and the offset it reports, before, inside and after its eight-byte ASCII fast path.
#include <gtest/gtest.h>

#include "eval/utf8.hpp"

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace {

using a3::eval::find_invalid_utf8;

std::string bytes(std::initializer_list<unsigned> values) {
  std::string s;
  for (unsigned v : values) s += static_cast<char>(v);
  return s;
}

// The shortest UTF-8 form of a code point; surrogates are encoded like any other value (CESU
// style), which is exactly what a validator must reject.
std::string encode(uint32_t cp) {
  if (cp < 0x80) return bytes({cp});
  if (cp < 0x800) return bytes({0xC0 | (cp >> 6), 0x80 | (cp & 0x3F)});
  if (cp < 0x10000) return bytes({0xE0 | (cp >> 12), 0x80 | ((cp >> 6) & 0x3F), 0x80 | (cp & 0x3F)});
  return bytes({0xF0 | (cp >> 18), 0x80 | ((cp >> 12) & 0x3F), 0x80 | ((cp >> 6) & 0x3F),
                0x80 | (cp & 0x3F)});
}

// A straightforward decoder (RFC 3629 §4 by value, not by byte ranges), as the reference.
std::optional<std::size_t> reference_find_invalid(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    std::size_t length;
    uint32_t cp;
    if (c < 0x80) {
      ++i;
      continue;
    } else if ((c & 0xE0) == 0xC0) {
      length = 2;
      cp = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
      length = 3;
      cp = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
      length = 4;
      cp = c & 0x07;
    } else {
      return i;
    }
    if (i + length > s.size()) return i;
    for (std::size_t k = 1; k < length; ++k) {
      const auto b = static_cast<unsigned char>(s[i + k]);
      if ((b & 0xC0) != 0x80) return i;
      cp = (cp << 6) | (b & 0x3F);
    }
    const uint32_t smallest[] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < smallest[length] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return i;
    i += length;
  }
  return std::nullopt;
}

TEST(FindInvalidUtf8, AcceptsAsciiIncludingNulAndEmptyText) {
  EXPECT_EQ(find_invalid_utf8(""), std::nullopt);
  std::string all_ascii;
  for (int c = 0; c < 0x80; ++c) all_ascii += static_cast<char>(c);
  EXPECT_EQ(find_invalid_utf8(all_ascii), std::nullopt);
  EXPECT_EQ(find_invalid_utf8(R"({"speaker": "agent", "turn": 1})"), std::nullopt);
}

TEST(FindInvalidUtf8, AcceptsMultiByteSequencesAndTheirBoundaries) {
  EXPECT_EQ(find_invalid_utf8("h\xC3\xA9llo"), std::nullopt);                // é, 2 bytes
  EXPECT_EQ(find_invalid_utf8("\xE2\x82\xAC 5"), std::nullopt);              // €, 3 bytes
  EXPECT_EQ(find_invalid_utf8("ok \xF0\x9F\x98\x80!"), std::nullopt);        // 😀, 4 bytes
  EXPECT_EQ(find_invalid_utf8("α³-Bench, ≤ 100 ms, 🚁"), std::nullopt);
  for (uint32_t cp : {0x7Fu, 0x80u, 0x7FFu, 0x800u, 0xD7FFu, 0xE000u, 0xFFFDu, 0xFFFFu, 0x10000u,
                      0x10FFFFu}) {
    EXPECT_EQ(find_invalid_utf8(encode(cp)), std::nullopt) << std::hex << "U+" << cp;
    EXPECT_EQ(find_invalid_utf8("0123456789" + encode(cp) + "abcdefghij"), std::nullopt)
        << std::hex << "U+" << cp;
  }
  EXPECT_EQ(encode(0x7FF), bytes({0xDF, 0xBF}));
  EXPECT_EQ(encode(0x10FFFF), bytes({0xF4, 0x8F, 0xBF, 0xBF}));
}

TEST(FindInvalidUtf8, AcceptsEveryScalarValueAndRejectsEverySurrogate) {
  for (uint32_t cp = 0; cp <= 0x10FFFF; ++cp) {
    const std::string text = encode(cp);
    const bool surrogate = cp >= 0xD800 && cp <= 0xDFFF;
    const auto bad = find_invalid_utf8(text);
    if (surrogate) {
      ASSERT_EQ(bad, std::optional<std::size_t>(0)) << std::hex << "U+" << cp;
    } else {
      ASSERT_EQ(bad, std::nullopt) << std::hex << "U+" << cp;
    }
  }
}

struct BadSequence {
  const char* what;
  std::string bytes;
  bool only_at_end;  // a truncated sequence: invalid only when nothing follows
};

std::vector<BadSequence> bad_sequences() {
  return {
      {"0xC0 lead (overlong U+0000)", bytes({0xC0, 0x80}), false},
      {"0xC1 lead (overlong U+007F)", bytes({0xC1, 0xBF}), false},
      {"overlong 3-byte U+0000", bytes({0xE0, 0x80, 0x80}), false},
      {"overlong 3-byte U+07FF", bytes({0xE0, 0x9F, 0xBF}), false},
      {"overlong 4-byte U+0000", bytes({0xF0, 0x80, 0x80, 0x80}), false},
      {"overlong 4-byte U+FFFF", bytes({0xF0, 0x8F, 0xBF, 0xBF}), false},
      {"surrogate U+D800", bytes({0xED, 0xA0, 0x80}), false},
      {"surrogate U+DBFF", bytes({0xED, 0xAF, 0xBF}), false},
      {"surrogate U+DC00", bytes({0xED, 0xB0, 0x80}), false},
      {"surrogate U+DFFF", bytes({0xED, 0xBF, 0xBF}), false},
      {"U+110000", bytes({0xF4, 0x90, 0x80, 0x80}), false},
      {"0xF5 lead (U+140000)", bytes({0xF5, 0x80, 0x80, 0x80}), false},
      {"0xF7 lead", bytes({0xF7, 0xBF, 0xBF, 0xBF}), false},
      {"0xF8 (5-byte form)", bytes({0xF8, 0x88, 0x80, 0x80, 0x80}), false},
      {"0xFC (6-byte form)", bytes({0xFC, 0x84, 0x80, 0x80, 0x80, 0x80}), false},
      {"0xFE", bytes({0xFE}), false},
      {"0xFF", bytes({0xFF}), false},
      {"stray continuation 0x80", bytes({0x80}), false},
      {"stray continuation 0xBF", bytes({0xBF}), false},
      {"2-byte lead then ASCII", bytes({0xC3, 'A'}), false},
      {"3-byte lead, bad second byte", bytes({0xE2, 0x28, 0xA1}), false},
      {"3-byte, bad third byte", bytes({0xE2, 0x82, 0xC0}), false},
      {"4-byte, bad third byte", bytes({0xF0, 0x9F, 0x28, 0x80}), false},
      {"4-byte, bad fourth byte", bytes({0xF0, 0x9F, 0x98, 0x41}), false},
      {"4-byte, lead byte as fourth", bytes({0xF0, 0x9F, 0x98, 0xF0}), false},
      {"truncated 2-byte", bytes({0xC3}), true},
      {"truncated 3-byte after 1", bytes({0xE2}), true},
      {"truncated 3-byte after 2", bytes({0xE2, 0x82}), true},
      {"truncated 4-byte after 1", bytes({0xF0}), true},
      {"truncated 4-byte after 2", bytes({0xF0, 0x9F}), true},
      {"truncated 4-byte after 3", bytes({0xF0, 0x9F, 0x98}), true},
  };
}

// The offset is the first byte of the bad sequence, for every position relative to the
// eight-byte ASCII words (offsets 0..20), with and without ASCII after it.
TEST(FindInvalidUtf8, ReportsTheOffsetOfTheBadSequenceAroundTheAsciiFastPath) {
  for (const BadSequence& bad : bad_sequences()) {
    ASSERT_EQ(reference_find_invalid(bad.bytes), std::optional<std::size_t>(0)) << bad.what;
    for (std::size_t offset = 0; offset <= 20; ++offset) {
      const std::string prefix(offset, 'a');
      EXPECT_EQ(find_invalid_utf8(prefix + bad.bytes), std::optional<std::size_t>(offset))
          << bad.what << " at offset " << offset;
      if (bad.only_at_end) continue;
      for (std::size_t suffix : {1u, 7u, 8u, 9u, 16u}) {
        EXPECT_EQ(find_invalid_utf8(prefix + bad.bytes + std::string(suffix, 'z')),
                  std::optional<std::size_t>(offset))
            << bad.what << " at offset " << offset << ", " << suffix << " ASCII bytes after";
      }
    }
  }
}

TEST(FindInvalidUtf8, ReportsTheFirstOfSeveralBadSequencesAfterValidMultiByteText) {
  const std::string e_acute = "\xC3\xA9";
  EXPECT_EQ(find_invalid_utf8(e_acute + "\x80"), std::optional<std::size_t>(2));
  // After a multi-byte character the fast path restarts at an odd offset.
  EXPECT_EQ(find_invalid_utf8(e_acute + "0123456789ABC" + "\xFF" + "x\xC0\x80"),
            std::optional<std::size_t>(15));
  EXPECT_EQ(find_invalid_utf8("\xF0\x9F\x98\x80\xF0\x9F\x98\x80\xF0\x9F\x98"),
            std::optional<std::size_t>(8));
  // A truncated sequence followed by a complete one is bad where the truncated one starts.
  EXPECT_EQ(find_invalid_utf8("abc\xE2\x82\xE2\x82\xAC"), std::optional<std::size_t>(3));
}

TEST(FindInvalidUtf8, AgreesWithAReferenceDecoderOnRandomText) {
  // Bytes biased towards the interesting ones: ASCII runs, lead bytes near every range edge,
  // continuation bytes near their edges.
  const std::vector<unsigned> pool = {'a',  ' ',  '"',  0x00, 0x7F, 0x80, 0x8F, 0x90, 0x9F, 0xA0,
                                      0xBF, 0xC0, 0xC1, 0xC2, 0xDF, 0xE0, 0xE1, 0xEC, 0xED, 0xEE,
                                      0xEF, 0xF0, 0xF1, 0xF3, 0xF4, 0xF5, 0xFF};
  std::mt19937 rng(20240607);
  std::uniform_int_distribution<std::size_t> pick(0, pool.size() - 1);
  std::uniform_int_distribution<int> length(0, 40), ascii_run(0, 12), coin(0, 3);
  int invalid = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    std::string text;
    const int n = length(rng);
    while (static_cast<int>(text.size()) < n) {
      if (coin(rng) == 0) {
        text.append(static_cast<std::size_t>(ascii_run(rng)), 'q');
      } else if (coin(rng) == 0) {
        text += encode(std::uniform_int_distribution<uint32_t>(0x80, 0x10FFFF)(rng));
      } else {
        text += static_cast<char>(pool[pick(rng)]);
      }
    }
    const auto expected = reference_find_invalid(text);
    if (expected) ++invalid;
    ASSERT_EQ(find_invalid_utf8(text), expected) << "trial " << trial << ", " << text.size() << " bytes";
  }
  // Both outcomes must be common, or the comparison says little.
  EXPECT_GT(invalid, 20000);
  EXPECT_LT(invalid, 190000);
}

}  // namespace
