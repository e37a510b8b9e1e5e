// Every DroneCAN test vector both ways: encoding `fields` gives the payload, the transfer
// CRC and the frames byte for byte; feeding the frames to the reassembler and decoding
// gives `decoded`. Run on ../shared/spec/dronecan/vectors.json (skipped when absent) and on
// our copy in tests/data/dronecan (always).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "bridge/dronecan/crc.hpp"
#include "bridge/dronecan/message_registry.hpp"
#include "bridge/dronecan/reassembler.hpp"
#include "bridge/dronecan/transfer.hpp"
#include "tests/bridge/bridge_test_util.hpp"
#include "tests/test_support.hpp"

namespace a3::bridge {
namespace {

using nlohmann::json;
using test::parse_hex_bytes;

// Compares decoded JSON with the vector's: integers exactly, floats after rounding both to
// float32 (every float field here is float16 or float32; the vector gives exact values).
void expect_same_value(const json& expected, const json& actual, const std::string& path) {
  if (expected.is_object()) {
    ASSERT_TRUE(actual.is_object()) << path;
    EXPECT_EQ(expected.size(), actual.size()) << path << ": field count";
    for (const auto& [key, value] : expected.items()) {
      ASSERT_TRUE(actual.contains(key)) << path << "." << key << " missing";
      expect_same_value(value, actual.at(key), path + "." + key);
    }
  } else if (expected.is_array()) {
    ASSERT_TRUE(actual.is_array()) << path;
    ASSERT_EQ(expected.size(), actual.size()) << path << ": element count";
    for (std::size_t i = 0; i < expected.size(); ++i) {
      expect_same_value(expected[i], actual[i], path + "[" + std::to_string(i) + "]");
    }
  } else if (expected.is_number_float()) {
    ASSERT_TRUE(actual.is_number()) << path;
    EXPECT_EQ(static_cast<float>(expected.get<double>()), static_cast<float>(actual.get<double>()))
        << path;
  } else {
    EXPECT_EQ(expected, actual) << path;
  }
}

struct VectorCounts {
  int encoded = 0;
  int decoded = 0;
};

void check_vectors(const json& file, VectorCounts& counts) {
  DataTypeTable table;
  add_all_message_types(table);
  for (const json& v : file.at("vectors")) {
    const std::string type_name = v.at("type");
    const std::string label = type_name + " (transfer ID " +
                              std::to_string(v.at("transfer_id").get<int>()) + ", priority " +
                              std::to_string(v.at("priority").get<int>()) + ")";
    SCOPED_TRACE(label);
    const MessageTypeEntry* type = find_message_type(type_name);
    if (type == nullptr) {
      ADD_FAILURE() << "no codec for " << type_name;
      continue;
    }
    EXPECT_EQ(type->info.default_dtid, v.at("dtid").get<int>());

    // Encode.
    Payload payload;
    std::string error;
    ASSERT_TRUE(type->encode_from_json(v.at("fields"), payload, error)) << error;
    const std::vector<uint8_t> expected_payload = parse_hex_bytes(v.at("payload"));
    EXPECT_EQ(test::to_hex_bytes(payload.data(), payload.size), v.at("payload").get<std::string>());
    EXPECT_EQ(payload.size, v.at("payload_len").get<std::size_t>());
    if (!v.at("transfer_crc").is_null()) {
      const auto crc = std::stoul(v.at("transfer_crc").get<std::string>(), nullptr, 16);
      EXPECT_EQ(transfer_crc(type->info.signature, expected_payload.data(), expected_payload.size()),
                crc);
    }
    TransferHeader header;
    header.priority = static_cast<uint8_t>(v.at("priority").get<int>());
    header.data_type_id = static_cast<uint16_t>(v.at("dtid").get<int>());
    header.source_node_id = static_cast<uint8_t>(v.at("source_node_id").get<int>());
    header.transfer_id = static_cast<uint8_t>(v.at("transfer_id").get<int>());
    std::vector<CanFrame> frames;
    append_transfer_frames(header, type->info.signature, payload.data(), payload.size, frames);
    const json& expected_frames = v.at("frames");
    ASSERT_EQ(frames.size(), expected_frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const CanFrame expected = test::frame_from_vector(expected_frames[i]);
      EXPECT_EQ(frames[i].id, expected.id) << "frame " << i;
      EXPECT_TRUE(frames[i].extended);
      EXPECT_EQ(test::to_hex_bytes(frames[i].data.data(), frames[i].size),
                expected_frames[i].at("data").get<std::string>())
          << "frame " << i;
    }
    ++counts.encoded;

    // Decode: the vector's frames (not ours) through the reassembler.
    TransferReassembler reassembler(table);
    ReceivedTransfer transfer;
    for (std::size_t i = 0; i < expected_frames.size(); ++i) {
      const FrameVerdict verdict =
          reassembler.accept(test::frame_from_vector(expected_frames[i]), 1000 + 100 * int64_t(i),
                             transfer);
      const bool last = i + 1 == expected_frames.size();
      ASSERT_EQ(verdict, last ? FrameVerdict::kTransferComplete : FrameVerdict::kInProgress)
          << "frame " << i << ": " << to_string(reassembler.last_error());
    }
    EXPECT_EQ(transfer.header, header);
    EXPECT_EQ(transfer.timestamp_us, 1000);
    EXPECT_EQ(test::to_hex_bytes(transfer.payload, transfer.size), v.at("payload").get<std::string>());
    json decoded;
    ASSERT_TRUE(type->decode_to_json(transfer.payload, transfer.size, decoded, error)) << error;
    expect_same_value(v.at("decoded"), decoded, "decoded");
    EXPECT_EQ(reassembler.stats().rejected_frames(), 0u);
    ++counts.decoded;
  }
}

void check_types(const json& file) {
  for (const auto& [name, t] : file.at("types").items()) {
    SCOPED_TRACE(name);
    const MessageTypeEntry* type = find_message_type(name);
    ASSERT_NE(type, nullptr);
    EXPECT_EQ(type->info.default_dtid, t.at("dtid").get<int>());
    const uint64_t signature = std::stoull(t.at("signature").get<std::string>(), nullptr, 16);
    EXPECT_EQ(type->info.signature, signature);
    EXPECT_EQ(type->layout_signature(), signature);
    EXPECT_EQ(type->info.max_bit_length, t.at("max_bit_len").get<unsigned>());
    EXPECT_EQ(type->layout_max_bit_length(), t.at("max_bit_len").get<unsigned>());
    EXPECT_EQ(transfer_crc_seed(signature), std::stoul(t.at("base_crc").get<std::string>(), nullptr, 16));
  }
  for (const auto& [name, t] : file.at("nested_types").items()) {
    SCOPED_TRACE(name);
    const MessageTypeEntry* found = nullptr;
    for (const auto& entry : nested_message_types()) {
      if (entry.info.full_name == name) found = &entry;
    }
    ASSERT_NE(found, nullptr);
    const uint64_t signature = std::stoull(t.at("signature").get<std::string>(), nullptr, 16);
    EXPECT_EQ(found->info.signature, signature);
    EXPECT_EQ(found->layout_signature(), signature);
    EXPECT_EQ(found->layout_max_bit_length(), t.at("max_bit_len").get<unsigned>());
  }
}

void check_crc_examples(const json& file) {
  for (const json& example : file.at("crc_examples")) {
    const auto payload = parse_hex_bytes(example.at("payload"));
    const auto crc = std::stoul(example.at("crc").get<std::string>(), nullptr, 16);
    if (example.at("type").is_null()) {
      EXPECT_EQ(crc16_ccitt_false(payload.data(), payload.size()), crc);
      continue;
    }
    const uint64_t signature = std::stoull(example.at("signature").get<std::string>(), nullptr, 16);
    EXPECT_EQ(transfer_crc_seed(signature),
              std::stoul(example.at("seed_after_signature").get<std::string>(), nullptr, 16));
    EXPECT_EQ(transfer_crc(signature, payload.data(), payload.size()), crc);
  }
}

TEST(DroneCanVectors, SharedVectorsPassBothWays) {
  A3_REQUIRE_SHARED(path, "spec/dronecan/vectors.json");
  const json file = test::read_json_file(path);
  check_types(file);
  check_crc_examples(file);
  VectorCounts counts;
  check_vectors(file, counts);
  EXPECT_EQ(counts.encoded, static_cast<int>(file.at("vectors").size()));
  EXPECT_EQ(counts.decoded, counts.encoded);
  EXPECT_GE(counts.decoded, 24) << "every standard message type has vectors";
  std::printf("[ vectors  ] %d shared vectors encoded and decoded\n", counts.decoded);
}

TEST(DroneCanVectors, LocalCopyPassesBothWays) {
  const json file = test::read_json_file(test::local_vectors_path());
  check_types(file);
  check_crc_examples(file);
  VectorCounts counts;
  check_vectors(file, counts);
  EXPECT_EQ(counts.decoded, static_cast<int>(file.at("vectors").size()));
  EXPECT_GE(counts.decoded, 24);
}

TEST(DroneCanVectors, LocalCopyAgreesWithTheSharedFile) {
  A3_REQUIRE_SHARED(path, "spec/dronecan/vectors.json");
  const json shared = test::read_json_file(path);
  const json local = test::read_json_file(test::local_vectors_path());
  EXPECT_EQ(local.at("types"), shared.at("types"));
  EXPECT_EQ(local.at("nested_types"), shared.at("nested_types"));
  EXPECT_EQ(local.at("vectors"), shared.at("vectors"));
  EXPECT_EQ(local.at("crc_examples"), shared.at("crc_examples"));
}

TEST(DroneCanVectors, EveryStandardTypeHasAVector) {
  const json file = test::read_json_file(test::local_vectors_path());
  for (const auto& entry : message_types()) {
    const std::string name(entry.info.full_name);
    if (name.rfind("uavcan.", 0) != 0) continue;
    bool found = false;
    for (const json& v : file.at("vectors")) found = found || v.at("type") == name;
    EXPECT_TRUE(found) << name;
  }
}

}  // namespace
}  // namespace a3::bridge
