// CAN frame wire length and arbitration order (see frame_timing.hpp). The exact length is
// computed a byte at a time: a table-driven CRC-15 (the data's bytes as independent lookups)
// and a table-driven stuff-bit counter (a five-equal-bits state machine stepped by whole
// bytes), both resumed from a cached state after the frame's header when that header was seen
// recently. frame_bits_reference.cpp holds the bit-by-bit version the tests compare this with.
#include "bridge/can/frame_timing.hpp"

#include <algorithm>
#include <array>
#include <utility>

#include "bridge/can/crc16_slicing.hpp"

namespace a3::bridge {
namespace {

constexpr unsigned kFixedTailBits = 1 + 2 + 7 + 3;  // CRC delimiter, ACK slot+delimiter, EOF, IFS
constexpr uint16_t kCrc15Polynomial = 0x4599;

constexpr uint16_t crc15_bit(uint16_t crc, unsigned in) {
  const unsigned top = (crc >> 14) & 1u;
  crc = static_cast<uint16_t>((crc << 1) & 0x7FFF);
  return (in ^ top) != 0 ? static_cast<uint16_t>(crc ^ kCrc15Polynomial) : crc;
}

// Entry i: the register after shifting eight zero bits through a register whose top eight
// bits are i, the rest zero.
constexpr std::array<uint16_t, 256> make_crc15_table() {
  std::array<uint16_t, 256> table{};
  for (unsigned i = 0; i < 256; ++i) {
    uint16_t crc = static_cast<uint16_t>(i << 7);
    for (int bit = 0; bit < 8; ++bit) crc = crc15_bit(crc, 0);
    table[i] = crc;
  }
  return table;
}
constexpr std::array<uint16_t, 256> kCrc15Table = make_crc15_table();

uint16_t crc15_byte(uint16_t crc, uint8_t byte) {
  const unsigned index = ((crc >> 7) ^ byte) & 0xFFu;
  return static_cast<uint16_t>(((crc << 8) & 0x7FFF) ^ kCrc15Table[index]);
}

// Stuffing state: the last bit's value (bit 2) and how many equal bits end with it, minus
// one (bits 0-1; a run of five is stuffed at once, so 1..4).
constexpr uint8_t stuff_step(uint8_t state, unsigned bit, unsigned& stuff_bits) {
  unsigned last = state >> 2;
  unsigned run = (state & 3u) + 1;
  if (bit == last) {
    ++run;
  } else {
    run = 1;
    last = bit;
  }
  if (run == 5) {
    // The stuff bit has the opposite value and starts the next run.
    ++stuff_bits;
    last = bit ^ 1u;
    run = 1;
  }
  return static_cast<uint8_t>((last << 2) | (run - 1));
}

struct StuffEntry {
  uint8_t next_state;
  uint8_t stuff_bits;
};
constexpr std::array<std::array<StuffEntry, 256>, 8> make_stuff_table() {
  std::array<std::array<StuffEntry, 256>, 8> table{};
  for (unsigned state = 0; state < 8; ++state) {
    for (unsigned byte = 0; byte < 256; ++byte) {
      unsigned stuff = 0;
      uint8_t s = static_cast<uint8_t>(state);
      for (int i = 7; i >= 0; --i) s = stuff_step(s, (byte >> i) & 1u, stuff);
      table[state][byte] = StuffEntry{s, static_cast<uint8_t>(stuff)};
    }
  }
  return table;
}
constexpr auto kStuffTable = make_stuff_table();

// Stuff bits in the last 1..7 bits of a stream: kTailStuff[count - 1][state][bits], the bits
// right-aligned. The state after them is not needed, as nothing follows.
constexpr std::array<std::array<std::array<uint8_t, 128>, 8>, 7> make_tail_stuff_table() {
  std::array<std::array<std::array<uint8_t, 128>, 8>, 7> table{};
  for (unsigned count = 1; count <= 7; ++count) {
    for (unsigned state = 0; state < 8; ++state) {
      for (unsigned bits = 0; bits < (1u << count); ++bits) {
        unsigned stuff = 0;
        uint8_t s = static_cast<uint8_t>(state);
        for (unsigned i = count; i-- > 0;) s = stuff_step(s, (bits >> i) & 1u, stuff);
        table[count - 1][state][bits] = static_cast<uint8_t>(stuff);
      }
    }
  }
  return table;
}
constexpr auto kTailStuff = make_tail_stuff_table();

// The CRC-15 over whole data bytes, n at a time: the 15-bit register left-aligned in 16 bits
// (polynomial << 1), so that, as for any 16-bit CRC, n bytes are n independent lookups.
constexpr Crc16SlicingTables kCrc15Slices = crc16_slicing_tables(kCrc15Polynomial << 1);

// The CRC-15 register after `crc` took N data bytes (straight-line code for each N).
template <unsigned N>
uint16_t crc15_bytes(uint16_t crc, const uint8_t* data) {
  const auto& t = kCrc15Slices;
  const unsigned aligned = crc << 1u;
  if constexpr (N == 0) {
    return crc;
  } else if constexpr (N == 1) {
    return static_cast<uint16_t>((((aligned << 8) & 0xFFFFu) ^ t[0][(aligned >> 8) ^ data[0]]) >> 1);
  } else {
    unsigned out = t[N - 1][(aligned >> 8) ^ data[0]] ^ t[N - 2][(aligned & 0xFFu) ^ data[1]];
    [&]<std::size_t... I>(std::index_sequence<I...>) { ((out ^= t[N - 3 - I][data[I + 2]]), ...); }
    (std::make_index_sequence<N - 2>{});
    return static_cast<uint16_t>(out >> 1);
  }
}

uint16_t crc15_bytes(uint16_t crc, const uint8_t* data, unsigned n) {
  switch (n) {
    case 0: return crc15_bytes<0>(crc, data);
    case 1: return crc15_bytes<1>(crc, data);
    case 2: return crc15_bytes<2>(crc, data);
    case 3: return crc15_bytes<3>(crc, data);
    case 4: return crc15_bytes<4>(crc, data);
    case 5: return crc15_bytes<5>(crc, data);
    case 6: return crc15_bytes<6>(crc, data);
    case 7: return crc15_bytes<7>(crc, data);
    default: return crc15_bytes<8>(crc, data);
  }
}

// Counts the stuff bits of a bit stream pushed in pieces of up to 56 bits, MSB first.
class StuffCounter {
 public:
  struct State {
    uint64_t acc;
    unsigned pending;
    uint8_t state;
    unsigned stuff_bits;
  };
  StuffCounter() = default;
  explicit StuffCounter(const State& s)
      : acc_(s.acc), pending_(s.pending), state_(s.state), stuff_bits_(s.stuff_bits) {}
  State state() const { return {acc_, pending_, state_, stuff_bits_}; }
  void push(uint64_t value, unsigned count) {
    acc_ = (acc_ << count) | value;
    pending_ += count;
    while (pending_ >= 8) {
      pending_ -= 8;
      const StuffEntry& e = kStuffTable[state_][(acc_ >> pending_) & 0xFFu];
      state_ = e.next_state;
      stuff_bits_ += e.stuff_bits;
    }
  }
  // The stuff bits of the whole stream; nothing may be pushed after it.
  unsigned finish() const {
    if (pending_ == 0) return stuff_bits_;
    return stuff_bits_ + kTailStuff[pending_ - 1][state_][acc_ & ((1u << pending_) - 1)];
  }

