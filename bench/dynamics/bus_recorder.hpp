// A node that records the vehicle states and rotor commands heard on the bus, for the dynamics
// benchmarks.
#pragma once

#include <mutex>
#include <string>
#include <vector>

#include "a3lcm/actuator_cmd_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "common/channels.hpp"
#include "common/node.hpp"

namespace a3::bench {

// Records the states and commands heard on the bus (optionally only the last state, and then
// no commands).
class BusRecorder final : public common::Node {
 public:
  explicit BusRecorder(bool keep_all = true) : keep_all_(keep_all) {}
  std::string name() const override { return "recorder"; }
  void start(common::Executor&, common::Bus& bus) override {
    bus.subscribe<a3lcm::vehicle_state_t>(common::channels::kState.of(0),
                                          [this](const a3lcm::vehicle_state_t& s, int64_t) {
                                            std::lock_guard<std::mutex> lock(mutex_);
                                            last_state_ = s;
                                            ++state_count_;
                                            if (keep_all_) states_.push_back(s);
                                          });
    // Only when commands are kept: a subscriber that drops them still costs a delivery per
    // command, which the speed benchmarks would count against the node.
    if (!keep_all_) return;
    bus.subscribe<a3lcm::actuator_cmd_t>(common::channels::kActuators.of(0),
                                         [this](const a3lcm::actuator_cmd_t& c, int64_t) {
                                           std::lock_guard<std::mutex> lock(mutex_);
                                           commands_.push_back(c);
                                         });
  }
  a3lcm::vehicle_state_t last_state() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return last_state_;
  }
  uint64_t state_count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return state_count_;
  }
  const std::vector<a3lcm::vehicle_state_t>& states() const { return states_; }
  const std::vector<a3lcm::actuator_cmd_t>& commands() const { return commands_; }

 private:
  bool keep_all_;
  mutable std::mutex mutex_;
  a3lcm::vehicle_state_t last_state_{};
  uint64_t state_count_ = 0;
  std::vector<a3lcm::vehicle_state_t> states_;
  std::vector<a3lcm::actuator_cmd_t> commands_;
};

}  // namespace a3::bench
