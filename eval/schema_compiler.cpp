// Compiles a JSON Schema's text into CompiledSchema's subschema list, refusing every keyword and
// form whose valijson meaning the checks in compiled_schema.cpp do not reproduce.
#include "eval/compiled_schema.hpp"

#include <algorithm>
#include <cstring>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include "common/json_pointer.hpp"
#include "eval/valijson_values.hpp"

namespace a3::eval {

class SchemaCompiler {
 public:
  SchemaCompiler(CompiledSchema& out, std::string_view schema_name) : out_(out), name_(schema_name) {}

  SchemaNodeIndex compile(const rapidjson::Value& schema, const std::string& pointer);
  void check_no_endless_conditional() const;

 private:
  [[noreturn]] void refuse(const std::string& pointer, const std::string& why) const {
    throw std::invalid_argument(name_ + ": " + (pointer.empty() ? "/" : pointer) + ": " + why +
                                " (not supported by the compiled schema validator, eval/compiled_schema.hpp)");
  }
  SchemaNodeIndex add_node(const rapidjson::Value& schema, SchemaNode node);
  SchemaNodeIndex compile_ref(const rapidjson::Value& schema, const std::string& pointer);
  const rapidjson::Value& resolve(const std::string& ref, const std::string& pointer) const;
  SchemaNode compile_keywords(const rapidjson::Value& schema, const std::string& pointer);
  void read_keyword(SchemaNode& node, const rapidjson::Value& schema, const std::string& keyword,
                    const rapidjson::Value& value, const std::string& pointer);
  uint8_t read_type(const rapidjson::Value& value, const std::string& pointer) const;
  uint8_t read_type_name(const rapidjson::Value& value, const std::string& pointer) const;
  std::string read_name(const rapidjson::Value& value, const std::string& pointer) const;
  std::vector<std::string> read_required(const rapidjson::Value& value, const std::string& pointer) const;
  std::vector<NamedSchema> read_properties(const rapidjson::Value& value, const std::string& pointer);
  static void mark_required_properties(SchemaNode& node);
  void read_additional(SchemaNode& node, const rapidjson::Value& value, const std::string& pointer);
  uint64_t read_count(const rapidjson::Value& value, const std::string& pointer) const;
  double read_number(const rapidjson::Value& value, const std::string& pointer) const;
  double read_divisor(const rapidjson::Value& value, const std::string& pointer) const;
  const rapidjson::Value* read_literal(const rapidjson::Value& value, const std::string& pointer) const;
  bool endless_from(SchemaNodeIndex node, std::vector<int>& state) const;

