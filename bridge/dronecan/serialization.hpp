// DSDL (UAVCAN v0) serialization of message structs declared as in dsdl_types.hpp:
// bit-exact packing, saturated/truncated casts, float16, dynamic arrays with length
// prefixes, and tail array optimisation (the last field's dynamic array of >= 8-bit
// elements has no prefix and runs to the end of the payload). Never throws, never
// allocates: a control loop can call it.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>

#include "bridge/dronecan/bit_stream.hpp"
#include "bridge/dronecan/dsdl_layout.hpp"
#include "bridge/dronecan/dsdl_types.hpp"
#include "bridge/dronecan/float16.hpp"

namespace a3::bridge {

// Largest transfer payload the codec handles (gnss.Fix2, the largest type here, needs 222).
inline constexpr std::size_t kMaxTransferPayloadBytes = 256;

struct Payload {
  std::array<uint8_t, kMaxTransferPayloadBytes> bytes{};
  std::size_t size = 0;
  const uint8_t* data() const { return bytes.data(); }
};

// Outcome of encoding or decoding a payload; on failure names the field and the problem.
struct CodecStatus {
  enum class Code : uint8_t {
    kOk,
    kArrayTooLong,     // more elements than the array allows
    kPayloadTooShort,  // the payload ends inside a field
    kTrailingBytes,    // whole bytes left after the last field
    kBufferTooSmall,   // the type's maximum size exceeds kMaxTransferPayloadBytes
  };
  Code code = Code::kOk;
  const char* field = "";   // the field where it happened
  std::size_t count = 0;    // elements found (kArrayTooLong), bytes left (kTrailingBytes)
  std::size_t limit = 0;    // elements allowed (kArrayTooLong)

