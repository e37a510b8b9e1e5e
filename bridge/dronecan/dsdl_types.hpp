// How a C++ message struct declares its DSDL layout. Each message type has
//   static constexpr DataTypeInfo kType{...};
//   template <class Self, class Visitor> static void visit_fields(Self& self, Visitor& v);
// where visit_fields calls, in DSDL order, v(self.field, "name", tag) for every field and
// v.void_field(bits) for every voidN. Tags: dsdl::Uint{bits}, dsdl::Int{bits},
// dsdl::Float{bits}, dsdl::Bool{}, dsdl::Compound{}, dsdl::Array{element tag}. An array is
// static for std::array<T, N> (T[N]) and dynamic for BoundedVector<T, N> (T[<=N]).
// Serialization, JSON, the normalized DSDL definition and the signature are all derived
// from this one declaration (serialization.hpp, dsdl_layout.hpp, json_codec.hpp), and a
// test checks it against the DSDL file.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <type_traits>

#include "bridge/dronecan/bounded_vector.hpp"

namespace a3::bridge {

struct DataTypeInfo {
  std::string_view full_name;      // e.g. "uavcan.equipment.esc.RawCommand"
  uint16_t default_dtid;           // 0 for nested types, which have none
  uint64_t signature;              // DroneCAN data type signature (CRC-64-WE)
  unsigned max_bit_length;         // longest serialized form, without tail array optimisation
};

namespace dsdl {

enum class Cast : uint8_t { kSaturated, kTruncated };

struct Uint {
  unsigned bits;
  Cast cast = Cast::kSaturated;
};
struct Int {
  unsigned bits;
  Cast cast = Cast::kSaturated;
};
struct Float {
  unsigned bits;  // 16, 32 or 64
  Cast cast = Cast::kSaturated;
};
struct Bool {};
struct Compound {};
template <class Element>
struct Array {
  Element element;
  bool text = false;  // uint8 array shown as a string (JSON, monitor)
};
template <class Element>
Array(Element) -> Array<Element>;
template <class Element>
Array(Element, bool) -> Array<Element>;

template <class C>
struct ArrayTraits;
template <class T, std::size_t N>
struct ArrayTraits<std::array<T, N>> {
  using Value = T;
  static constexpr bool kDynamic = false;
  static constexpr std::size_t kMaxSize = N;
};
template <class T, std::size_t N>
struct ArrayTraits<BoundedVector<T, N>> {
  using Value = T;
  static constexpr bool kDynamic = true;
  static constexpr std::size_t kMaxSize = N;
};

// Bits of a dynamic array's length prefix: enough for max_size itself.
constexpr unsigned length_prefix_bits(std::size_t max_size) {
  unsigned bits = 0;
  while (max_size != 0) {
    ++bits;
    max_size >>= 1;
  }
  return bits;
}

}  // namespace dsdl

// True for message structs declaring kType and visit_fields.
template <class T>
concept DsdlCompound = requires { T::kType.full_name; };

}  // namespace a3::bridge
