// Reads DroneCAN (UAVCAN v0) DSDL files far enough to compute what identifies a type on
// the bus: its normalized definition, data type signature, default data type ID and
// maximum bit length, exactly as DroneCAN's DSDL tools do. Used by tests (the codec's
// declared layouts must match the files) and by tools; not needed to run a node.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace a3::bridge {

struct DsdlField {
  std::string name;             // "" for void fields
  std::string normalized;       // e.g. "saturated float16[<=36] covariance", "void13"
  std::string nested_type;      // full name of the compound type used (directly or as array
                                // elements), "" for primitives
  unsigned max_bit_length = 0;
};

struct DsdlDefinition {
  std::string full_name;
  std::filesystem::path file;
  std::optional<uint16_t> default_dtid;
  bool service = false;
  bool request_union = false;   // messages: the @union flag
  bool response_union = false;
  std::vector<DsdlField> request;  // messages: the fields
  std::vector<DsdlField> response;
  std::string normalized_definition;
  uint64_t signature = 0;
  unsigned max_bit_length = 0;       // messages; services: of the request
  unsigned response_max_bit_length = 0;
};

class DsdlLibrary {
 public:
  // Each root holds top-level namespace folders: root/uavcan/protocol/341.NodeStatus.uavcan
  // is uavcan.protocol.NodeStatus. Throws std::runtime_error for a missing root or two files
  // defining the same type.
  explicit DsdlLibrary(const std::vector<std::filesystem::path>& roots);

  // Parses the type (and those it uses) on first use. Throws std::runtime_error naming the
  // file and line for bad DSDL, or the type that cannot be found.
  const DsdlDefinition& get(const std::string& full_name);
  bool contains(const std::string& full_name) const { return files_.count(full_name) != 0; }
  std::vector<std::string> type_names() const;

 private:
  const DsdlDefinition& parse(const std::string& full_name, std::vector<std::string>& stack);

  std::map<std::string, std::filesystem::path> files_;
  std::map<std::string, std::unique_ptr<DsdlDefinition>> parsed_;
};

// DroneCAN's signature of a normalized definition extended by nested signatures in order:
// CRC-64-WE(definition), then for each nested type: add(nested), add(value so far).
uint64_t dsdl_signature(const std::string& normalized_definition,
                        const std::vector<uint64_t>& nested_signatures);

}  // namespace a3::bridge
