// Counters of the link emulator, per direction: messages in, delivered, lost, and dropped
// for each bad-input reason.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace a3::linkemu {

enum class DropReason : uint8_t {
  kUndecodable = 0,   // not a link_message_t
  kBadSize = 1,       // payload_size_bytes negative, or below the payload it carries
  kOversized = 2,     // charged size above max_message_bytes
  kQueueFull = 3,     // the direction's buffer is full (messages, bytes or backlog)
};
inline constexpr std::size_t kDropReasonCount = 4;
const char* to_string(DropReason reason);

struct DirectionStats {
  uint64_t received = 0;   // everything that arrived on the TX channel
  uint64_t delivered = 0;  // published on the RX channel
  uint64_t lost = 0;       // lost by the loss model
  std::array<uint64_t, kDropReasonCount> dropped{};
  uint64_t bytes_delivered = 0;  // charged sizes
  uint64_t pending = 0;          // waiting for their delivery time now
  uint64_t max_pending = 0;
  uint64_t dropped_total() const;
};

struct LinkStats {
  DirectionStats up, down;
  uint64_t slice_switch_requests = 0;
  uint64_t edge_requests = 0;
  uint64_t net_published = 0;
  uint64_t records = 0;
};

// "up: 120 in, 118 delivered, 2 lost, 0 dropped; down: ..." for logs.
std::string summary(const LinkStats& stats);

}  // namespace a3::linkemu
