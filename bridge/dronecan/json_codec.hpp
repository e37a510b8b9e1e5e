// Message structs <-> JSON objects, field by field from the declared DSDL layout: for the
// test vectors, `a3rig can monitor` and `a3rig can send`. Floats that are NaN are null in
// JSON; text arrays (BatteryInfo.model_name) are strings. Reading is strict: a missing or
// unknown field, a wrong type or a value outside the field's range throws
// std::invalid_argument naming the JSON path.
#pragma once

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "bridge/dronecan/dsdl_types.hpp"

namespace a3::bridge {

template <DsdlCompound Msg>
nlohmann::json message_to_json(const Msg& msg);
template <DsdlCompound Msg>
Msg message_from_json(const nlohmann::json& json, const std::string& path = "");

namespace json_detail {

[[noreturn]] inline void bad(const std::string& path, const std::string& what) {
  throw std::invalid_argument((path.empty() ? std::string("message") : path) + ": " + what);
}

template <class T, class Tag>
nlohmann::json to_json_value(const T& value, const Tag&) {
  if constexpr (std::is_same_v<Tag, dsdl::Compound>) {
    return message_to_json(value);
  } else if constexpr (std::is_same_v<Tag, dsdl::Float>) {
    if (std::isnan(value)) return nullptr;
    return static_cast<double>(value);
  } else if constexpr (std::is_same_v<Tag, dsdl::Bool>) {
    return static_cast<bool>(value);
  } else if constexpr (std::is_signed_v<T>) {
    return static_cast<int64_t>(value);
  } else {
    return static_cast<uint64_t>(value);
  }
}

template <class C, class E>
nlohmann::json to_json_value(const C& items, const dsdl::Array<E>& tag) {
  if constexpr (std::is_integral_v<typename dsdl::ArrayTraits<C>::Value>) {
    if (tag.text) return std::string(items.begin(), items.end());
  }
  nlohmann::json array = nlohmann::json::array();
  for (const auto& item : items) array.push_back(to_json_value(item, tag.element));
  return array;
}

struct ToJson {
  nlohmann::json object = nlohmann::json::object();
  template <class V, class Tag>
  void operator()(const V& value, const char* name, const Tag& tag) {
    object[name] = to_json_value(value, tag);
  }
  void void_field(unsigned) {}
};

template <class T>
void integer_from_json(const nlohmann::json& j, T& out, bool is_signed, unsigned bits,
                       const std::string& path) {
  const std::string type = (is_signed ? "int" : "uint") + std::to_string(bits);
  if (!j.is_number_integer()) bad(path, "expected an integer (" + type + "), got " + j.dump());
  if (is_signed) {
    const int64_t v = j.get<int64_t>();
    const int64_t max = bits >= 64 ? std::numeric_limits<int64_t>::max()
                                   : (int64_t{1} << (bits - 1)) - 1;
    if (v > max || v < -max - 1 || (j.is_number_unsigned() && j.get<uint64_t>() > uint64_t(max))) {
      bad(path, j.dump() + " is outside " + type);
    }
    out = static_cast<T>(v);
  } else {
    if (!j.is_number_unsigned()) bad(path, j.dump() + " is outside " + type);
    const uint64_t v = j.get<uint64_t>();
    const uint64_t max = bits >= 64 ? std::numeric_limits<uint64_t>::max()
                                    : (uint64_t{1} << bits) - 1;
    if (v > max) bad(path, j.dump() + " is outside " + type);
    out = static_cast<T>(v);
  }
}

template <class T>
void from_json_value(const nlohmann::json& j, T& out, const dsdl::Uint& t, const std::string& p) {
  integer_from_json(j, out, false, t.bits, p);
}
template <class T>
void from_json_value(const nlohmann::json& j, T& out, const dsdl::Int& t, const std::string& p) {
  integer_from_json(j, out, true, t.bits, p);
}
template <class T>
void from_json_value(const nlohmann::json& j, T& out, const dsdl::Bool&, const std::string& p) {
  if (j.is_boolean()) {
    out = j.get<bool>();
  } else if (j.is_number_unsigned() && j.get<uint64_t>() <= 1) {
    out = j.get<uint64_t>() == 1;
  } else {
    bad(p, "expected true or false, got " + j.dump());
  }
}
template <class T>
void from_json_value(const nlohmann::json& j, T& out, const dsdl::Float&, const std::string& p) {
  if (j.is_null()) {
    out = std::numeric_limits<T>::quiet_NaN();
  } else if (j.is_number()) {
    out = static_cast<T>(j.get<double>());
  } else {
    bad(p, "expected a number (or null for NaN), got " + j.dump());
  }
}
template <class T>
void from_json_value(const nlohmann::json& j, T& out, const dsdl::Compound&,
                     const std::string& p) {
  out = message_from_json<T>(j, p);
}

template <class C, class E>
void from_json_value(const nlohmann::json& j, C& items, const dsdl::Array<E>& tag,
                     const std::string& p) {
  using Traits = dsdl::ArrayTraits<C>;
  const std::size_t max = Traits::kMaxSize;
  if constexpr (Traits::kDynamic && std::is_integral_v<typename Traits::Value>) {
    if (tag.text && j.is_string()) {
      const std::string text = j.get<std::string>();
      if (text.size() > max) {
        bad(p, "text of " + std::to_string(text.size()) + " bytes, at most " +
                   std::to_string(max));
      }
      items.clear();
      for (char c : text) items.push_back(static_cast<typename Traits::Value>(c));
      return;
    }
  }
  if (!j.is_array()) bad(p, "expected an array, got " + j.dump());
  if constexpr (Traits::kDynamic) {
    if (j.size() > max) {
      bad(p, std::to_string(j.size()) + " elements, at most " + std::to_string(max));
    }
    items.clear();
    for (std::size_t i = 0; i < j.size(); ++i) {
      typename Traits::Value item{};
      from_json_value(j[i], item, tag.element, p + "[" + std::to_string(i) + "]");
      items.push_back(item);
    }
  } else {
    if (j.size() != max) {
      bad(p, std::to_string(j.size()) + " elements, exactly " + std::to_string(max) + " needed");
    }
    for (std::size_t i = 0; i < max; ++i) {
      from_json_value(j[i], items[i], tag.element, p + "[" + std::to_string(i) + "]");
    }
  }
}

struct FromJson {
  const nlohmann::json& object;
  const std::string& path;
  std::size_t used = 0;
  template <class V, class Tag>
  void operator()(V& value, const char* name, const Tag& tag) {
    const std::string field_path = path.empty() ? std::string(name) : path + "." + name;
    const auto it = object.find(name);
    if (it == object.end()) bad(field_path, "missing");
    ++used;
    from_json_value(*it, value, tag, field_path);
  }
  void void_field(unsigned) {}
};

struct FieldNames {
  std::vector<std::string> names;
  template <class V, class Tag>
  void operator()(V&, const char* name, const Tag&) { names.emplace_back(name); }
  void void_field(unsigned) {}
};

}  // namespace json_detail

template <DsdlCompound Msg>
nlohmann::json message_to_json(const Msg& msg) {
  json_detail::ToJson visitor;
  Msg::visit_fields(msg, visitor);
  return visitor.object;
}

template <DsdlCompound Msg>
Msg message_from_json(const nlohmann::json& json, const std::string& path) {
  if (!json.is_object()) {
    json_detail::bad(path, std::string("expected an object with the fields of ") +
                               std::string(Msg::kType.full_name) + ", got " + json.dump());
  }
  Msg msg{};
  json_detail::FromJson visitor{json, path};
  Msg::visit_fields(msg, visitor);
  if (visitor.used != json.size()) {
    json_detail::FieldNames known;
    Msg::visit_fields(msg, known);
    for (const auto& [key, value] : json.items()) {
      if (std::find(known.names.begin(), known.names.end(), key) == known.names.end()) {
        json_detail::bad(path.empty() ? key : path + "." + key,
                         std::string("not a field of ") + std::string(Msg::kType.full_name));
      }
    }
  }
  return msg;
}

}  // namespace a3::bridge