  bool ok() const { return code == Code::kOk; }
  // E.g. "uavcan.equipment.esc.RawCommand: field 'cmd' has 21 elements, at most 20".
  std::string message(std::string_view type_name) const;
};

namespace codec_detail {

struct EncodeContext {
  BitWriter writer;
  CodecStatus status;
  bool failed() const { return !status.ok(); }
  void fail(CodecStatus::Code code, const char* field, std::size_t count = 0,
            std::size_t limit = 0) {
    if (!failed()) status = CodecStatus{code, field, count, limit};
  }
};

struct DecodeContext {
  BitReader reader;
  CodecStatus status;
  bool failed() const { return !status.ok(); }
  void fail(CodecStatus::Code code, const char* field, std::size_t count = 0,
            std::size_t limit = 0) {
    if (!failed()) status = CodecStatus{code, field, count, limit};
  }
};

template <class Msg>
void encode_compound(EncodeContext& c, const Msg& msg, bool tao);
template <class Msg>
void decode_compound(DecodeContext& c, Msg& msg, bool tao);

// ---- encoding ----------------------------------------------------------------------

inline void put(EncodeContext& c, uint64_t raw, unsigned bits, const char* field) {
  if (!c.writer.write_scalar(raw, bits)) c.fail(CodecStatus::Code::kBufferTooSmall, field);
}

template <class T>
void encode_value(EncodeContext& c, const T& value, const dsdl::Uint& t, bool, const char* f) {
  uint64_t raw = 0;
  if constexpr (std::is_signed_v<T>) {
    // A negative value saturates to 0; truncation keeps its low bits.
    raw = value < 0 && t.cast == dsdl::Cast::kSaturated
              ? 0
              : static_cast<uint64_t>(static_cast<int64_t>(value));
  } else {
    raw = static_cast<uint64_t>(value);
  }
  if (t.bits < 64) {
    const uint64_t max = (uint64_t{1} << t.bits) - 1;
    raw = t.cast == dsdl::Cast::kSaturated ? std::min(raw, max) : raw & max;
  }
  put(c, raw, t.bits, f);
}

template <class T>
void encode_value(EncodeContext& c, const T& value, const dsdl::Int& t, bool, const char* f) {
  int64_t v = static_cast<int64_t>(value);
  if (t.bits < 64 && t.cast == dsdl::Cast::kSaturated) {
    const int64_t max = (int64_t{1} << (t.bits - 1)) - 1;
    v = std::clamp(v, -max - 1, max);
  }
  uint64_t raw = static_cast<uint64_t>(v);
  if (t.bits < 64) raw &= (uint64_t{1} << t.bits) - 1;
  put(c, raw, t.bits, f);
}

template <class T>
void encode_value(EncodeContext& c, const T& value, const dsdl::Bool&, bool, const char* f) {
  put(c, value ? 1u : 0u, 1, f);
}

template <class T>
void encode_value(EncodeContext& c, const T& value, const dsdl::Float& t, bool, const char* f) {
  const bool saturate = t.cast == dsdl::Cast::kSaturated;
  if (t.bits == 16) {
    float v = static_cast<float>(value);
    if (saturate && std::isfinite(v)) v = std::clamp(v, -kFloat16Max, kFloat16Max);
    put(c, float16_bits_from_float(v), 16, f);
  } else if (t.bits == 32) {
    double v = static_cast<double>(value);
    constexpr double kMax = std::numeric_limits<float>::max();
    if (saturate && std::isfinite(v)) v = std::clamp(v, -kMax, kMax);
    put(c, std::bit_cast<uint32_t>(static_cast<float>(v)), 32, f);
  } else {
    put(c, std::bit_cast<uint64_t>(static_cast<double>(value)), 64, f);
  }
}

template <class T>
void encode_value(EncodeContext& c, const T& value, const dsdl::Compound&, bool tao,
                  const char*) {
  encode_compound(c, value, tao);
}

template <class C, class E>
void encode_value(EncodeContext& c, const C& items, const dsdl::Array<E>& t, bool tao,
                  const char* f) {
  using Traits = dsdl::ArrayTraits<C>;
  using Value = typename Traits::Value;
  const std::size_t size = items.size();
  bool elements_tao = tao;
  if constexpr (Traits::kDynamic) {
    if (size > Traits::kMaxSize) {
      c.fail(CodecStatus::Code::kArrayTooLong, f, size, Traits::kMaxSize);
      return;
    }
    const bool optimised = tao && dsdl_layout::detail::min_bits<Value>(t.element) >= 8;
    if (!optimised) {
      put(c, size, dsdl::length_prefix_bits(Traits::kMaxSize), f);
    } else {
      elements_tao = false;  // the elements of an optimised tail array are not optimised
    }
  }
  for (std::size_t i = 0; i < size && !c.failed(); ++i) {
    encode_value(c, items[i], t.element, elements_tao && i + 1 == size, f);
  }
}

struct FieldEncoder {
  EncodeContext& c;
  bool tao;
  std::size_t fields;
  std::size_t index = 0;
  template <class V, class Tag>
  void operator()(const V& value, const char* name, const Tag& tag) {
    const bool last = ++index == fields;
    if (!c.failed()) encode_value(c, value, tag, tao && last, name);
  }
  void void_field(unsigned bits) {
    ++index;
    if (!c.failed() && !c.writer.write_zeros(bits)) {
      c.fail(CodecStatus::Code::kBufferTooSmall, "void");
    }
  }
};

template <class Msg>
void encode_compound(EncodeContext& c, const Msg& msg, bool tao) {
  FieldEncoder encoder{c, tao, dsdl_layout::field_count<Msg>()};
  Msg::visit_fields(msg, encoder);
}

// ---- decoding ----------------------------------------------------------------------

inline bool take_unsigned(DecodeContext& c, unsigned bits, uint64_t& raw, const char* field) {
  if (c.reader.read_unsigned(bits, raw)) return true;
  c.fail(CodecStatus::Code::kPayloadTooShort, field);
  return false;
}

template <class T>
void decode_value(DecodeContext& c, T& value, const dsdl::Uint& t, bool, const char* f) {
  uint64_t raw = 0;
  if (take_unsigned(c, t.bits, raw, f)) value = static_cast<T>(raw);
}

template <class T>
void decode_value(DecodeContext& c, T& value, const dsdl::Int& t, bool, const char* f) {
  int64_t raw = 0;
  if (c.reader.read_signed(t.bits, raw)) {
    value = static_cast<T>(raw);
  } else {
    c.fail(CodecStatus::Code::kPayloadTooShort, f);
  }
}

template <class T>
void decode_value(DecodeContext& c, T& value, const dsdl::Bool&, bool, const char* f) {
  uint64_t raw = 0;
  if (take_unsigned(c, 1, raw, f)) value = raw != 0;
}

template <class T>
void decode_value(DecodeContext& c, T& value, const dsdl::Float& t, bool, const char* f) {
  uint64_t raw = 0;
  if (!take_unsigned(c, t.bits, raw, f)) return;
  if (t.bits == 16) {
    value = static_cast<T>(float_from_float16_bits(static_cast<uint16_t>(raw)));
  } else if (t.bits == 32) {
    value = static_cast<T>(std::bit_cast<float>(static_cast<uint32_t>(raw)));
  } else {
    value = static_cast<T>(std::bit_cast<double>(raw));
  }
}

template <class T>
void decode_value(DecodeContext& c, T& value, const dsdl::Compound&, bool tao, const char*) {
  decode_compound(c, value, tao);
}

template <class C, class E>
void decode_value(DecodeContext& c, C& items, const dsdl::Array<E>& t, bool tao,
                  const char* f) {
  using Traits = dsdl::ArrayTraits<C>;
  using Value = typename Traits::Value;
  if constexpr (!Traits::kDynamic) {
    for (std::size_t i = 0; i < Traits::kMaxSize && !c.failed(); ++i) {
      decode_value(c, items[i], t.element, tao && i + 1 == Traits::kMaxSize, f);
    }
  } else {
    items.clear();
    const bool optimised = tao && dsdl_layout::detail::min_bits<Value>(t.element) >= 8;
    if (optimised) {
      // No prefix: elements run to the end of the payload (less its padding bits).
      while (c.reader.remaining_bits() >= 8 && !c.failed()) {
        Value item{};
        decode_value(c, item, t.element, false, f);
        if (c.failed()) return;
        if (!items.push_back(item)) {
          c.fail(CodecStatus::Code::kArrayTooLong, f, Traits::kMaxSize + 1, Traits::kMaxSize);
          return;
        }
      }
      return;
    }
    uint64_t size = 0;
    if (!take_unsigned(c, dsdl::length_prefix_bits(Traits::kMaxSize), size, f)) return;
    if (size > Traits::kMaxSize) {
      c.fail(CodecStatus::Code::kArrayTooLong, f, size, Traits::kMaxSize);
      return;
    }
    for (std::size_t i = 0; i < size && !c.failed(); ++i) {
      Value item{};
      decode_value(c, item, t.element, tao && i + 1 == size, f);
      items.push_back(item);
    }
  }
}

struct FieldDecoder {
  DecodeContext& c;
  bool tao;
  std::size_t fields;
  std::size_t index = 0;
  template <class V, class Tag>
  void operator()(V& value, const char* name, const Tag& tag) {
    const bool last = ++index == fields;
    if (!c.failed()) decode_value(c, value, tag, tao && last, name);
  }
  void void_field(unsigned bits) {
    ++index;
    if (!c.failed() && !c.reader.skip(bits)) c.fail(CodecStatus::Code::kPayloadTooShort, "void");
  }
};

template <class Msg>
void decode_compound(DecodeContext& c, Msg& msg, bool tao) {
  FieldDecoder decoder{c, tao, dsdl_layout::field_count<Msg>()};
  Msg::visit_fields(msg, decoder);
}

}  // namespace codec_detail

// Serializes msg (tail array optimisation on, as for a transfer's top-level message).
template <DsdlCompound Msg>
CodecStatus encode_payload(const Msg& msg, Payload& out) {
  static_assert((Msg::kType.max_bit_length + 7) / 8 <= kMaxTransferPayloadBytes,
                "message larger than kMaxTransferPayloadBytes");
  codec_detail::EncodeContext context{BitWriter(out.bytes.data(), out.bytes.size()), {}};
  codec_detail::encode_compound(context, msg, true);
  out.size = context.failed() ? 0 : context.writer.byte_size();
  return context.status;
}

// Deserializes a whole transfer payload into msg. Fails when the payload ends inside a
// field, an array is longer than allowed, or whole bytes are left over.
template <DsdlCompound Msg>
CodecStatus decode_payload(const uint8_t* data, std::size_t size, Msg& msg) {
  codec_detail::DecodeContext context{BitReader(data, size), {}};
  codec_detail::decode_compound(context, msg, true);
  if (!context.failed() && context.reader.remaining_bits() >= 8) {
    context.fail(CodecStatus::Code::kTrailingBytes, "", context.reader.remaining_bits() / 8);
  }
  return context.status;
}

}  // namespace a3::bridge
