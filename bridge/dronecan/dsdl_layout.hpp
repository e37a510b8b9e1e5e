// What a message struct's declared layout (dsdl_types.hpp) implies, computed from the C++
// declaration alone: field count, minimum and maximum bit length, the normalized DSDL
// definition and the DroneCAN data type signature. Tests compare these with the DSDL files,
// so the code cannot drift from them.
#pragma once

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "bridge/dronecan/crc.hpp"
#include "bridge/dronecan/dsdl_types.hpp"

namespace a3::bridge::dsdl_layout {

template <DsdlCompound Msg>
std::size_t field_count();
template <DsdlCompound Msg>
unsigned min_bit_length();
template <DsdlCompound Msg>
unsigned max_bit_length();
template <DsdlCompound Msg>
std::string normalized_definition();
template <DsdlCompound Msg>
uint64_t signature();

namespace detail {

inline const char* cast_name(dsdl::Cast cast) {
  return cast == dsdl::Cast::kSaturated ? "saturated" : "truncated";
}

template <class V>
unsigned max_bits(const dsdl::Uint& t) { return t.bits; }
template <class V>
unsigned max_bits(const dsdl::Int& t) { return t.bits; }
template <class V>
unsigned max_bits(const dsdl::Float& t) { return t.bits; }
template <class V>
unsigned max_bits(const dsdl::Bool&) { return 1; }
template <class V>
unsigned max_bits(const dsdl::Compound&) { return max_bit_length<V>(); }
template <class V, class E>
unsigned max_bits(const dsdl::Array<E>& t) {
  using Traits = dsdl::ArrayTraits<V>;
  const unsigned element = max_bits<typename Traits::Value>(t.element);
  const unsigned items = static_cast<unsigned>(Traits::kMaxSize) * element;
  return Traits::kDynamic ? dsdl::length_prefix_bits(Traits::kMaxSize) + items : items;
}

// Minimum bit length as pydronecan counts it: a dynamic array may be empty (0 bits).
template <class V>
unsigned min_bits(const dsdl::Uint& t) { return t.bits; }
template <class V>
unsigned min_bits(const dsdl::Int& t) { return t.bits; }
template <class V>
unsigned min_bits(const dsdl::Float& t) { return t.bits; }
template <class V>
unsigned min_bits(const dsdl::Bool&) { return 1; }
template <class V>
unsigned min_bits(const dsdl::Compound&) { return min_bit_length<V>(); }
template <class V, class E>
unsigned min_bits(const dsdl::Array<E>& t) {
  using Traits = dsdl::ArrayTraits<V>;
  if constexpr (Traits::kDynamic) {
    return 0;
  } else {
    return static_cast<unsigned>(Traits::kMaxSize) * min_bits<typename Traits::Value>(t.element);
  }
}

template <class V>
std::string type_name(const dsdl::Uint& t) {
  return std::string(cast_name(t.cast)) + " uint" + std::to_string(t.bits);
}
template <class V>
std::string type_name(const dsdl::Int& t) {
  return std::string(cast_name(t.cast)) + " int" + std::to_string(t.bits);
}
template <class V>
std::string type_name(const dsdl::Float& t) {
  return std::string(cast_name(t.cast)) + " float" + std::to_string(t.bits);
}
template <class V>
std::string type_name(const dsdl::Bool&) { return "saturated bool"; }
template <class V>
std::string type_name(const dsdl::Compound&) { return std::string(V::kType.full_name); }
template <class V, class E>
std::string type_name(const dsdl::Array<E>& t) {
  using Traits = dsdl::ArrayTraits<V>;
  return type_name<typename Traits::Value>(t.element) + (Traits::kDynamic ? "[<=" : "[") +
         std::to_string(Traits::kMaxSize) + "]";
}

// Signature of the compound type a field refers to (directly or as array elements), if any.
template <class V, class Tag>
bool nested_signature(const Tag&, uint64_t&) { return false; }
template <class V>
bool nested_signature(const dsdl::Compound&, uint64_t& out) {
  out = signature<V>();
  return true;
}
template <class V, class E>
bool nested_signature(const dsdl::Array<E>& t, uint64_t& out) {
  return nested_signature<typename dsdl::ArrayTraits<V>::Value>(t.element, out);
}

struct CountVisitor {
  std::size_t count = 0;
  template <class V, class Tag>
  void operator()(V&, const char*, const Tag&) { ++count; }
  void void_field(unsigned) { ++count; }
};

struct BitsVisitor {
  bool max = true;
  unsigned total = 0;
  template <class V, class Tag>
  void operator()(V&, const char*, const Tag& tag) {
    using Value = std::remove_const_t<V>;
    total += max ? max_bits<Value>(tag) : min_bits<Value>(tag);
  }
  void void_field(unsigned bits) { total += bits; }
};

struct DefinitionVisitor {
  std::string text;
  std::vector<uint64_t> nested;
  template <class V, class Tag>
  void operator()(V&, const char* name, const Tag& tag) {
    using Value = std::remove_const_t<V>;
    text += "\n" + type_name<Value>(tag) + " " + name;
    uint64_t sig = 0;
    if (nested_signature<Value>(tag, sig)) nested.push_back(sig);
  }
  void void_field(unsigned bits) { text += "\nvoid" + std::to_string(bits); }
};

template <class Msg, class Visitor>
Visitor visit_type() {
  const Msg instance{};
  Visitor visitor{};
  Msg::visit_fields(instance, visitor);
  return visitor;
}

}  // namespace detail

template <DsdlCompound Msg>
std::size_t field_count() {
  static const std::size_t count = detail::visit_type<Msg, detail::CountVisitor>().count;
  return count;
}

template <DsdlCompound Msg>
unsigned max_bit_length() {
  static const unsigned bits = detail::visit_type<Msg, detail::BitsVisitor>().total;
  return bits;
}

template <DsdlCompound Msg>
unsigned min_bit_length() {
  static const unsigned bits = [] {
    const Msg instance{};
    detail::BitsVisitor visitor{false, 0};
    Msg::visit_fields(instance, visitor);
    return visitor.total;
  }();
  return bits;
}

// The DSDL normalized definition (full name, then one line per field with explicit cast
// modes and [<=N] bounds, no constants or comments), as DroneCAN's tools build it.
template <DsdlCompound Msg>
std::string normalized_definition() {
  return std::string(Msg::kType.full_name) +
         detail::visit_type<Msg, detail::DefinitionVisitor>().text;
}

// CRC-64-WE of the normalized definition, extended by each nested type's signature in
// field order (DroneCAN's data type signature).
template <DsdlCompound Msg>
uint64_t signature() {
  const auto visitor = detail::visit_type<Msg, detail::DefinitionVisitor>();
  Crc64We crc;
  crc.add(std::string(Msg::kType.full_name) + visitor.text);
  for (const uint64_t nested : visitor.nested) {
    const uint64_t current = crc.value();
    crc.add_u64_le(nested);
    crc.add_u64_le(current);
  }
  return crc.value();
}

}  // namespace a3::bridge::dsdl_layout
