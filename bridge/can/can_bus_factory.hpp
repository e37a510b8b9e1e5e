// Opens the CAN bus a node or tool names: "vcan0" means SocketCAN when this machine has an
// interface of that name, else the userspace bus of the same name, and says so in the log
// (warn) with the reason. "socketcan:NAME" insists on SocketCAN, "userspace:NAME" on the
// userspace bus.
#pragma once

#include <memory>
#include <string>

#include "bridge/can/can_bus.hpp"
#include "bridge/can/socketcan_bus.hpp"
#include "bridge/can/userspace_bus.hpp"

namespace a3::bridge {

enum class CanTransport : uint8_t { kSocketCan, kUserspace };

struct CanTransportChoice {
  CanTransport transport = CanTransport::kUserspace;
  std::string name;        // interface or userspace bus name
  bool fell_back = false;  // asked for a plain name, SocketCAN could not be had
  std::string reason;      // why SocketCAN could not be had ("" otherwise)
};

// Decides without opening anything (probes the interface). Throws std::invalid_argument
// for an empty name or an unknown "kind:" prefix.
CanTransportChoice choose_can_transport(const std::string& spec);

struct CanBusOpenOptions {
  SocketCanOptions socketcan;
  UserspaceCanOptions userspace;
};

// Opens the bus; logs the choice (info), or the fall-back and its reason (warn).
// Throws std::runtime_error when the bus cannot be opened (e.g. "socketcan:can0" without
// SocketCAN), with the reason.
std::unique_ptr<CanBus> open_can_bus(const std::string& spec, const CanBusOpenOptions& options = {});

}  // namespace a3::bridge
