// The project's message a3.fc.CommandRefused (20602): the flight controller's rate-limited
// report of transfers it refused because their source node may not command it (DSDL:
// bridge/dsdl/a3/fc/20602.CommandRefused.uavcan; a test derives the signature from that file).
#pragma once

#include <cstdint>

#include "bridge/dronecan/dsdl_types.hpp"

namespace a3::bridge {

struct FcCommandRefused {
  static constexpr DataTypeInfo kType{"a3.fc.CommandRefused", 20602, 0xd34bb7fe96d8c46bULL, 111};
  uint8_t source_node_id = 0;  // uint7
  uint16_t data_type_id = 0;
  uint8_t command = 0;
  int32_t seq = 0;
  uint16_t refused_in_report = 0;
  uint32_t refused_total = 0;

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.source_node_id, "source_node_id", dsdl::Uint{7});
    v(self.data_type_id, "data_type_id", dsdl::Uint{16});
    v(self.command, "command", dsdl::Uint{8});
    v(self.seq, "seq", dsdl::Int{32});
    v(self.refused_in_report, "refused_in_report", dsdl::Uint{16});
    v(self.refused_total, "refused_total", dsdl::Uint{32});
  }
  bool operator==(const FcCommandRefused&) const = default;
};

}  // namespace a3::bridge
