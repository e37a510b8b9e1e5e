// The project's lockstep time message a3.sim.Clock (20610): the simulated time granted by the
// lockstep time master, forwarded by the bridge to the flight controller (DSDL:
// bridge/dsdl/a3/sim/20610.Clock.uavcan; a test derives the signature from that file).
#pragma once

#include <cstdint>

#include "bridge/dronecan/dsdl_types.hpp"

namespace a3::bridge {

struct SimClock {
  static constexpr DataTypeInfo kType{"a3.sim.Clock", 20610, 0x644689b9a0ab3237ULL, 56};
  uint64_t utime_us = 0;  // truncated uint56, microseconds of simulated time

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.utime_us, "utime_us", dsdl::Uint{56, dsdl::Cast::kTruncated});
  }
  bool operator==(const SimClock&) const = default;
};

}  // namespace a3::bridge
