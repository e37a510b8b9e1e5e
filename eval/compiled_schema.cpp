// Validation with a compiled schema: one short check per keyword, in valijson's meaning (see
// valijson/validation_visitor.hpp). Every check is a conjunct, so their order only decides how
// soon a failure is found: the type first, then the cheap checks, then the subschemas.
#include "eval/compiled_schema.hpp"

#include <cmath>
#include <cstring>
#include <limits>

#include "eval/valijson_values.hpp"

namespace a3::eval {
namespace {

bool type_matches(uint8_t mask, const rapidjson::Value& value) {
  switch (value.GetType()) {
    case rapidjson::kNullType: return (mask & kTypeNull) != 0;
    case rapidjson::kFalseType:
    case rapidjson::kTrueType: return (mask & kTypeBoolean) != 0;
    case rapidjson::kObjectType: return (mask & kTypeObject) != 0;
    case rapidjson::kArrayType: return (mask & kTypeArray) != 0;
    case rapidjson::kStringType: return (mask & kTypeString) != 0;
    case rapidjson::kNumberType:
      return (mask & kTypeNumber) != 0 || ((mask & kTypeInteger) != 0 && !value.IsDouble());
  }
  return false;
}

bool is_named(const rapidjson::Value& key, const std::string& name) {
  // Length and first byte settle most members without a memcmp.
  return key.GetStringLength() == name.size() &&
         (name.empty() || (key.GetString()[0] == name[0] &&
                           std::memcmp(key.GetString(), name.data(), name.size()) == 0));
}

// valijson looks a name up with the object's first member of that name.
const rapidjson::Value* find_member(const rapidjson::Value& object, const std::string& name) {
  for (auto it = object.MemberBegin(); it != object.MemberEnd(); ++it) {
    if (is_named(it->name, name)) return &it->value;
  }
  return nullptr;
}

// find_member for a subschema's properties, looked up in their order. While every member
// before `next_` has been found for an earlier property (documents list members in the schema's
// order as a rule), a member there cannot bear the name looked up now (the properties' names
// differ), so the member at `next_` is the first of its name when it has it: one comparison
// instead of a scan from the start. Any other lookup is find_member's, and once a member is
// found elsewhere, every later one too.
class PropertyCursor {
 public:
  explicit PropertyCursor(const rapidjson::Value& object) : object_(object) {}

  const rapidjson::Value* find(const std::string& name) {
    if (in_order_ && next_ < object_.MemberCount()) {
      const auto& member = object_.MemberBegin()[next_];
      if (is_named(member.name, name)) {
        ++next_;
        return &member.value;
      }
    }
    const rapidjson::Value* found = find_member(object_, name);
    in_order_ = in_order_ && found == nullptr;
    return found;
  }

 private:
  const rapidjson::Value& object_;
  rapidjson::SizeType next_ = 0;
  bool in_order_ = true;
};

bool is_property_name(const std::vector<NamedSchema>& properties, const rapidjson::Value& name) {
  for (const NamedSchema& property : properties) {
    if (is_named(name, property.name)) return true;
  }
  return false;
}

bool bounds_valid(const SchemaNode& node, const rapidjson::Value& value) {
  if (!value.IsNumber() || (!node.minimum && !node.maximum)) return true;
  const double number = valijson_number(value);
  if (node.minimum && number < *node.minimum) return false;
  return !(node.maximum && number > *node.maximum);
}

// valijson's MultipleOfDoubleConstraint: a remainder within one epsilon of zero passes, and so
// do strings that read as numbers (it does not check types here).
bool multiple_of_valid(const SchemaNode& node, const rapidjson::Value& value) {
  if (!node.multiple_of) return true;
  double number = 0.0;
  if (!valijson_maybe_double(value, number) || number == 0) return true;
  const double remainder = std::remainder(number, *node.multiple_of);
  return !(std::fabs(remainder) > std::numeric_limits<double>::epsilon());
}

bool enum_valid(const SchemaNode& node, const rapidjson::Value& value) {
  if (node.enum_values == nullptr) return true;
  for (const rapidjson::Value& allowed : node.enum_values->GetArray()) {
    if (valijson_equal(allowed, value)) return true;
  }
  return false;
}

}  // namespace

bool CompiledSchema::valid_at(SchemaNodeIndex index, const rapidjson::Value& value) const {
  const SchemaNode& node = nodes_[static_cast<std::size_t>(index)];
  if (node.kind != SchemaNode::Kind::kKeywords) return node.kind == SchemaNode::Kind::kAlwaysValid;
  if (node.type_mask && !type_matches(*node.type_mask, value)) return false;
  if (!bounds_valid(node, value) || !multiple_of_valid(node, value)) return false;
  if (node.const_value != nullptr && !valijson_equal(*node.const_value, value)) return false;
  if (!enum_valid(node, value)) return false;
  if (value.IsObject() && !object_valid(node, value)) return false;
  if (value.IsArray() && !array_valid(node, value)) return false;
  return conditional_valid(node, value);
}

bool CompiledSchema::object_valid(const SchemaNode& node, const rapidjson::Value& object) const {
  for (const std::string& name : node.required_beyond_properties) {
    if (find_member(object, name) == nullptr) return false;
  }
  rapidjson::SizeType matched = 0;
  PropertyCursor members(object);
  for (const NamedSchema& property : node.properties) {
    const rapidjson::Value* member = members.find(property.name);
    if (member == nullptr) {
      if (property.required) return false;
      continue;
    }
    ++matched;
    if (!valid_at(property.schema, *member)) return false;
  }
  switch (node.additional) {
    case AdditionalProperties::kAny: return true;
    // valijson counts the distinct names matched: a repeated name is one too many.
    case AdditionalProperties::kNone: return matched == object.MemberCount();
    case AdditionalProperties::kSchema: return additional_valid(node, object);
  }
  return false;
}

bool CompiledSchema::additional_valid(const SchemaNode& node, const rapidjson::Value& object) const {
  for (auto it = object.MemberBegin(); it != object.MemberEnd(); ++it) {
    if (is_property_name(node.properties, it->name)) continue;
    if (!valid_at(node.additional_schema, it->value)) return false;
  }
  return true;
}

bool CompiledSchema::array_valid(const SchemaNode& node, const rapidjson::Value& array) const {
  const uint64_t size = array.Size();
  if (node.min_items && size < *node.min_items) return false;
  if (node.max_items && size > *node.max_items) return false;
  if (node.items == kNoSchemaNode) return true;
  for (const rapidjson::Value& element : array.GetArray()) {
    if (!valid_at(node.items, element)) return false;
  }
  return true;
}

bool CompiledSchema::conditional_valid(const SchemaNode& node, const rapidjson::Value& value) const {
  if (node.if_schema == kNoSchemaNode) return true;
  if (valid_at(node.if_schema, value)) {
    return node.then_schema == kNoSchemaNode || valid_at(node.then_schema, value);
  }
  return node.else_schema == kNoSchemaNode || valid_at(node.else_schema, value);
}

}  // namespace a3::eval