  CompiledSchema& out_;
  std::string name_;
  std::map<const rapidjson::Value*, SchemaNodeIndex> compiled_;  // by place in the schema text
  std::set<const rapidjson::Value*> refs_in_progress_;
};

namespace {

const std::set<std::string> kAnnotations = {"$schema", "title", "description", "$comment"};

std::string child(const std::string& pointer, std::string_view token) {
  return pointer + "/" + common::json_pointer_token(token);
}

std::string name_of(const rapidjson::Value& name) { return std::string(name.GetString(), name.GetStringLength()); }

bool has_nul(const rapidjson::Value& text) {
  return std::memchr(text.GetString(), '\0', text.GetStringLength()) != nullptr;
}

// An empty schema, or one of annotations only, accepts everything.
bool accepts_everything(const SchemaNode& node) {
  return !node.type_mask && node.required.empty() && node.properties.empty() &&
         node.additional != AdditionalProperties::kNone && node.additional_schema == kNoSchemaNode &&
         node.items == kNoSchemaNode && !node.min_items && !node.max_items && !node.minimum &&
         !node.maximum && !node.multiple_of && node.const_value == nullptr &&
         node.enum_values == nullptr && node.if_schema == kNoSchemaNode;
}

}  // namespace

SchemaNodeIndex SchemaCompiler::add_node(const rapidjson::Value& schema, SchemaNode node) {
  out_.nodes_.push_back(std::move(node));
  const auto index = static_cast<SchemaNodeIndex>(out_.nodes_.size() - 1);
  compiled_[&schema] = index;
  return index;
}

SchemaNodeIndex SchemaCompiler::compile(const rapidjson::Value& schema, const std::string& pointer) {
  if (const auto it = compiled_.find(&schema); it != compiled_.end()) return it->second;
  if (schema.IsBool()) {
    SchemaNode node;
    node.kind = schema.GetBool() ? SchemaNode::Kind::kAlwaysValid : SchemaNode::Kind::kAlwaysInvalid;
    return add_node(schema, std::move(node));
  }
  if (!schema.IsObject()) refuse(pointer, "a schema must be an object or a boolean");
  if (schema.HasMember("$ref")) return compile_ref(schema, pointer);
  // Reserve the index first: subschemas may refer back to this one through $ref.
  const SchemaNodeIndex index = add_node(schema, SchemaNode{});
  SchemaNode node = compile_keywords(schema, pointer);
  if (accepts_everything(node)) node.kind = SchemaNode::Kind::kAlwaysValid;
  out_.nodes_[static_cast<std::size_t>(index)] = std::move(node);
  return index;
}

// Draft 7 (valijson) ignores the keywords beside $ref and 2020-12 applies them: only annotations
// and containers of schemas may stand beside it. The reference becomes the index of the schema
// it points to.
SchemaNodeIndex SchemaCompiler::compile_ref(const rapidjson::Value& schema, const std::string& pointer) {
  for (auto it = schema.MemberBegin(); it != schema.MemberEnd(); ++it) {
    const std::string keyword = name_of(it->name);
    if (keyword != "$ref" && keyword != "$defs" && keyword != "definitions" && kAnnotations.count(keyword) == 0) {
      refuse(child(pointer, keyword), "keyword \"" + keyword + "\" beside $ref");
    }
  }
  const rapidjson::Value& ref = schema["$ref"];
  if (!ref.IsString()) refuse(child(pointer, "$ref"), "$ref must be a string");
  const std::string target_pointer = name_of(ref).substr(std::min<std::size_t>(1, ref.GetStringLength()));
  const rapidjson::Value& target = resolve(name_of(ref), child(pointer, "$ref"));
  if (!refs_in_progress_.insert(&schema).second) {
    refuse(child(pointer, "$ref"), "a cycle of $ref that never reaches a schema");
  }
  const SchemaNodeIndex index = compile(target, target_pointer);
  refs_in_progress_.erase(&schema);
  compiled_[&schema] = index;
  return index;
}

// "#" or "#/a/b~1c/0": a JSON Pointer into this schema (nothing is fetched).
const rapidjson::Value& SchemaCompiler::resolve(const std::string& ref, const std::string& pointer) const {
  if (ref.empty() || ref[0] != '#' || ref.find('%') != std::string::npos ||
      (ref.size() > 1 && ref[1] != '/')) {
    refuse(pointer, "$ref \"" + ref + "\" is not a local JSON Pointer (\"#/...\") without %-escapes");
  }
  const rapidjson::Value* at = &out_.schema_;
  std::size_t start = 1;
  while (start < ref.size()) {
    const std::size_t end = std::min(ref.find('/', start + 1), ref.size());
    std::string token = ref.substr(start + 1, end - start - 1);
    for (std::size_t i = 0; (i = token.find("~1", i)) != std::string::npos; ++i) token.replace(i, 2, "/");
    for (std::size_t i = 0; (i = token.find("~0", i)) != std::string::npos; ++i) token.replace(i, 2, "~");
    const rapidjson::Value* next = nullptr;
    if (at->IsObject()) {
      const auto member = at->FindMember(rapidjson::Value(rapidjson::StringRef(token.data(), token.size())));
      if (member != at->MemberEnd()) next = &member->value;
    } else if (at->IsArray() && !token.empty() && token.size() < 10 &&
               token.find_first_not_of("0123456789") == std::string::npos && (token == "0" || token[0] != '0')) {
      const auto i = static_cast<rapidjson::SizeType>(std::stoul(token));
      if (i < at->Size()) next = &(*at)[i];
    }
    if (next == nullptr) refuse(pointer, "$ref \"" + ref + "\" points to nothing in the schema");
    at = next;
    start = end;
  }
  return *at;
}

SchemaNode SchemaCompiler::compile_keywords(const rapidjson::Value& schema, const std::string& pointer) {
  SchemaNode node;
  std::set<std::string> seen;
  for (auto it = schema.MemberBegin(); it != schema.MemberEnd(); ++it) {
    const std::string keyword = name_of(it->name);
    if (!seen.insert(keyword).second) refuse(child(pointer, keyword), "keyword written twice");
    read_keyword(node, schema, keyword, it->value, child(pointer, keyword));
  }
  mark_required_properties(node);
  return node;
}

// A required name with a property schema is found once, when its schema is checked.
void SchemaCompiler::mark_required_properties(SchemaNode& node) {
  for (const std::string& name : node.required) {
    auto property = std::find_if(node.properties.begin(), node.properties.end(),
                                 [&](const NamedSchema& p) { return p.name == name; });
    if (property != node.properties.end()) {
      property->required = true;
    } else {
      node.required_beyond_properties.push_back(name);
    }
  }
}

void SchemaCompiler::read_keyword(SchemaNode& node, const rapidjson::Value& schema, const std::string& keyword,
                                  const rapidjson::Value& value, const std::string& at) {
  if (kAnnotations.count(keyword) != 0) {
    if (keyword != "$comment" && !value.IsString()) refuse(at, "must be a string");
  } else if (keyword == "$defs" || keyword == "definitions") {
    // Containers: their schemas take effect only where a $ref points, and are compiled there.
    if (!value.IsObject()) refuse(at, "must be an object of schemas");
  } else if (keyword == "type") {
    node.type_mask = read_type(value, at);
  } else if (keyword == "required") {
    node.required = read_required(value, at);
  } else if (keyword == "properties") {
    node.properties = read_properties(value, at);
  } else if (keyword == "additionalProperties") {
    read_additional(node, value, at);
  } else if (keyword == "items") {
    if (value.IsArray()) refuse(at, "items as a list of schemas (a tuple)");
    node.items = compile(value, at);
  } else if (keyword == "minItems") {
    node.min_items = read_count(value, at);
  } else if (keyword == "maxItems") {
    node.max_items = read_count(value, at);
  } else if (keyword == "minimum") {
    node.minimum = read_number(value, at);
  } else if (keyword == "maximum") {
    node.maximum = read_number(value, at);
  } else if (keyword == "multipleOf") {
    node.multiple_of = read_divisor(value, at);
  } else if (keyword == "const") {
    node.const_value = read_literal(value, at);
  } else if (keyword == "enum") {
    if (!value.IsArray()) refuse(at, "enum must be a list");
    node.enum_values = read_literal(value, at);
  } else if (keyword == "if") {
    node.if_schema = compile(value, at);
    // valijson, like the drafts, reads then and else only beside if.
    const std::string parent = at.substr(0, at.size() - 3);
    if (schema.HasMember("then")) node.then_schema = compile(schema["then"], parent + "/then");
    if (schema.HasMember("else")) node.else_schema = compile(schema["else"], parent + "/else");
  } else if (keyword != "then" && keyword != "else") {
    refuse(at, "keyword \"" + keyword + "\"");
  }
}

uint8_t SchemaCompiler::read_type_name(const rapidjson::Value& value, const std::string& pointer) const {
  static const std::map<std::string, uint8_t> kTypes = {
      {"null", kTypeNull},     {"boolean", kTypeBoolean}, {"object", kTypeObject}, {"array", kTypeArray},
      {"string", kTypeString}, {"number", kTypeNumber},   {"integer", kTypeInteger}};
  if (value.IsString()) {
    if (const auto it = kTypes.find(name_of(value)); it != kTypes.end()) return it->second;
  }
  refuse(pointer, "a type must be one of null, boolean, object, array, string, number, integer");
}

uint8_t SchemaCompiler::read_type(const rapidjson::Value& value, const std::string& pointer) const {
  if (!value.IsArray()) return read_type_name(value, pointer);
  uint8_t mask = 0;
  for (rapidjson::SizeType i = 0; i < value.Size(); ++i) {
    mask |= read_type_name(value[i], pointer + "/" + std::to_string(i));
  }
  return mask;
}

std::string SchemaCompiler::read_name(const rapidjson::Value& value, const std::string& pointer) const {
  if (!value.IsString()) refuse(pointer, "a property name must be a string");
  if (has_nul(value)) refuse(pointer, "a property name holding a NUL character");
  return name_of(value);
}

std::vector<std::string> SchemaCompiler::read_required(const rapidjson::Value& value,
                                                        const std::string& pointer) const {
  if (!value.IsArray()) refuse(pointer, "required must be a list of names");
  std::vector<std::string> names;
  for (rapidjson::SizeType i = 0; i < value.Size(); ++i) {
    names.push_back(read_name(value[i], pointer + "/" + std::to_string(i)));
  }
  return names;
}

std::vector<NamedSchema> SchemaCompiler::read_properties(const rapidjson::Value& value, const std::string& pointer) {
  if (!value.IsObject()) refuse(pointer, "properties must be an object of schemas");
  std::vector<NamedSchema> properties;
  std::set<std::string> seen;
  for (auto it = value.MemberBegin(); it != value.MemberEnd(); ++it) {
    const std::string at = child(pointer, name_of(it->name));
    NamedSchema property{read_name(it->name, at), kNoSchemaNode};
    if (!seen.insert(property.name).second) refuse(at, "a property written twice");
    property.schema = compile(it->value, at);
    properties.push_back(std::move(property));
  }
  return properties;
}

void SchemaCompiler::read_additional(SchemaNode& node, const rapidjson::Value& value, const std::string& pointer) {
  if (value.IsBool()) {
    node.additional = value.GetBool() ? AdditionalProperties::kAny : AdditionalProperties::kNone;
    return;
  }
  if (!value.IsObject()) refuse(pointer, "additionalProperties must be a boolean or a schema");
  const SchemaNodeIndex schema = compile(value, pointer);
  // An empty schema accepts every extra property: as if absent.
  if (out_.nodes_[static_cast<std::size_t>(schema)].kind == SchemaNode::Kind::kAlwaysValid) return;
  node.additional = AdditionalProperties::kSchema;
  node.additional_schema = schema;
}

uint64_t SchemaCompiler::read_count(const rapidjson::Value& value, const std::string& pointer) const {
  if (!value.IsInt64() || value.GetInt64() < 0) refuse(pointer, "must be a non-negative integer");
  return static_cast<uint64_t>(value.GetInt64());
}

double SchemaCompiler::read_number(const rapidjson::Value& value, const std::string& pointer) const {
  if (!value.IsNumber()) refuse(pointer, "must be a number");
  return valijson_number(value);
}

// valijson truncates fractional values before checking an integer divisor (1.5 passes
// "multipleOf": 1): only a divisor written with a fraction or exponent has the drafts' meaning.
double SchemaCompiler::read_divisor(const rapidjson::Value& value, const std::string& pointer) const {
  if (!value.IsDouble()) refuse(pointer, "multipleOf must be a number written with a fraction (1.0, not 1)");
  if (!(value.GetDouble() > 0)) refuse(pointer, "multipleOf must be greater than 0");
  return value.GetDouble();
}

// const and enum values stay in the schema's document; names with a NUL are refused because
// valijson compares names with strncmp.
const rapidjson::Value* SchemaCompiler::read_literal(const rapidjson::Value& value, const std::string& pointer) const {
  if (value.IsObject()) {
    for (auto it = value.MemberBegin(); it != value.MemberEnd(); ++it) {
      read_name(it->name, pointer);
      read_literal(it->value, pointer);
    }
  } else if (value.IsArray()) {
    for (const rapidjson::Value& element : value.GetArray()) read_literal(element, pointer);
  }
  return &value;
}

// if/then/else apply a schema to the same value: a cycle through them would never end.
bool SchemaCompiler::endless_from(SchemaNodeIndex index, std::vector<int>& state) const {
  auto& mark = state[static_cast<std::size_t>(index)];
  if (mark == 1) return true;
  if (mark == 2) return false;
  mark = 1;
  const SchemaNode& node = out_.nodes_[static_cast<std::size_t>(index)];
  for (SchemaNodeIndex next : {node.if_schema, node.then_schema, node.else_schema}) {
    if (next != kNoSchemaNode && endless_from(next, state)) return true;
  }
  mark = 2;
  return false;
}

void SchemaCompiler::check_no_endless_conditional() const {
  std::vector<int> state(out_.nodes_.size(), 0);
  for (std::size_t i = 0; i < out_.nodes_.size(); ++i) {
    if (endless_from(static_cast<SchemaNodeIndex>(i), state)) {
      refuse("", "if/then/else refer back to themselves through $ref without descending into the value");
    }
  }
}

CompiledSchema::CompiledSchema(std::string_view schema_json, std::string_view schema_name) {
  schema_.Parse(schema_json.data(), schema_json.size());
  if (schema_.HasParseError()) {
    throw std::invalid_argument(std::string(schema_name) + ": schema is not valid JSON (offset " +
                                std::to_string(schema_.GetErrorOffset()) + "): " +
                                rapidjson::GetParseError_En(schema_.GetParseError()));
  }
  SchemaCompiler compiler(*this, schema_name);
  root_ = compiler.compile(schema_, "");
  compiler.check_no_endless_conditional();
}

}  // namespace a3::eval
