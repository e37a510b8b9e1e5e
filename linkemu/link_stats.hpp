// Counters of the link emulator, per direction: messages in, delivered, lost, and dropped
// for each bad-input reason. They live in the node's CounterSet (common/counters.hpp) under
// dotted names ("up.delivered", "down.dropped.queue_full", "slice_switch_requests"), which is
// how they reach the bus and the episode.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "common/counters.hpp"

namespace a3::linkemu {

enum class DropReason : uint8_t {
  kUndecodable = 0,   // not a link_message_t
  kBadSize = 1,       // payload_size_bytes negative, or below the payload it carries
  kOversized = 2,     // charged size above max_message_bytes
  kQueueFull = 3,     // the direction's buffer is full (messages, bytes or backlog)
};
inline constexpr std::size_t kDropReasonCount = 4;
const char* to_string(DropReason reason);

struct DropCounters {
  std::array<common::Counter*, kDropReasonCount> counters{};
  common::Counter& operator[](std::size_t reason) const { return *counters[reason]; }
};

struct DirectionStats {
  DirectionStats(common::CounterSet& set, const std::string& direction);
  common::Counter& received;   // everything that arrived on the TX channel
  common::Counter& delivered;  // published on the RX channel
  common::Counter& lost;       // lost by the loss model
  DropCounters dropped;
  common::Counter& bytes_delivered;  // charged sizes
  common::Counter& pending;          // waiting for their delivery time now
  common::Counter& max_pending;
  uint64_t dropped_total() const;
};

struct LinkStats {
  explicit LinkStats(common::CounterSet& set);
  DirectionStats up, down;
  common::Counter& slice_switch_requests;
  common::Counter& edge_requests;
  common::Counter& net_published;
  common::Counter& records;
};

// "up: 120 in, 118 delivered, 2 lost, 0 dropped; down: ..." for logs.
std::string summary(const LinkStats& stats);

}  // namespace a3::linkemu
