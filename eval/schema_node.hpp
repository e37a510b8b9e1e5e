// One subschema of a CompiledSchema: the keywords it uses, read once from the schema text.
// Subschemas refer to each other by index into CompiledSchema's node list ($ref resolves to the
// index of its target), so recursive schemas need no pointers and no copies.
#pragma once

#include "eval/rapidjson.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace a3::eval {

using SchemaNodeIndex = int32_t;
inline constexpr SchemaNodeIndex kNoSchemaNode = -1;

// JSON types as bits of `type`'s mask.
enum JsonTypeBit : uint8_t {
  kTypeNull = 1u << 0,
  kTypeBoolean = 1u << 1,
  kTypeObject = 1u << 2,
  kTypeArray = 1u << 3,
  kTypeString = 1u << 4,
  kTypeNumber = 1u << 5,
  kTypeInteger = 1u << 6,
};

struct NamedSchema {
  std::string name;  // never holds a NUL (refused when compiling)
  SchemaNodeIndex schema = kNoSchemaNode;
  bool required = false;  // also in the node's `required`: checked when looked up for its schema
};

// additionalProperties: absent or true (anything), false (nothing beyond `properties`), a schema.
enum class AdditionalProperties : uint8_t { kAny, kNone, kSchema };

struct SchemaNode {
  enum class Kind : uint8_t { kAlwaysValid, kAlwaysInvalid, kKeywords } kind = Kind::kKeywords;
  std::optional<uint8_t> type_mask;                    // type
  std::vector<std::string> required;                   // required
  std::vector<std::string> required_beyond_properties; // required names without a property schema
  std::vector<NamedSchema> properties;                 // properties
  AdditionalProperties additional = AdditionalProperties::kAny;
  SchemaNodeIndex additional_schema = kNoSchemaNode;   // additionalProperties when a schema
  SchemaNodeIndex items = kNoSchemaNode;               // items (one schema for every element)
  std::optional<uint64_t> min_items, max_items;        // minItems, maxItems
  std::optional<double> minimum, maximum;              // minimum, maximum (inclusive)
  std::optional<double> multiple_of;                   // multipleOf (a non-integer divisor)
  const rapidjson::Value* const_value = nullptr;       // const, in the schema's document
  const rapidjson::Value* enum_values = nullptr;       // enum (an array), in the schema's document
  SchemaNodeIndex if_schema = kNoSchemaNode, then_schema = kNoSchemaNode, else_schema = kNoSchemaNode;
};

}  // namespace a3::eval
