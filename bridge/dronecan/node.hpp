// A DroneCAN node on a CanBus: the interface the flight controller and the LCM<->CAN bridge
// build on. publish<T>() serializes a message, numbers it with the next transfer ID of its
// type and puts its frames on the bus; subscribe<T>() reassembles, checks and decodes
// received transfers of that type and calls the handler on the node's executor. Bad frames
// and payloads are counted (stats()), never passed on; the first of each kind is logged.
// Stale partial transfers are swept by a timer on the executor clock. Optionally publishes
// uavcan.protocol.NodeStatus (1 Hz is what DroneCAN expects).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "bridge/can/can_bus.hpp"
#include "bridge/dronecan/data_type_table.hpp"
#include "bridge/dronecan/msg/protocol.hpp"
#include "bridge/dronecan/reassembler.hpp"
#include "bridge/dronecan/serialization.hpp"
#include "bridge/dronecan/transfer.hpp"
#include "common/executor.hpp"
#include "common/log.hpp"

namespace a3::bridge {

struct DroneCanNodeConfig {
  uint8_t node_id = 0;  // 1..127, unique on the bus
  ReassemblerConfig reassembler;
  int64_t stale_sweep_period_us = 500'000;
};

struct DroneCanNodeStats {
  uint64_t transfers_published = 0;
  uint64_t publish_failures = 0;   // encoding failed or the bus refused a frame
  uint64_t transfers_received = 0;  // decoded and handed to a subscriber
  uint64_t decode_failures = 0;     // transfers whose payload did not decode
  uint64_t node_id_conflicts = 0;   // frames from another node using our node ID
};

class DroneCanNode {
 public:
  template <class Msg>
  using Handler = std::function<void(const Msg& msg, const ReceivedTransfer& transfer)>;

  // Throws std::invalid_argument for a node ID outside 1..127. The bus must outlive the node.
  DroneCanNode(CanBus& bus, DroneCanNodeConfig config);
  DroneCanNode(CanBus& bus, uint8_t node_id) : DroneCanNode(bus, config_for(node_id)) {}
  ~DroneCanNode();
  DroneCanNode(const DroneCanNode&) = delete;
  DroneCanNode& operator=(const DroneCanNode&) = delete;

  // Starts receiving (bus.start) and the stale-transfer sweep on `executor`.
  void start(common::Executor& executor);
  void stop();

  template <DsdlCompound Msg>
  bool publish(const Msg& msg, uint8_t priority = kPriorityMedium) {
    TransferHeader header = message_header<Msg>(config_.node_id, 0, priority);
    uint8_t& next = next_transfer_id(header.data_type_id);
    header.transfer_id = next;
    frames_.clear();
    const CodecStatus status = append_message_frames(msg, header, payload_, frames_);
    if (!status.ok()) {
      ++stats_.publish_failures;
      warn_once("encode:" + std::string(Msg::kType.full_name), status.message(Msg::kType.full_name));
      return false;
    }
    next = static_cast<uint8_t>((next + 1) % kTransferIdModulo);
    return send_frames(Msg::kType.full_name);
  }

  template <DsdlCompound Msg>
  void subscribe(Handler<Msg> handler) {
    types_.add_message<Msg>();
    handlers_for(Msg::kType.default_dtid).push_back(
        [this, handler = std::move(handler)](const ReceivedTransfer& transfer) {
          Msg msg{};
          const CodecStatus status = decode_payload(transfer.payload, transfer.size, msg);
          if (!status.ok()) {
            ++stats_.decode_failures;
            warn_once("decode:" + std::string(Msg::kType.full_name),
                      status.message(Msg::kType.full_name) + " (from node " +
                          std::to_string(transfer.header.source_node_id) + ")");
            return;
          }
          ++stats_.transfers_received;
          handler(msg, transfer);
        });
  }

  // Publishes NodeStatus every period_us from start(); uptime from the executor clock.
  void publish_node_status_every(int64_t period_us);
  void set_health(uint8_t health) { node_status_.health = health; }
  void set_mode(uint8_t mode) { node_status_.mode = mode; }
  void set_vendor_status(uint16_t code) { node_status_.vendor_specific_status_code = code; }

  uint8_t node_id() const { return config_.node_id; }
  const DroneCanNodeStats& stats() const { return stats_; }
  const ReassemblerStats& reassembler_stats() const { return reassembler_.stats(); }
  CanBus& bus() { return bus_; }

 private:
  static DroneCanNodeConfig config_for(uint8_t node_id) {
    DroneCanNodeConfig config;
    config.node_id = node_id;
    return config;
  }
  using TransferHandler = std::function<void(const ReceivedTransfer&)>;
  void on_frame(const CanFrame& frame, int64_t rx_time_us);
  uint8_t& next_transfer_id(uint16_t data_type_id);
  std::vector<TransferHandler>& handlers_for(uint16_t data_type_id);
  bool send_frames(std::string_view type_name);
  void publish_node_status();
  void warn_once(const std::string& key, const std::string& message);

  CanBus& bus_;
  DroneCanNodeConfig config_;
  DataTypeTable types_;
  TransferReassembler reassembler_;
  // Per data type ID, searched in place: a node has a handful, looked up for every transfer.
  std::vector<std::pair<uint16_t, std::vector<TransferHandler>>> handlers_;
  std::vector<std::pair<uint16_t, uint8_t>> next_transfer_id_;
  Payload payload_;
  std::vector<CanFrame> frames_;
  DroneCanNodeStats stats_;
  common::Executor* executor_ = nullptr;
  std::vector<common::TimerId> timers_;
  int64_t node_status_period_us_ = 0;
  int64_t start_us_ = 0;
  NodeStatus node_status_;
  std::unordered_map<std::string, bool> warned_;
};

}  // namespace a3::bridge
