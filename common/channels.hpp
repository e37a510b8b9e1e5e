// LCM channel names: the one list of who says what on the bus.
#pragma once

namespace a3::common::channels {

inline constexpr const char* kState = "A3_STATE";            // vehicle_state_t, dynamics
inline constexpr const char* kActuators = "A3_ACTUATORS";    // actuator_cmd_t, bridge (from ESC frames)
inline constexpr const char* kFcCommand = "A3_FC_CMD";       // fc_command_t, tool server
inline constexpr const char* kFcStatus = "A3_FC_STATUS";     // fc_status_t, bridge (from CAN)
inline constexpr const char* kNet = "A3_NET";                // network_state_t, link emulator
inline constexpr const char* kLinkUpTx = "A3_LINK_UP_TX";    // link_message_t, ground -> link
inline constexpr const char* kLinkUpRx = "A3_LINK_UP_RX";    // link_message_t, link -> vehicle
inline constexpr const char* kLinkDownTx = "A3_LINK_DOWN_TX";  // link_message_t, vehicle -> link
inline constexpr const char* kLinkDownRx = "A3_LINK_DOWN_RX";  // link_message_t, link -> ground
inline constexpr const char* kLinkRecord = "A3_LINK_RECORD";  // link_record_t, link emulator
inline constexpr const char* kEdgeRequest = "A3_EDGE_REQ";   // edge_compute_request_t, agent side
inline constexpr const char* kEdgeReply = "A3_EDGE_REPLY";   // edge_compute_reply_t, link emulator
inline constexpr const char* kSliceRequest = "A3_SLICE_REQ";  // slice_switch_request_t, tool server
inline constexpr const char* kSliceReply = "A3_SLICE_REPLY";  // slice_switch_reply_t, link emulator
inline constexpr const char* kPayload = "A3_PAYLOAD";        // payload_event_t, tool server
inline constexpr const char* kTraffic = "A3_TRAFFIC";        // traffic_state_t, tool server (swarm peers)
inline constexpr const char* kEpisode = "A3_EPISODE";        // episode_event_t, orchestrator
inline constexpr const char* kSafety = "A3_SAFETY";          // safety_event_t, any node
inline constexpr const char* kClock = "A3_CLOCK";            // sim_clock_t, lockstep pacer (grants)
inline constexpr const char* kClockAck = "A3_CLOCK_ACK";     // clock_ack_t, lockstep followers (answers)
inline constexpr const char* kNodeStats = "A3_NODE_STATS";   // node_stats_t, runtime (every node)

}  // namespace a3::common::channels
