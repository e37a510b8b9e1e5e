// DroneCAN node over a CanBus (see node.hpp).
#include "bridge/dronecan/node.hpp"

#include <stdexcept>

namespace a3::bridge {

DroneCanNode::DroneCanNode(CanBus& bus, DroneCanNodeConfig config)
    : bus_(bus), config_(config), reassembler_(types_, config.reassembler) {
  if (config_.node_id < 1 || config_.node_id > kMaxNodeId) {
    throw std::invalid_argument("DroneCAN node ID " + std::to_string(config_.node_id) +
                                " is not in 1..127");
  }
  if (config_.stale_sweep_period_us <= 0) {
    throw std::invalid_argument("DroneCanNode: stale_sweep_period_us must be positive");
  }
  node_status_.mode = NodeStatus::kModeOperational;
  frames_.reserve(64);
}

DroneCanNode::~DroneCanNode() { stop(); }

void DroneCanNode::start(common::Executor& executor) {
  if (executor_ != nullptr) throw std::logic_error("DroneCanNode: started twice");
  executor_ = &executor;
  start_us_ = executor.clock().now_us();
  bus_.start(executor, [this](const CanFrame& frame, int64_t rx_time_us) { on_frame(frame, rx_time_us); });
  timers_.push_back(executor.schedule_every(config_.stale_sweep_period_us, [this] {
    reassembler_.expire(executor_->clock().now_us());
  }));
  if (node_status_period_us_ > 0) {
    publish_node_status();
    timers_.push_back(executor.schedule_every(node_status_period_us_, [this] { publish_node_status(); }));
  }
}

void DroneCanNode::stop() {
  if (executor_ == nullptr) return;
  bus_.stop();
  for (const auto id : timers_) executor_->cancel(id);
  timers_.clear();
  executor_ = nullptr;
}

void DroneCanNode::publish_node_status_every(int64_t period_us) {
  if (period_us <= 0) throw std::invalid_argument("NodeStatus period must be positive");
  node_status_period_us_ = period_us;
  if (executor_ != nullptr) {
    timers_.push_back(executor_->schedule_every(period_us, [this] { publish_node_status(); }));
  }
}

void DroneCanNode::publish_node_status() {
  node_status_.uptime_sec = static_cast<uint32_t>((executor_->clock().now_us() - start_us_) / 1'000'000);
  publish(node_status_, kPriorityLow);
}

bool DroneCanNode::send_frames(std::string_view type_name) {
  bool ok = true;
  for (const CanFrame& frame : frames_) {
    if (!bus_.send(frame)) {
      ok = false;
      break;  // the rest of the transfer is useless without this frame
    }
  }
  if (ok) {
    ++stats_.transfers_published;
  } else {
    ++stats_.publish_failures;
    warn_once("send:" + std::string(type_name),
              std::string(type_name) + ": " + bus_.name() + " refused a frame (queue full?)");
  }
  return ok;
}

void DroneCanNode::on_frame(const CanFrame& frame, int64_t rx_time_us) {
  if (frame.extended && !frame.error) {
    const TransferHeader header = parse_can_id(frame.id);
    if (header.source_node_id == config_.node_id) {
      ++stats_.node_id_conflicts;
      warn_once("conflict", "another node on " + bus_.name() + " uses node ID " +
                                std::to_string(config_.node_id));
      return;
    }
  }
  ReceivedTransfer transfer;
  const FrameVerdict verdict = reassembler_.accept(frame, rx_time_us, transfer);
  if (verdict == FrameVerdict::kRejected) {
    warn_once("frame:" + std::string(to_string(reassembler_.last_error())),
              "rejected a frame on " + bus_.name() + ": " +
                  std::string(to_string(reassembler_.last_error())) + " (" +
                  to_cansend_string(frame) + "); further ones are only counted");
    return;
  }
  if (verdict != FrameVerdict::kTransferComplete || transfer.header.kind != TransferKind::kMessage) {
    return;
  }
  // By index: a handler that subscribes to another type may grow handlers_.
  for (std::size_t i = 0; i < handlers_.size(); ++i) {
    if (handlers_[i].first != transfer.header.data_type_id) continue;
    for (std::size_t j = 0; j < handlers_[i].second.size(); ++j) handlers_[i].second[j](transfer);
    return;
  }
}

uint8_t& DroneCanNode::next_transfer_id(uint16_t data_type_id) {
  for (auto& [id, next] : next_transfer_id_) {
    if (id == data_type_id) return next;
  }
  return next_transfer_id_.emplace_back(data_type_id, uint8_t{0}).second;
}

std::vector<DroneCanNode::TransferHandler>& DroneCanNode::handlers_for(uint16_t data_type_id) {
  for (auto& [id, handlers] : handlers_) {
    if (id == data_type_id) return handlers;
  }
  return handlers_.emplace_back(data_type_id, std::vector<TransferHandler>{}).second;
}

void DroneCanNode::warn_once(const std::string& key, const std::string& message) {
  if (warned_[key]) return;
  warned_[key] = true;
  common::log_warn("dronecan", "node " + std::to_string(config_.node_id) + ": " + message);
}

}  // namespace a3::bridge
