// Bit packing, float16 and the CRCs: the primitives every DroneCAN payload rests on.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "bridge/dronecan/bit_stream.hpp"
#include "bridge/dronecan/crc.hpp"
#include "bridge/dronecan/float16.hpp"
#include "common/rng.hpp"

namespace a3::bridge {
namespace {

TEST(BitStream, Int14ValuesPackAsTheRawCommandVector) {
  // esc.RawCommand cmd = [0, 4000, 8191, -8192] is "00 02 80 ff f7 c0 20" (vectors.json).
  uint8_t buffer[16];
  BitWriter writer(buffer, sizeof buffer);
  for (int64_t v : {0, 4000, 8191, -8192}) {
    ASSERT_TRUE(writer.write_scalar(static_cast<uint64_t>(v) & 0x3FFF, 14));
  }
  ASSERT_EQ(writer.byte_size(), 7u);
  const uint8_t expected[] = {0x00, 0x02, 0x80, 0xff, 0xf7, 0xc0, 0x20};
  EXPECT_EQ(0, std::memcmp(buffer, expected, sizeof expected));

  BitReader reader(buffer, 7);
  for (int64_t v : {0, 4000, 8191, -8192}) {
    int64_t got = 0;
    ASSERT_TRUE(reader.read_signed(14, got));
    EXPECT_EQ(got, v);
  }
  EXPECT_EQ(reader.remaining_bits(), 0u);
  int64_t none = 0;
  EXPECT_FALSE(reader.read_signed(1, none));
}

TEST(BitStream, MixedWidthsRoundTripAtEveryAlignment) {
  common::Rng rng(20240611);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::pair<unsigned, uint64_t>> fields;
    unsigned total_bits = 0;
    while (total_bits < 900) {
      const unsigned bits = 1 + static_cast<unsigned>(rng.next_u64() % 64);
      const uint64_t mask = bits == 64 ? ~uint64_t{0} : (uint64_t{1} << bits) - 1;
      fields.emplace_back(bits, rng.next_u64() & mask);
      total_bits += bits;
    }
    std::vector<uint8_t> buffer((total_bits + 7) / 8);
    BitWriter writer(buffer.data(), buffer.size());
    for (const auto& [bits, value] : fields) ASSERT_TRUE(writer.write_scalar(value, bits));
    ASSERT_EQ(writer.bit_offset(), total_bits);
    EXPECT_FALSE(writer.write_scalar(1, 8)) << "the buffer is full";
    BitReader reader(buffer.data(), buffer.size());
    for (const auto& [bits, value] : fields) {
      uint64_t got = 0;
      ASSERT_TRUE(reader.read_unsigned(bits, got));
      ASSERT_EQ(got, value) << bits << "-bit field";
    }
  }
}

TEST(BitStream, ByteAlignedScalarsAreLittleEndian) {
  uint8_t buffer[8];
  BitWriter writer(buffer, sizeof buffer);
  ASSERT_TRUE(writer.write_scalar(12345, 32));  // NodeStatus.uptime_sec "39 30 00 00"
  EXPECT_EQ(buffer[0], 0x39);
  EXPECT_EQ(buffer[1], 0x30);
  EXPECT_EQ(buffer[2], 0x00);
  EXPECT_EQ(buffer[3], 0x00);
}

TEST(Float16, KnownValues) {
  EXPECT_EQ(float16_bits_from_float(1.0f), 0x3C00);
  EXPECT_EQ(float16_bits_from_float(-2.0f), 0xC000);
  EXPECT_EQ(float16_bits_from_float(65504.0f), 0x7BFF);
  EXPECT_EQ(float16_bits_from_float(65520.0f), 0x7C00) << "rounds up to infinity";
  EXPECT_EQ(float16_bits_from_float(65519.0f), 0x7BFF);
  EXPECT_EQ(float16_bits_from_float(std::ldexp(1.0f, -24)), 0x0001) << "smallest subnormal";
  EXPECT_EQ(float16_bits_from_float(std::ldexp(1.0f, -26)), 0x0000) << "rounds to zero";
  EXPECT_EQ(float16_bits_from_float(std::numeric_limits<float>::infinity()), 0x7C00);
  EXPECT_EQ(float16_bits_from_float(-std::numeric_limits<float>::infinity()), 0xFC00);
  EXPECT_EQ(float16_bits_from_float(std::numeric_limits<float>::quiet_NaN()), 0x7E00);
  EXPECT_EQ(float16_bits_from_float(16.8f), 0x4C33) << "16.8 V -> 16.796875 (vectors.json)";
  EXPECT_FLOAT_EQ(float_from_float16_bits(0x4C33), 16.796875f);
  // Ties go to even: 1 + 2^-11 lies halfway between 1 and 1 + 2^-10.
  EXPECT_EQ(float16_bits_from_float(1.0f + std::ldexp(1.0f, -11)), 0x3C00);
  EXPECT_EQ(float16_bits_from_float(1.0f + 3 * std::ldexp(1.0f, -11)), 0x3C02);
}

TEST(Float16, EveryHalfValueSurvivesARoundTrip) {
  for (uint32_t bits = 0; bits <= 0xFFFF; ++bits) {
    const float value = float_from_float16_bits(static_cast<uint16_t>(bits));
    if (std::isnan(value)) {
      EXPECT_TRUE((bits & 0x7C00) == 0x7C00 && (bits & 0x3FF) != 0);
      continue;
    }
    ASSERT_EQ(float16_bits_from_float(value), bits) << "half 0x" << std::hex << bits;
  }
}

TEST(Crc, CheckValues) {
  const uint8_t text[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(crc16_ccitt_false(text, sizeof text), 0x29B1);
  Crc64We crc;
  crc.add(text, sizeof text);
  EXPECT_EQ(crc.value(), 0x62EC59E3F1A4F00AULL) << "CRC-64/WE check value";
  // vectors.json crc_examples: esc.Status seed after its signature.
  EXPECT_EQ(transfer_crc_seed(0xa9af28aea2fbb254ULL), 0x1591);
}

// The CRC-16 takes eight bytes at a time: it must give the bit-by-bit definition's value for
// every length (whole blocks, tails, both) and any starting register.
TEST(Crc, Crc16MatchesTheBitwiseDefinitionForEveryLengthAndStart) {
  auto bitwise = [](const uint8_t* data, std::size_t size, uint16_t crc) {
    for (std::size_t i = 0; i < size; ++i) {
      crc = static_cast<uint16_t>(crc ^ (data[i] << 8));
      for (int bit = 0; bit < 8; ++bit) {
        crc = static_cast<uint16_t>((crc & 0x8000u) != 0 ? (crc << 1) ^ 0x1021u : crc << 1);
      }
    }
    return crc;
  };
  uint32_t x = 12345;
  std::vector<uint8_t> data(80);
  for (uint8_t& byte : data) {
    x = x * 1664525u + 1013904223u;
    byte = static_cast<uint8_t>(x >> 24);
  }
  for (const uint16_t start : {uint16_t{0xFFFF}, uint16_t{0}, uint16_t{0x1591}, uint16_t{0x8001}}) {
    for (std::size_t size = 0; size <= data.size(); ++size) {
      ASSERT_EQ(crc16_ccitt_false(data.data(), size, start), bitwise(data.data(), size, start))
          << size << " bytes from 0x" << std::hex << start;
    }
  }
  static_assert(transfer_crc_seed(0xa9af28aea2fbb254ULL) == 0x1591, "the seed is a constant expression");
}

TEST(Crc, Crc64CanBeExtendedFromAValue) {
  Crc64We whole;
  whole.add("abcdef");
  Crc64We first;
  first.add("abc");
  Crc64We second(first.value());
  second.add("def");
  EXPECT_EQ(second.value(), whole.value());
}

}  // namespace
}  // namespace a3::bridge
