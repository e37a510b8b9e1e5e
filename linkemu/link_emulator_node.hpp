// The link emulator node. Relays link_message_t between the ground side and the vehicle
// side (A3_LINK_UP_TX → A3_LINK_UP_RX, A3_LINK_DOWN_TX → A3_LINK_DOWN_RX), each message
// delayed, lost or slowed as the active slice's n_t dictates at its send time (see
// LinkTransmitter); publishes n_t on A3_NET (periodically and whenever it changes); writes
// one link_record_t per message; switches slices on request after the handover delay;
// answers edge-compute requests. Runs unchanged on either runtime of common/; in virtual
// time it is deterministic for a seed.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "a3lcm/edge_compute_request_t.hpp"
#include "a3lcm/link_record_t.hpp"
#include "a3lcm/slice_switch_request_t.hpp"
#include "common/bus.hpp"
#include "common/executor.hpp"
#include "common/node.hpp"
#include "linkemu/delivery_queue.hpp"
#include "linkemu/link_emulator_config.hpp"
#include "linkemu/link_stats.hpp"
#include "linkemu/link_transmitter.hpp"
#include "linkemu/network_state_source.hpp"
#include "linkemu/slice_profile.hpp"
#include "linkemu/slice_selector.hpp"

namespace a3::linkemu {

class LinkEmulatorNode final : public common::Node {
 public:
  using RecordSink = std::function<void(const a3lcm::link_record_t& record)>;

  // Throws std::invalid_argument (bad config) naming the field. The executor and the bus
  // given to start() must outlive the node's activity (as for every common::Node).
  explicit LinkEmulatorNode(LinkEmulatorConfig config,
                            const SliceProfiles& profiles = default_slice_profiles());

  std::string name() const override { return "linkemu"; }
  void start(common::Executor& executor, common::Bus& bus) override;
  // Subscribes the two directions' TX channels and the slice and edge requests; publishes the
  // RX channels, A3_NET, the slice and edge replies and (publish_records) A3_LINK_RECORD.
  std::optional<common::NodePorts> ports() const override;

  // Called for every record, on the executor's thread. Add before start().
  void add_record_sink(RecordSink sink) { sinks_.push_back(std::move(sink)); }

  // The accessors below belong to the executor's thread (or to after it stopped).
  const LinkStats& stats() const { return stats_; }
  const common::CounterSet& counters() const override { return counter_set_; }
  NetworkState current_state();
  std::optional<Slice> pending_slice() const { return selector_->pending(); }
  // Publish time minus scheduled delivery time of the last deliveries, µs (0 in virtual
  // time; the real-time error of the node). Keeps the last `capacity` samples.
  std::vector<float> delivery_lateness_us() const;
  void set_lateness_capacity(std::size_t capacity);
  const LinkEmulatorConfig& config() const { return config_; }
  const SliceProfiles& profiles() const { return profiles_; }
  std::string describe_source() const;

 private:
  struct Direction {
    const char* name;
    std::string tx_channel, rx_channel;
    LinkTransmitter transmitter;
    DeliveryQueue queue;
    DirectionStats* stats;
    common::TimerId timer = 0;
    int64_t armed_us;
  };

  void on_link_bytes(Direction& d, const uint8_t* data, std::size_t size);
  void drop(Direction& d, DropReason reason, const a3lcm::link_message_t* message,
            int64_t size_bytes, const std::string& detail, const NetworkState& state);
  void emit_record(a3lcm::link_record_t& record, const NetworkState& state);
  void arm(Direction& d, int64_t t_us);
  void deliver_due(Direction& d);
  void on_slice_request(const a3lcm::slice_switch_request_t& request);
  void on_edge_request(const a3lcm::edge_compute_request_t& request);
  void publish_net();
  void on_state_change();
  void schedule_change_timer();
  std::string pending_name() const;

  LinkEmulatorConfig config_;
  SliceProfiles profiles_;
  common::Executor* executor_ = nullptr;
  common::Bus* bus_ = nullptr;
  std::unique_ptr<NetworkStateSource> source_;
  std::unique_ptr<SliceSelector> selector_;
  Direction up_, down_;
  common::CounterSet counter_set_;
  LinkStats stats_{counter_set_};
  std::vector<RecordSink> sinks_;
  common::TimerId change_timer_ = 0;
  std::vector<float> lateness_us_;
  std::size_t lateness_capacity_ = 1u << 18;
  std::size_t lateness_next_ = 0;
};

}  // namespace a3::linkemu