 private:
  uint64_t acc_ = 0;
  unsigned pending_ = 0;
  // Before SOF (a dominant 0): "last bit recessive", so SOF starts a run of one.
  uint8_t state_ = 0b100;
  unsigned stuff_bits_ = 0;
};

struct HeaderBits {
  uint64_t value;  // SOF .. DLC, MSB first, right-aligned
  unsigned count;
};

HeaderBits header_bits(const CanFrame& frame, unsigned dlc) {
  const uint64_t rtr = frame.remote ? 1u : 0u;
  if (frame.extended) {
    // SOF, base ID (11), SRR=1, IDE=1, ID extension (18), RTR, r1, r0, DLC (4).
    const uint64_t base = (frame.id >> 18) & 0x7FF;
    const uint64_t extension = frame.id & 0x3FFFF;
    return {(base << 27) | (1u << 26) | (1u << 25) | (extension << 7) | (rtr << 6) | dlc, 39};
  }
  // SOF, ID (11), RTR, IDE=0, r0, DLC (4).
  return {(uint64_t{frame.id & 0x7FF} << 7) | (rtr << 6) | dlc, 19};
}

// CRC-15 of the header. The register starts at zero, so the header's leading zero padding
// up to whole bytes leaves it unchanged.
uint16_t header_crc15(const HeaderBits& header) {
  uint16_t crc = 0;
  for (unsigned shift = (header.count + 7) / 8 * 8; shift > 0;) {
    shift -= 8;
    crc = crc15_byte(crc, static_cast<uint8_t>(header.value >> shift));
  }
  return crc;
}

// The CRC and stuffing state after a header, for the last headers seen: a bus carries few
// distinct IDs (the rig's: nearly every frame's header was seen before), and the header is a
// third of the work. Direct-mapped, per thread; `tag` is the header's key + 1 (0: empty).
struct HeaderState {
  uint64_t tag;
  StuffCounter::State stuff;
  uint16_t crc;
};
constexpr std::size_t kHeaderCacheSize = 64;
thread_local HeaderState header_cache[kHeaderCacheSize];

const HeaderState& header_state(const HeaderBits& header) {
  const uint64_t tag = (header.value | (uint64_t{header.count} << 48)) + 1;
  HeaderState& entry = header_cache[(tag * 0x9E3779B97F4A7C15ull) >> 58];
  if (entry.tag != tag) {
    StuffCounter stuff;
    stuff.push(header.value, header.count);
    entry = HeaderState{tag, stuff.state(), header_crc15(header)};
  }
  return entry;
}

// The stuff bits of a whole frame whose header left `after`: its data bytes, then its CRC.
// The header left fewer than 8 bits pending, and each data byte keeps that count, so every
// byte is one table step.
unsigned stuff_bits_after_header(const HeaderState& after, const uint8_t* data, unsigned n) {
  const StuffCounter::State& h = after.stuff;
  uint64_t acc = h.acc;
  const unsigned pending = h.pending;
  unsigned state = h.state, stuff = h.stuff_bits;
  for (unsigned i = 0; i < n; ++i) {
    acc = (acc << 8) | data[i];
    const StuffEntry& e = kStuffTable[state][(acc >> pending) & 0xFFu];
    state = e.next_state;
    stuff += e.stuff_bits;
  }
  StuffCounter tail(StuffCounter::State{acc, pending, static_cast<uint8_t>(state), stuff});
  tail.push(crc15_bytes(after.crc, data, n), 15);
  return tail.finish();
}

}  // namespace

uint16_t can_crc15(const uint8_t* bits, unsigned bit_count) {
  uint16_t crc = 0;
  const unsigned whole_bytes = bit_count / 8;
  for (unsigned i = 0; i < whole_bytes; ++i) crc = crc15_byte(crc, bits[i]);
  for (unsigned i = whole_bytes * 8; i < bit_count; ++i) {
    crc = crc15_bit(crc, (bits[i / 8] >> (7 - i % 8)) & 1u);
  }
  return crc;
}

unsigned can_frame_bits(const CanFrame& frame, BitStuffing stuffing) {
  const unsigned data_bytes = frame.remote ? 0u : std::min<unsigned>(frame.size, 8);
  const unsigned dlc = std::min<unsigned>(frame.size, 8);
  // g: bits from SOF to the end of the CRC that stuffing applies to, besides the data.
  const unsigned g = frame.extended ? 54 : 34;
  const unsigned stuffed_region = g + 8 * data_bytes;
  if (stuffing == BitStuffing::kNone) return stuffed_region + kFixedTailBits;
  if (stuffing == BitStuffing::kWorstCase) {
    return stuffed_region + kFixedTailBits + (stuffed_region - 1) / 4;
  }
  const HeaderState& after_header = header_state(header_bits(frame, dlc));
  return stuffed_region + stuff_bits_after_header(after_header, frame.data.data(), data_bytes) + kFixedTailBits;
}

uint32_t can_arbitration_key(const CanFrame& frame) {
  const uint32_t rtr = frame.remote ? 1u : 0u;
  if (frame.extended) {
    const uint32_t base = (frame.id >> 18) & 0x7FF;
    return (base << 21) | (1u << 20) | (1u << 19) | ((frame.id & 0x3FFFF) << 1) | rtr;
  }
  return ((frame.id & 0x7FF) << 21) | (rtr << 20);
}

}  // namespace a3::bridge
