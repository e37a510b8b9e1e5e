// The C++ layout of every message type agrees with its DSDL file: same normalized
// definition, signature, maximum bit length and data type ID, computed the DroneCAN way from
// the DSDL text. Standard types against ../shared/spec/dronecan/dsdl (skipped if absent), the
// project's a3.* types against bridge/dsdl (always), so neither can drift from its file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <unistd.h>

#include "bridge/dronecan/dsdl_parser.hpp"
#include "bridge/dronecan/message_registry.hpp"
#include "tests/bridge/bridge_test_util.hpp"
#include "tests/test_support.hpp"

namespace a3::bridge {
namespace {

void expect_matches_dsdl(const MessageTypeEntry& entry, DsdlLibrary& library) {
  const std::string name(entry.info.full_name);
  SCOPED_TRACE(name);
  const DsdlDefinition& def = library.get(name);
  EXPECT_EQ(entry.normalized_definition(), def.normalized_definition);
  EXPECT_EQ(def.signature, entry.info.signature)
      << std::hex << "DSDL gives 0x" << def.signature << ", the code says 0x"
      << entry.info.signature;
  EXPECT_EQ(entry.layout_signature(), entry.info.signature);
  EXPECT_EQ(def.max_bit_length, entry.info.max_bit_length);
  EXPECT_EQ(entry.layout_max_bit_length(), entry.info.max_bit_length);
  if (entry.info.default_dtid != 0) {
    ASSERT_TRUE(def.default_dtid.has_value());
    EXPECT_EQ(*def.default_dtid, entry.info.default_dtid);
  } else {
    EXPECT_FALSE(def.default_dtid.has_value());
  }
}

std::vector<const MessageTypeEntry*> entries_with_prefix(const std::string& prefix) {
  std::vector<const MessageTypeEntry*> out;
  for (const auto* list : {&message_types(), &nested_message_types()}) {
    for (const auto& entry : *list) {
      if (std::string(entry.info.full_name).rfind(prefix, 0) == 0) out.push_back(&entry);
    }
  }
  return out;
}

TEST(DsdlSignatures, StandardTypesMatchTheSharedDsdl) {
  A3_REQUIRE_SHARED(root, "spec/dronecan/dsdl");
  DsdlLibrary library({root});
  const auto entries = entries_with_prefix("uavcan.");
  ASSERT_EQ(entries.size(), 14u);  // 11 messages + Timestamp, ECEFPositionVelocity, Command
  for (const auto* entry : entries) expect_matches_dsdl(*entry, library);
}

TEST(DsdlSignatures, ParserReproducesTheVectorSignatures) {
  A3_REQUIRE_SHARED(root, "spec/dronecan/dsdl");
  DsdlLibrary library({root});
  const auto file = test::read_json_file(test::local_vectors_path());
  for (const auto* group : {"types", "nested_types"}) {
    for (const auto& [name, t] : file.at(group).items()) {
      SCOPED_TRACE(name);
      const DsdlDefinition& def = library.get(name);
      EXPECT_EQ(def.signature, std::stoull(t.at("signature").get<std::string>(), nullptr, 16));
      EXPECT_EQ(def.max_bit_length, t.at("max_bit_len").get<unsigned>());
    }
  }
}

TEST(DsdlSignatures, ProjectTypesMatchTheirDsdlFiles) {
  DsdlLibrary library({::a3::test::source_dir() / "bridge/dsdl"});
  const auto entries = entries_with_prefix("a3.");
  ASSERT_EQ(entries.size(), 4u);
  for (const auto* entry : entries) {
    expect_matches_dsdl(*entry, library);
    // Vendor-specific message range of DroneCAN.
    EXPECT_GE(entry->info.default_dtid, 20000);
    EXPECT_LE(entry->info.default_dtid, 21000);
  }
  EXPECT_EQ(library.type_names().size(), entries.size()) << "a DSDL file without C++ type";
  // What the normalized definition looks like (explicit casts, no constants, no comments).
  EXPECT_EQ(library.get("a3.fc.Command").normalized_definition,
            "a3.fc.Command\nsaturated int32 seq\nsaturated uint8 command\n"
            "saturated float32[3] target_W_m\nsaturated float32 speed_limit_mps\n"
            "saturated float32 yaw_deg");
}

TEST(DsdlSignatures, ProjectDataTypeIdsDoNotCollide) {
  std::set<uint16_t> ids;
  for (const auto& entry : message_types()) {
    EXPECT_TRUE(ids.insert(entry.info.default_dtid).second) << entry.info.full_name;
  }
}

class DsdlParserErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = std::filesystem::temp_directory_path() /
            ("a3_dsdl_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(root_ / "ns");
  }
  void TearDown() override { std::filesystem::remove_all(root_); }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(root_ / "ns" / name) << text;
  }
  std::string error_of(const std::string& type) {
    try {
      DsdlLibrary library({root_});
      library.get(type);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }
  std::filesystem::path root_;
};

TEST_F(DsdlParserErrors, NameFileAndLine) {
  write("20001.Bad.uavcan", "# comment\nuint8 ok\nfloat17 wrong\n");
  const std::string error = error_of("ns.Bad");
  EXPECT_NE(error.find("20001.Bad.uavcan:3"), std::string::npos) << error;
  EXPECT_NE(error.find("float width"), std::string::npos) << error;
}

TEST_F(DsdlParserErrors, UnknownNestedType) {
  write("20002.Uses.uavcan", "Missing thing\n");
  const std::string error = error_of("ns.Uses");
  EXPECT_NE(error.find("unknown type Missing"), std::string::npos) << error;
  EXPECT_NE(error.find(":1"), std::string::npos) << error;
}

TEST_F(DsdlParserErrors, GarbageLine) {
  write("20003.Junk.uavcan", "uint8 a b c\n");
  EXPECT_NE(error_of("ns.Junk").find("cannot parse 'uint8 a b c'"), std::string::npos);
}

TEST_F(DsdlParserErrors, ServicesAndUnionsHaveTheirMarkers) {
  write("200.Svc.uavcan", "uint8 a\n---\n@union\nuint8 x\nfloat16 y\n");
  DsdlLibrary library({root_});
  const DsdlDefinition& def = library.get("ns.Svc");
  EXPECT_TRUE(def.service);
  EXPECT_TRUE(def.response_union);
  EXPECT_EQ(def.normalized_definition,
            "ns.Svc\nsaturated uint8 a\n---\n@union\nsaturated uint8 x\nsaturated float16 y");
  EXPECT_EQ(def.response_max_bit_length, 1u + 16u);
}

}  // namespace
}  // namespace a3::bridge
