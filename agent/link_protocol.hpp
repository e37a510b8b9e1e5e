// What crosses the emulated link between the agent (ground side) and the tool server (vehicle
// side), as the JSON payload of link_message_t:
//   uplink   kind "mcp_call" | "a2a_message":  {"turn": T, "action_index": i, "action": {...}}
//   downlink kind "observation" | "image":     {"turn": T, "action_index": i, "obs": {...}}
// The action and observation objects are exactly the α³-Bench episode's (SPEC §1). An image's
// bytes are charged to the downlink through payload_size_bytes (the JSON carries only a
// reference), so a large capture really takes its time on a slow slice.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "a3lcm/link_message_t.hpp"

namespace a3::agent {

struct ActionEnvelope {
  int turn = 0;
  int action_index = 0;
  nlohmann::json action;  // {"type": "mcp", "name", "args"} | {"type": "a2a", "task", "to", "payload"}
};

struct ObservationEnvelope {
  int turn = 0;
  int action_index = 0;
  nlohmann::json obs;  // {"tool", "result"} | {"task", "from", "status", "payload"}
};

// Upper bound on a link message's JSON text; larger messages are refused as malformed.
inline constexpr std::size_t kMaxLinkJsonBytes = 256 * 1024;

a3lcm::link_message_t encode_action(const ActionEnvelope& a, int64_t message_id, int64_t utime_us,
                                    const std::string& sender);
// extra_bytes: bytes charged to the link beyond the JSON (an image's data).
a3lcm::link_message_t encode_observation(const ObservationEnvelope& o, int64_t message_id, int64_t utime_us,
                                         const std::string& sender, int64_t extra_bytes = 0);

// Nothing (and the reason in *error) when the message is not a well-formed envelope.
std::optional<ActionEnvelope> decode_action(const a3lcm::link_message_t& m, std::string* error);
std::optional<ObservationEnvelope> decode_observation(const a3lcm::link_message_t& m, std::string* error);

}  // namespace a3::agent
