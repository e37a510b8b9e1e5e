#include "eval/parser_agreement.hpp"

#include <cstring>
#include <vector>

#include "eval/exact_numbers.hpp"
#include "eval/json_shape.hpp"
#include "eval/simdjson_parser.hpp"
#include "eval/utf8.hpp"

namespace a3::eval {
namespace {

bool same_number(const rapidjson::Value& a, const rapidjson::Value& b) {
  if (a.IsInt() != b.IsInt() || a.IsUint() != b.IsUint() || a.IsInt64() != b.IsInt64() ||
      a.IsUint64() != b.IsUint64() || a.IsDouble() != b.IsDouble()) {
    return false;
  }
  if (a.IsDouble()) {
    const double x = a.GetDouble(), y = b.GetDouble();
    return std::memcmp(&x, &y, sizeof x) == 0;
  }
  return a.IsInt64() ? a.GetInt64() == b.GetInt64() : a.GetUint64() == b.GetUint64();
}

bool same_string(const rapidjson::Value& a, const rapidjson::Value& b) {
  return std::string_view(a.GetString(), a.GetStringLength()) ==
         std::string_view(b.GetString(), b.GetStringLength());
}

bool has_duplicate_key_violation(const Violations& violations) {
  for (const Violation& v : violations) {
    if (v.rule == "json-duplicate-key") return true;
  }
  return false;
}

}  // namespace

bool identical_json(const rapidjson::Value& a, const rapidjson::Value& b) {
  if (a.GetType() != b.GetType()) return false;
  switch (a.GetType()) {
    case rapidjson::kNullType:
    case rapidjson::kFalseType:
    case rapidjson::kTrueType: return true;
    case rapidjson::kNumberType: return same_number(a, b);
    case rapidjson::kStringType: return same_string(a, b);
    case rapidjson::kArrayType:
      if (a.Size() != b.Size()) return false;
      for (rapidjson::SizeType i = 0; i < a.Size(); ++i) {
        if (!identical_json(a[i], b[i])) return false;
      }
      return true;
    case rapidjson::kObjectType:
      if (a.MemberCount() != b.MemberCount()) return false;
      for (auto x = a.MemberBegin(), y = b.MemberBegin(); x != a.MemberEnd(); ++x, ++y) {
        if (!same_string(x->name, y->name) || !identical_json(x->value, y->value)) return false;
      }
      return true;
  }
  return false;
}

ParserAgreement compare_parsers(std::string_view text) {
  ParserAgreement result;
  std::vector<char> padded(text.size() + kSimdjsonPaddingBytes + 1, '\0');
  std::memcpy(padded.data(), text.data(), text.size());
  SimdjsonParser fast;
  rapidjson::Document fast_document;
  result.fast_accepted = fast.parse(fast_document, std::string_view(padded.data(), text.size()));
  if (!result.fast_accepted) return result;
  if (find_invalid_utf8(text)) {
    result.disagreement = "simdjson accepted text that is not UTF-8";
  } else if (std::memchr(text.data(), '\0', text.size()) != nullptr) {
    result.disagreement = "simdjson accepted text with a NUL byte";
  }
  if (result.disagreement) return result;
  std::vector<char> in_place(padded);
  ExactNumberParser reference;
  rapidjson::Document reference_document;
  const auto parsed = reference.parse_insitu(reference_document, in_place.data());
  if (parsed.IsError()) {
    result.disagreement = "simdjson accepted text the reference parser refuses (" +
                          std::string(rapidjson::GetParseError_En(parsed.Code())) + " at byte " +
                          std::to_string(parsed.Offset()) + ")";
    return result;
  }
  if (!identical_json(fast_document, reference_document)) {
    result.disagreement = "the two parsers built different documents";
    return result;
  }
  Violations shape;
  JsonShapeChecker().check(reference_document, shape);
  for (const Violation& v : shape) {
    if (v.rule == "json-depth") result.disagreement = "simdjson accepted a document nested too deep";
  }
  if (!result.disagreement && has_duplicate_key_violation(shape) != fast.has_duplicate_key()) {
    result.disagreement = fast.has_duplicate_key()
                              ? "simdjson found a duplicate key the shape check does not"
                              : "the shape check found a duplicate key simdjson did not";
  }
  return result;
}

}  // namespace a3::eval
