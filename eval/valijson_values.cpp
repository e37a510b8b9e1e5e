// valijson 1.0's number reading and strict equality, in the same order of cases as its
// BasicAdapter::equalTo (valijson/internal/basic_adapter.hpp).
#include "eval/valijson_values.hpp"

#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace a3::eval {
namespace {

int64_t valijson_integer(const rapidjson::Value& value) {
  if (value.IsInt()) return value.GetInt();
  if (value.IsInt64()) return value.GetInt64();
  if (value.IsUint()) return static_cast<int64_t>(value.GetUint());
  return static_cast<int64_t>(value.GetUint64());
}

bool same_string(const rapidjson::Value& a, const rapidjson::Value& b) {
  return a.GetStringLength() == b.GetStringLength() &&
         std::memcmp(a.GetString(), b.GetString(), a.GetStringLength()) == 0;
}

const rapidjson::Value* first_member(const rapidjson::Value& object, const rapidjson::Value& name) {
  for (auto it = object.MemberBegin(); it != object.MemberEnd(); ++it) {
    if (same_string(it->name, name)) return &it->value;
  }
  return nullptr;
}

bool equal_arrays(const rapidjson::Value& schema_value, const rapidjson::Value& target) {
  if (!target.IsArray() || target.Size() != schema_value.Size()) return false;
  for (rapidjson::SizeType i = 0; i < target.Size(); ++i) {
    if (!valijson_equal(schema_value[i], target[i])) return false;
  }
  return true;
}

// Every member of the target must equal the schema object's first member of that name.
bool equal_objects(const rapidjson::Value& schema_value, const rapidjson::Value& target) {
  if (!target.IsObject() || target.MemberCount() != schema_value.MemberCount()) return false;
  for (auto it = target.MemberBegin(); it != target.MemberEnd(); ++it) {
    const rapidjson::Value* mine = first_member(schema_value, it->name);
    if (mine == nullptr || !valijson_equal(*mine, it->value)) return false;
  }
  return true;
}

}  // namespace

double valijson_number(const rapidjson::Value& value) {
  if (value.IsDouble()) return value.GetDouble();
  return static_cast<double>(valijson_integer(value));
}

bool valijson_maybe_double(const rapidjson::Value& value, double& out) {
  if (value.IsNumber()) {
    out = valijson_number(value);
    return true;
  }
  if (!value.IsString()) return false;
  // RapidJSON strings end with a NUL, so strtod stops at the end or at an embedded NUL.
  const char* begin = value.GetString();
  char* end = nullptr;
  out = std::strtod(begin, &end);
  return end != begin && end == begin + value.GetStringLength();
}

bool valijson_equal(const rapidjson::Value& schema_value, const rapidjson::Value& target) {
  if (schema_value.IsNull()) return target.IsNull();
  if (schema_value.IsBool()) return target.IsBool() && target.GetBool() == schema_value.GetBool();
  if (schema_value.IsNumber()) {
    return target.IsNumber() && valijson_number(target) == valijson_number(schema_value);
  }
  if (schema_value.IsString()) return target.IsString() && same_string(schema_value, target);
  if (schema_value.IsArray()) return equal_arrays(schema_value, target);
  return equal_objects(schema_value, target);
}

}  // namespace a3::eval
