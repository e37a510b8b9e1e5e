// The table-driven frame length (can_frame_bits) against the bit-by-bit reference
// (can_frame_bits_reference): identical for random frames of every kind and length, for
// frames built to stress stuffing, and for every frame of the DroneCAN test vectors; the
// byte-wise CRC-15 against the bit-wise one for every bit count; frames whose headers repeat
// (the cached state after a header).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>

#include "bridge/can/frame_bits_reference.hpp"
#include "bridge/can/frame_timing.hpp"
#include "tests/bridge/bridge_test_util.hpp"
#include "tests/test_support.hpp"

namespace a3::bridge {
namespace {

constexpr BitStuffing kAllStuffings[] = {BitStuffing::kExact, BitStuffing::kWorstCase,
                                         BitStuffing::kNone};

std::string describe(const CanFrame& frame) {
  return to_cansend_string(frame) + (frame.extended ? " (extended)" : " (standard)");
}

void expect_same_bits(const CanFrame& frame) {
  for (BitStuffing stuffing : kAllStuffings) {
    ASSERT_EQ(can_frame_bits(frame, stuffing), can_frame_bits_reference(frame, stuffing))
        << describe(frame) << ", stuffing " << static_cast<int>(stuffing);
  }
}

CanFrame random_frame(std::mt19937_64& rng, bool extended, uint8_t size) {
  CanFrame frame;
  frame.extended = extended;
  frame.id = static_cast<uint32_t>(rng()) & (extended ? 0x1FFFFFFFu : 0x7FFu);
  frame.remote = rng() % 8 == 0;
  frame.size = size;
  // Data from a few byte patterns as well as uniform bytes, so long equal runs occur.
  for (uint8_t& byte : frame.data) {
    switch (rng() % 4) {
      case 0: byte = 0x00; break;
      case 1: byte = 0xFF; break;
      default: byte = static_cast<uint8_t>(rng()); break;
    }
  }
  return frame;
}

TEST(FrameBitsFastPath, MatchesTheReferenceOnRandomFramesOfEveryKindAndLength) {
  std::mt19937_64 rng(16);
  int compared = 0;
  for (bool extended : {true, false}) {
    for (uint8_t size = 0; size <= 8; ++size) {
      for (int i = 0; i < 4000; ++i) {
        expect_same_bits(random_frame(rng, extended, size));
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 2 * 9 * 4000);
}

// The state after a header is cached (64 entries): headers seen again, evicted, or sharing
// a cache slot must give the same counts as fresh ones. IDs from small sets, so most repeat.
TEST(FrameBitsFastPath, MatchesTheReferenceWhenHeadersRepeat) {
  std::mt19937_64 rng(7);
  for (uint32_t distinct_ids : {1u, 8u, 60u, 500u}) {
    for (int i = 0; i < 20000; ++i) {
      const bool extended = rng() % 4 != 0;
      CanFrame frame = random_frame(rng, extended, static_cast<uint8_t>(rng() % 9));
      const uint32_t id = static_cast<uint32_t>(rng() % distinct_ids);
      frame.id = extended ? 0x1E04A300u + id : 0x400u + id % 0x400u;
      expect_same_bits(frame);
    }
  }
}

TEST(FrameBitsFastPath, MatchesTheReferenceOnRunsOfEqualBits) {
  // All-zero and all-one identifiers and data: the most stuff bits, runs across fields.
  for (bool extended : {true, false}) {
    for (bool remote : {false, true}) {
      for (uint32_t id : {0u, 0x7FFu, 0x1FFFFFFFu, 0x1F0u, 0x3E07C1Fu}) {
        for (uint8_t fill : {0x00, 0xFF, 0xF0, 0x0F, 0x55, 0x83}) {
          for (uint8_t size = 0; size <= 8; ++size) {
            CanFrame frame;
            frame.extended = extended;
            frame.remote = remote;
            frame.id = id & (extended ? 0x1FFFFFFFu : 0x7FFu);
            frame.size = size;
            frame.data.fill(fill);
            expect_same_bits(frame);
          }
        }
      }
    }
  }
}

TEST(FrameBitsFastPath, KeepsTheKnownCountOfAnAllZeroStandardFrame) {
  CanFrame zeros;
  zeros.extended = false;
  EXPECT_EQ(can_frame_bits(zeros), 34u + 6u + 13u);
  EXPECT_EQ(can_frame_bits_reference(zeros), 34u + 6u + 13u);
}

int compare_vector_frames(const nlohmann::json& file) {
  int compared = 0;
  for (const nlohmann::json& vector : file.at("vectors")) {
    for (const nlohmann::json& f : vector.at("frames")) {
      expect_same_bits(test::frame_from_vector(f));
      ++compared;
    }
  }
  return compared;
}

TEST(FrameBitsFastPath, MatchesTheReferenceOnTheLocalDroneCanVectors) {
  EXPECT_GE(compare_vector_frames(test::read_json_file(test::local_vectors_path())), 24);
}

TEST(FrameBitsFastPath, MatchesTheReferenceOnTheSharedDroneCanVectors) {
  A3_REQUIRE_SHARED(path, "spec/dronecan/vectors.json");
  EXPECT_GE(compare_vector_frames(test::read_json_file(path)), 24);
}

TEST(FrameBitsFastPath, ByteWiseCrc15MatchesTheBitWiseOneForEveryBitCount) {
  std::mt19937_64 rng(15);
  uint8_t bits[20];
  for (unsigned count = 0; count <= 8 * sizeof bits; ++count) {
    for (int i = 0; i < 50; ++i) {
      for (uint8_t& b : bits) b = static_cast<uint8_t>(rng());
      ASSERT_EQ(can_crc15(bits, count), can_crc15_reference(bits, count)) << count << " bits";
    }
  }
  const uint8_t text[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(can_crc15_reference(text, 72), 0x059E);
}

}  // namespace
}  // namespace a3::bridge
