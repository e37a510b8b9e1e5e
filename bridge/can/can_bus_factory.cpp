// Choosing and opening a CAN transport (see can_bus_factory.hpp).
#include "bridge/can/can_bus_factory.hpp"

#include <stdexcept>

#include "common/log.hpp"

namespace a3::bridge {

CanTransportChoice choose_can_transport(const std::string& spec) {
  CanTransportChoice choice;
  const auto colon = spec.find(':');
  const std::string kind = colon == std::string::npos ? "" : spec.substr(0, colon);
  choice.name = colon == std::string::npos ? spec : spec.substr(colon + 1);
  if (choice.name.empty()) {
    throw std::invalid_argument("CAN bus '" + spec + "': no interface or bus name");
  }
  if (kind == "userspace") {
    choice.transport = CanTransport::kUserspace;
    return choice;
  }
  if (kind != "socketcan" && !kind.empty()) {
    throw std::invalid_argument("CAN bus '" + spec +
                                "': unknown kind '" + kind + "' (socketcan:NAME, userspace:NAME or NAME)");
  }
  choice.reason = SocketCanBus::probe(choice.name);
  if (choice.reason.empty() || kind == "socketcan") {
    choice.transport = CanTransport::kSocketCan;
    return choice;
  }
  choice.transport = CanTransport::kUserspace;
  choice.fell_back = true;
  return choice;
}

std::unique_ptr<CanBus> open_can_bus(const std::string& spec, const CanBusOpenOptions& options) {
  const CanTransportChoice choice = choose_can_transport(spec);
  if (choice.transport == CanTransport::kSocketCan) {
    auto bus = std::make_unique<SocketCanBus>(choice.name, options.socketcan);
    common::log_info("can", "using SocketCAN interface " + choice.name);
    return bus;
  }
  auto bus = std::make_unique<UserspaceCanBus>(choice.name, options.userspace);
  if (choice.fell_back) {
    common::log_warn("can", "SocketCAN " + choice.name + " cannot be used: " + choice.reason +
                                "; falling back to the userspace CAN bus '" + choice.name +
                                "' in " + bus->directory().string() +
                                " (reaches only processes on this machine that use it too)");
  } else {
    common::log_info("can", "using the userspace CAN bus '" + choice.name + "' in " +
                                bus->directory().string());
  }
  return bus;
}

}  // namespace a3::bridge
