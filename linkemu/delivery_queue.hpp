// Messages of one direction waiting for their delivery time, earliest first (ties in
// arrival order), with the payload bytes they hold.
#pragma once

#include <cstdint>
#include <map>
#include <utility>

#include "a3lcm/link_message_t.hpp"

namespace a3::linkemu {

class DeliveryQueue {
 public:
  void push(int64_t delivery_us, a3lcm::link_message_t message) {
    bytes_ += message.payload.size();
    queue_.emplace(Key{delivery_us, next_seq_++}, std::move(message));
  }
  bool empty() const { return queue_.empty(); }
  std::size_t size() const { return queue_.size(); }
  uint64_t payload_bytes() const { return bytes_; }
  int64_t earliest_us() const { return queue_.begin()->first.first; }
  // Removes and returns the earliest message with its delivery time.
  std::pair<int64_t, a3lcm::link_message_t> pop() {
    auto node = queue_.extract(queue_.begin());
    bytes_ -= node.mapped().payload.size();
    return {node.key().first, std::move(node.mapped())};
  }

 private:
  using Key = std::pair<int64_t, uint64_t>;
  std::map<Key, a3lcm::link_message_t> queue_;
  uint64_t next_seq_ = 0;
  uint64_t bytes_ = 0;
};

}  // namespace a3::linkemu
