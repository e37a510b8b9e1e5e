// The link emulator node: relay with per-message timing and loss, n_t publication,
// slice switching, edge-compute answers, per-message records.
#include "linkemu/link_emulator_node.hpp"

#include <algorithm>
#include <exception>
#include <limits>
#include <sstream>

#include "a3lcm/edge_compute_reply_t.hpp"
#include "a3lcm/link_message_t.hpp"
#include "a3lcm/network_state_t.hpp"
#include "a3lcm/slice_switch_reply_t.hpp"
#include "common/log.hpp"
#include "common/rng.hpp"
#include "linkemu/synthetic_network.hpp"
#include "linkemu/trace_replay.hpp"

namespace a3::linkemu {
namespace {

constexpr int64_t kNever = std::numeric_limits<int64_t>::max();
constexpr const char* kLog = "linkemu";

// Log the first few drops of a reason, then every thousandth, so a flood cannot flood the log.
bool worth_logging(uint64_t count) { return count <= 5 || count % 1000 == 0; }

Slice initial_slice(const LinkEmulatorConfig& c) {
  return c.trace ? c.trace->points.front().state.slice : c.initial_slice;
}

LinkEmulatorConfig validated(LinkEmulatorConfig config) {
  validate(config);
  return config;
}

// How far ahead of this node's clock a sender's send time is believed (ingress_time_us).
constexpr int64_t kMaxSenderLead_us = 100'000;

// A message enters the link when it was sent, or when it is heard if that is later. In lockstep
// a sender's datagram can reach this node before the master's grant of its send time does (they
// come from different sockets): one quantum early, and its send time puts it where virtual time
// does. Bounded, so that a sender whose clock is wrong cannot hold a message back for long.
int64_t ingress_time_us(int64_t heard_us, int64_t sent_us) {
  return std::clamp(sent_us, heard_us, heard_us + kMaxSenderLead_us);
}

}  // namespace

LinkEmulatorNode::LinkEmulatorNode(LinkEmulatorConfig config, const SliceProfiles& profiles)
    : config_(validated(std::move(config))),
      profiles_(effective_profiles(profiles, config_)),
      selector_(std::make_unique<SliceSelector>(
          initial_slice(config_), std::llround(config_.handover_delay_ms * 1e3))),
      up_{"up", config_.channels.up_tx, config_.channels.up_rx,
          LinkTransmitter(common::RngStreams(config_.seed), "up", config_.link), {}, &stats_.up,
          0, kNever},
      down_{"down", config_.channels.down_tx, config_.channels.down_rx,
            LinkTransmitter(common::RngStreams(config_.seed), "down", config_.link), {},
            &stats_.down, 0, kNever} {
  // Check the regime timing now rather than at start(): a bad override fails here.
  if (!config_.trace) {
    SyntheticNetwork probe(profiles_, common::RngStreams(config_.seed), config_.start_regime, 0);
  }
}

std::optional<common::NodePorts> LinkEmulatorNode::ports() const {
  const LinkChannels& c = config_.channels;
  using common::TypedChannel;
  common::NodePorts ports;
  ports.subscribes(TypedChannel<a3lcm::link_message_t>{c.up_tx})
      .subscribes(TypedChannel<a3lcm::link_message_t>{c.down_tx})
      .subscribes(TypedChannel<a3lcm::slice_switch_request_t>{c.slice_request})
      .listens(TypedChannel<a3lcm::edge_compute_request_t>{c.edge_request})  // for edge-compute clients
      .publishes(TypedChannel<a3lcm::link_message_t>{c.up_rx})
      .publishes(TypedChannel<a3lcm::link_message_t>{c.down_rx})
      .publishes(TypedChannel<a3lcm::network_state_t>{c.net})
      .publishes(TypedChannel<a3lcm::slice_switch_reply_t>{c.slice_reply})
      .publishes(TypedChannel<a3lcm::edge_compute_reply_t>{c.edge_reply});
  if (config_.publish_records) ports.publishes(TypedChannel<a3lcm::link_record_t>{c.record});
  return ports;
}

void LinkEmulatorNode::start(common::Executor& executor, common::Bus& bus) {
  if (executor_ != nullptr) throw std::logic_error("LinkEmulatorNode::start called twice");
  executor_ = &executor;
  bus_ = &bus;
  const int64_t now_us = executor.clock().now_us();
  const common::RngStreams streams(config_.seed);
  if (config_.trace) {
    source_ = std::make_unique<TraceReplay>(*config_.trace, now_us, config_.trace_loop);
  } else {
    DegradationWindows forced;
    for (const auto& w : config_.forced_degradations) forced.emplace_back(now_us + w.start_us, now_us + w.end_us);
    source_ = std::make_unique<SyntheticNetwork>(profiles_, streams, config_.start_regime, now_us, forced);
  }

  for (Direction* d : {&up_, &down_}) {
    bus.subscribe_raw(d->tx_channel, [this, d](const std::string&, const uint8_t* data,
                                               std::size_t size, int64_t) {
      on_link_bytes(*d, data, size);
    });
  }
  bus.subscribe<a3lcm::slice_switch_request_t>(
      config_.channels.slice_request,
      [this](const a3lcm::slice_switch_request_t& m, int64_t) { on_slice_request(m); });
  bus.subscribe<a3lcm::edge_compute_request_t>(
      config_.channels.edge_request,
      [this](const a3lcm::edge_compute_request_t& m, int64_t) { on_edge_request(m); });

  executor.schedule_at(now_us, [this] { on_state_change(); });
  if (config_.net_rate_hz > 0.0) {
    const int64_t period_us = std::max<int64_t>(1, std::llround(1e6 / config_.net_rate_hz));
    executor.schedule(now_us + period_us, period_us, [this] { publish_net(); });
  }
  std::ostringstream line;
  line << "started: " << describe_source() << ", slice " << to_string(selector_->active_at(now_us))
       << ", handover " << config_.handover_delay_ms << " ms, "
       << (config_.link.reordering ? "reordering" : "FIFO")
       << (config_.link.gilbert_elliott.enabled ? ", Gilbert-Elliott loss" : "");
  common::log_info(kLog, line.str());
}

std::string LinkEmulatorNode::describe_source() const {
  if (source_) return source_->describe();
  return config_.trace ? "trace replay" : "seeded slice-profile process";
}

NetworkState LinkEmulatorNode::current_state() {
  const int64_t now_us = executor_ != nullptr ? executor_->clock().now_us() : 0;
  const Slice slice = selector_->active_at(now_us);
  if (!source_) {
    throw std::logic_error("LinkEmulatorNode::current_state before start()");
  }
  return source_->state_at(slice, now_us);
}

std::string LinkEmulatorNode::pending_name() const {
  const auto pending = selector_->pending();
  return pending ? to_string(*pending) : "";
}

void LinkEmulatorNode::publish_net() {
  const NetworkState state = current_state();
  bus_->publish(config_.channels.net, to_lcm(state, executor_->clock().now_us(), pending_name()));
  ++stats_.net_published;
}

void LinkEmulatorNode::on_state_change() {
  publish_net();
  schedule_change_timer();
}

void LinkEmulatorNode::schedule_change_timer() {
  if (change_timer_ != 0) executor_->cancel(change_timer_);
  change_timer_ = 0;
  const Slice slice = selector_->active_at(executor_->clock().now_us());
  const int64_t next_us =
      std::min(source_->next_change_us(slice), selector_->pending_effective_us());
  if (next_us == kNever) return;
  change_timer_ = executor_->schedule_at(next_us, [this] {
    change_timer_ = 0;  // this timer has fired: nothing to cancel any more
    on_state_change();
  });
}

void LinkEmulatorNode::emit_record(a3lcm::link_record_t& r, const NetworkState& state) {
  r.slice = to_string(state.slice);
  r.net_lat_ms = state.lat_ms;
  r.net_jitter_ms = state.jitter_ms;
  r.net_loss_pct = state.loss_pct;
  r.net_throughput_mbps = state.throughput_mbps;
  r.net_edge_load = state.edge_load;
  r.net_degraded = state.degraded;
  ++stats_.records;
  for (const RecordSink& sink : sinks_) sink(r);
  if (config_.publish_records) bus_->publish(config_.channels.record, r);
}

void LinkEmulatorNode::drop(Direction& d, DropReason reason, const a3lcm::link_message_t* message,
                            int64_t size_bytes, const std::string& detail,
                            const NetworkState& state) {
  const uint64_t count = ++d.stats->dropped[static_cast<std::size_t>(reason)];
  if (worth_logging(count)) {
    std::ostringstream line;
    line << "dropped " << (d.name == std::string("up") ? "an uplink" : "a downlink") << " message";
    if (message != nullptr) line << " (id " << message->message_id << " from '" << message->sender << "')";
    line << ": " << to_string(reason) << ": " << detail << " [" << count << " " << d.name << " "
         << to_string(reason) << " drops so far]";
    common::log_warn(kLog, line.str());
  }
  a3lcm::link_record_t r{};
  r.utime_us = executor_->clock().now_us();
  r.direction = d.name;
  r.message_id = message != nullptr ? message->message_id : -1;
  if (message != nullptr) {
    r.sender = message->sender;
    r.kind = message->kind;
    r.sent_utime_us = message->sent_utime_us;
  }
  r.size_bytes = size_bytes;
  r.outcome = a3lcm::link_record_t::DROPPED;
  r.drop_reason = std::string(to_string(reason)) + ": " + detail;
  r.delivery_utime_us = -1;
  emit_record(r, state);
}

void LinkEmulatorNode::on_link_bytes(Direction& d, const uint8_t* data, std::size_t size) {
  ++d.stats->received;
  const int64_t now_us = executor_->clock().now_us();
  const NetworkState state = current_state();

  a3lcm::link_message_t message;
  int decoded = -1;
  try {
    decoded = message.decode(data, 0, static_cast<int>(size));
  } catch (const std::exception&) {
    decoded = -1;  // lcm-gen decoders throw on a bad length field
  }
  if (decoded < 0) {
    drop(d, DropReason::kUndecodable, nullptr, static_cast<int64_t>(size),
         std::to_string(size) + " bytes that do not decode as link_message_t", state);
    return;
  }
  if (message.payload_size_bytes < 0) {
    drop(d, DropReason::kBadSize, &message, message.payload_length,
         "payload_size_bytes " + std::to_string(message.payload_size_bytes) + " is negative", state);
    return;
  }
  if (message.payload_size_bytes > 0 && message.payload_size_bytes < message.payload_length) {
    drop(d, DropReason::kBadSize, &message, message.payload_length,
         "payload_size_bytes " + std::to_string(message.payload_size_bytes) +
             " is less than the " + std::to_string(message.payload_length) + "-byte payload",
         state);
    return;
  }
  const int64_t size_bytes =
      message.payload_size_bytes > 0 ? message.payload_size_bytes : message.payload_length;
  if (size_bytes > config_.max_message_bytes) {
    drop(d, DropReason::kOversized, &message, size_bytes,
         std::to_string(size_bytes) + " bytes > max_message_bytes " +
             std::to_string(config_.max_message_bytes),
         state);
    return;
  }
  const int64_t backlog_us = d.transmitter.backlog_us(now_us);
  std::string full;
  if (static_cast<int64_t>(d.queue.size()) >= config_.max_pending_messages) {
    full = std::to_string(d.queue.size()) + " messages in flight (max_pending_messages)";
  } else if (static_cast<int64_t>(d.queue.payload_bytes() + message.payload.size()) >
             config_.max_pending_bytes) {
    full = std::to_string(d.queue.payload_bytes()) + " payload bytes in flight (max_pending_bytes " +
           std::to_string(config_.max_pending_bytes) + ")";
  } else if (static_cast<double>(backlog_us) * 1e-6 > config_.max_backlog_s) {
    full = "transmitter backlog " + std::to_string(backlog_us / 1000) + " ms > max_backlog_s";
  }
  if (!full.empty()) {
    drop(d, DropReason::kQueueFull, &message, size_bytes, full, state);
    return;
  }

  const TransmitOutcome out = d.transmitter.transmit(ingress_time_us(now_us, message.sent_utime_us), size_bytes, state);
  a3lcm::link_record_t r{};
  r.utime_us = now_us;
  r.direction = d.name;
  r.message_id = message.message_id;
  r.sender = message.sender;
  r.kind = message.kind;
  r.sent_utime_us = message.sent_utime_us;
  r.size_bytes = size_bytes;
  r.outcome = out.lost ? a3lcm::link_record_t::LOST : a3lcm::link_record_t::DELIVERED;
  r.delivery_utime_us = out.lost ? -1 : out.delivery_us;
  r.queue_ms = out.queue_ms;
  r.serialization_ms = out.serialization_ms;
  r.latency_ms = out.lost ? 0.0 : out.latency_ms;
  emit_record(r, state);
  if (out.lost) {
    ++d.stats->lost;
    return;
  }
  message.slice = to_string(state.slice);
  d.queue.push(out.delivery_us, std::move(message));
  d.stats->pending.set(d.queue.size());
  d.stats->max_pending.set(std::max<uint64_t>(d.stats->max_pending, d.queue.size()));
  if (out.delivery_us < d.armed_us) arm(d, out.delivery_us);
}

void LinkEmulatorNode::arm(Direction& d, int64_t t_us) {
  if (d.timer != 0) executor_->cancel(d.timer);
  d.armed_us = t_us;
  d.timer = executor_->schedule_at(t_us, [this, &d] { deliver_due(d); });
}

void LinkEmulatorNode::deliver_due(Direction& d) {
  d.timer = 0;
  d.armed_us = kNever;
  const int64_t now_us = executor_->clock().now_us();
  while (!d.queue.empty() && d.queue.earliest_us() <= now_us) {
    auto [delivery_us, message] = d.queue.pop();
    message.utime_us = delivery_us;
    bus_->publish(d.rx_channel, message);
    ++d.stats->delivered;
    d.stats->bytes_delivered += static_cast<uint64_t>(
        message.payload_size_bytes > 0 ? message.payload_size_bytes : message.payload_length);
    if (lateness_capacity_ > 0) {
      const float late_us = static_cast<float>(executor_->clock().now_us() - delivery_us);
      if (lateness_us_.size() < lateness_capacity_) {
        lateness_us_.push_back(late_us);
      } else {
        lateness_us_[lateness_next_] = late_us;
        lateness_next_ = (lateness_next_ + 1) % lateness_capacity_;
      }
    }
  }
  d.stats->pending.set(d.queue.size());
  if (!d.queue.empty()) arm(d, d.queue.earliest_us());
}

std::vector<float> LinkEmulatorNode::delivery_lateness_us() const { return lateness_us_; }

void LinkEmulatorNode::set_lateness_capacity(std::size_t capacity) {
  lateness_capacity_ = capacity;
  lateness_us_.clear();
  lateness_next_ = 0;
}

void LinkEmulatorNode::on_slice_request(const a3lcm::slice_switch_request_t& request) {
  ++stats_.slice_switch_requests;
  const int64_t now_us = executor_->clock().now_us();
  a3lcm::slice_switch_reply_t reply{};
  reply.utime_us = now_us;
  reply.request_id = request.request_id;
  reply.requester = request.requester;
  reply.from_slice = to_string(current_state().slice);
  reply.to_slice = request.slice;
  reply.effective_utime_us = -1;
  if (source_->dictates_slice()) {
    reply.accepted = false;
    reply.reason = "the link is replaying a trace: the slice follows the trace";
  } else {
    try {
      const SwitchResult result = selector_->request(parse_slice(request.slice), now_us);
      reply.accepted = true;
      reply.reason = result.note;
      reply.effective_utime_us = result.effective_us;
    } catch (const std::invalid_argument& e) {
      reply.accepted = false;
      reply.reason = e.what();
    }
  }
  common::log_info(kLog, "slice switch to '" + request.slice + "' requested by '" +
                             request.requester + "': " +
                             (reply.accepted ? "accepted, effective at " +
                                                   std::to_string(reply.effective_utime_us) + " us"
                                             : "refused: " + reply.reason));
  bus_->publish(config_.channels.slice_reply, reply);
  on_state_change();
}

void LinkEmulatorNode::on_edge_request(const a3lcm::edge_compute_request_t& request) {
  ++stats_.edge_requests;
  const NetworkState state = current_state();
  a3lcm::edge_compute_reply_t reply{};
  reply.utime_us = executor_->clock().now_us();
  reply.request_id = request.request_id;
  reply.requester = request.requester;
  reply.work_ms = request.work_ms;
  reply.edge_load = state.edge_load;
  reply.slice = to_string(state.slice);
  try {
    reply.delay_ms = config_.edge.delay_ms(request.work_ms, state.edge_load);
  } catch (const std::invalid_argument& e) {
    reply.delay_ms = -1.0;
    reply.error = e.what();
    common::log_warn(kLog, "edge request " + std::to_string(request.request_id) + " from '" +
                               request.requester + "' refused: " + e.what());
  }
  bus_->publish(config_.channels.edge_reply, reply);
}

}  // namespace a3::linkemu
