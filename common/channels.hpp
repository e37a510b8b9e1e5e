// The bus's channels, each declared once with its message type and scope (channel.hpp): the one
// list of who says what on the bus. Vehicle channels are per vehicle (`kState.of(vehicle)`);
// `a3rig topology` prints which node publishes and which subscribes each.
#pragma once

#include <string>
#include <vector>

#include "a3lcm/actuator_cmd_t.hpp"
#include "a3lcm/clock_ack_t.hpp"
#include "a3lcm/edge_compute_reply_t.hpp"
#include "a3lcm/edge_compute_request_t.hpp"
#include "a3lcm/episode_event_t.hpp"
#include "a3lcm/fc_command_t.hpp"
#include "a3lcm/fc_status_t.hpp"
#include "a3lcm/link_message_t.hpp"
#include "a3lcm/link_record_t.hpp"
#include "a3lcm/network_state_t.hpp"
#include "a3lcm/node_stats_t.hpp"
#include "a3lcm/payload_event_t.hpp"
#include "a3lcm/safety_event_t.hpp"
#include "a3lcm/sim_clock_t.hpp"
#include "a3lcm/slice_switch_reply_t.hpp"
#include "a3lcm/slice_switch_request_t.hpp"
#include "a3lcm/traffic_state_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "common/channel.hpp"

// X(constant, message type, vehicle 0's name): one vehicle's physics, flight controller, link
// and tools. The comment says who publishes.
#define A3_VEHICLE_CHANNELS(X)                                                               \
  X(kState, vehicle_state_t, "A3_STATE")                      /* dynamics: the true state */ \
  X(kActuators, actuator_cmd_t, "A3_ACTUATORS")               /* bridge, from ESC frames */  \
  X(kFcCommand, fc_command_t, "A3_FC_CMD")                    /* tool server */              \
  X(kFcStatus, fc_status_t, "A3_FC_STATUS")                   /* bridge, from CAN */         \
  X(kNet, network_state_t, "A3_NET")                          /* link emulator */            \
  X(kLinkUpTx, link_message_t, "A3_LINK_UP_TX")               /* ground -> link */           \
  X(kLinkUpRx, link_message_t, "A3_LINK_UP_RX")               /* link -> vehicle */          \
  X(kLinkDownTx, link_message_t, "A3_LINK_DOWN_TX")           /* vehicle -> link */          \
  X(kLinkDownRx, link_message_t, "A3_LINK_DOWN_RX")           /* link -> ground */           \
  X(kLinkRecord, link_record_t, "A3_LINK_RECORD")             /* link emulator */            \
  X(kEdgeRequest, edge_compute_request_t, "A3_EDGE_REQ")      /* an edge-compute client */   \
  X(kEdgeReply, edge_compute_reply_t, "A3_EDGE_REPLY")        /* link emulator */            \
  X(kSliceRequest, slice_switch_request_t, "A3_SLICE_REQ")    /* tool server */              \
  X(kSliceReply, slice_switch_reply_t, "A3_SLICE_REPLY")      /* link emulator */            \
  X(kPayload, payload_event_t, "A3_PAYLOAD")                  /* tool server */              \
  X(kSafety, safety_event_t, "A3_SAFETY")                     /* any of its nodes */

// X(constant, message type, name): the whole rig's shared airspace, episode, time and statistics.
#define A3_RIG_CHANNELS(X)                                                           \
  X(kTraffic, traffic_state_t, "A3_TRAFFIC")       /* tool servers (swarm peers) */ \
  X(kEpisode, episode_event_t, "A3_EPISODE")       /* the conversation */           \
  X(kClock, sim_clock_t, "A3_CLOCK")               /* lockstep pacer (grants) */    \
  X(kClockAck, clock_ack_t, "A3_CLOCK_ACK")        /* lockstep followers */         \
  X(kNodeStats, node_stats_t, "A3_NODE_STATS")     /* runtime (every node) */

namespace a3::common::channels {

#define A3_DECLARE_VEHICLE_CHANNEL(constant, type, text) inline constexpr VehicleChannel<a3lcm::type> constant{text};
#define A3_DECLARE_RIG_CHANNEL(constant, type, text) inline constexpr RigChannel<a3lcm::type> constant{text};
A3_VEHICLE_CHANNELS(A3_DECLARE_VEHICLE_CHANNEL)
A3_RIG_CHANNELS(A3_DECLARE_RIG_CHANNEL)
#undef A3_DECLARE_VEHICLE_CHANNEL
#undef A3_DECLARE_RIG_CHANNEL

struct DeclaredChannel {
  std::string name;          // on the bus, for the vehicle asked
  std::string message_type;  // "a3lcm.vehicle_state_t"
  bool per_vehicle = false;
};

// Every channel above: the vehicle channels of `vehicle`, then the rig's.
std::vector<DeclaredChannel> declared_channels(VehicleId vehicle);

}  // namespace a3::common::channels
