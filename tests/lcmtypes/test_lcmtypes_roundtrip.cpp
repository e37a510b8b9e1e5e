// Every LCM message type in lcmtypes/ survives encode/decode with non-default values in
// every field, rejects truncated and foreign bytes, and has a case here: adding a .lcm
// file without a round-trip case below makes EveryLcmFileHasARoundTripCase fail.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
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
#include "a3lcm/safety_event_t.hpp"
#include "a3lcm/node_stats_t.hpp"
#include "a3lcm/sim_clock_t.hpp"
#include "a3lcm/slice_switch_reply_t.hpp"
#include "a3lcm/slice_switch_request_t.hpp"
#include "a3lcm/payload_event_t.hpp"
#include "a3lcm/traffic_state_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "tests/test_support.hpp"

namespace {

constexpr int64_t kBigTime = int64_t{1} << 40;  // does not fit in 32 bits

// Bit-exact comparison: NaN survives as NaN, -0.0 stays -0.0.
uint64_t bits(double x) {
  uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}
#define EXPECT_SAME_DOUBLE(a, b) EXPECT_EQ(bits(a), bits(b)) << #a " = " << (a) << ", " #b " = " << (b)

template <std::size_t N>
void expect_same_array(const double (&a)[N], const double (&b)[N], const char* name) {
  for (std::size_t i = 0; i < N; ++i) {
    EXPECT_EQ(bits(a[i]), bits(b[i])) << name << "[" << i << "]: " << a[i] << " vs " << b[i];
  }
}

// Distinct, non-round values so a swapped or dropped element shows.
template <std::size_t N>
void fill(double (&a)[N], double base) {
  for (std::size_t i = 0; i < N; ++i) a[i] = base + 0.125 * static_cast<double>(i + 1) + 1.0 / 3.0;
}

std::string long_json(std::size_t n) {
  std::string s = "{\"intent\":\"α³ \\\"quoted\\\" tab\\t\",\"pad\":\"";
  while (s.size() < n) s += "0123456789abcdef";
  return s + "\"}";
}

// One specialisation per message type: a message with every field set to a non-default
// value, and the field-by-field comparison.
template <typename Msg>
struct Case;

template <>
struct Case<a3lcm::actuator_cmd_t> {
  static a3lcm::actuator_cmd_t make() {
    a3lcm::actuator_cmd_t m;
    m.utime_us = kBigTime + 11;
    m.throttle[0] = 0.0625;
    m.throttle[1] = 0.25;
    m.throttle[2] = 0.75;
    m.throttle[3] = 1.0;
    m.armed = true;
    return m;
  }
  static void expect_equal(const a3lcm::actuator_cmd_t& a, const a3lcm::actuator_cmd_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    expect_same_array(a.throttle, b.throttle, "throttle");
    EXPECT_EQ(a.armed, b.armed);
  }
};

template <>
struct Case<a3lcm::episode_event_t> {
  static a3lcm::episode_event_t make() {
    a3lcm::episode_event_t m;
    m.utime_us = -kBigTime;  // negative survives sign extension
    m.turn = 17;
    m.speaker = "agent";
    m.kind = "turn_end";
    m.status = "interrupted";
    m.detail_json = long_json(5000);  // length needs more than one byte
    return m;
  }
  static void expect_equal(const a3lcm::episode_event_t& a, const a3lcm::episode_event_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.turn, b.turn);
    EXPECT_EQ(a.speaker, b.speaker);
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.detail_json, b.detail_json);
  }
};

template <>
struct Case<a3lcm::fc_command_t> {
  static a3lcm::fc_command_t make() {
    a3lcm::fc_command_t m;
    m.utime_us = kBigTime + 3;
    m.seq = std::numeric_limits<int32_t>::max();
    m.command = a3lcm::fc_command_t::SET_SPEED;
    fill(m.target_W_m, -120.0);
    m.speed_limit_mps = 7.5;
    m.yaw_deg = std::numeric_limits<double>::quiet_NaN();  // "NaN: keep" must survive
    return m;
  }
  static void expect_equal(const a3lcm::fc_command_t& a, const a3lcm::fc_command_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.seq, b.seq);
    EXPECT_EQ(a.command, b.command);
    expect_same_array(a.target_W_m, b.target_W_m, "target_W_m");
    EXPECT_SAME_DOUBLE(a.speed_limit_mps, b.speed_limit_mps);
    EXPECT_SAME_DOUBLE(a.yaw_deg, b.yaw_deg);
    EXPECT_TRUE(std::isnan(b.yaw_deg));
  }
};

template <>
struct Case<a3lcm::fc_status_t> {
  static a3lcm::fc_status_t make() {
    a3lcm::fc_status_t m;
    m.utime_us = kBigTime + 5;
    m.mode = a3lcm::fc_status_t::RETURN_HOME;
    m.armed = true;
    m.failsafe = a3lcm::fc_status_t::FAILSAFE_GEOFENCE;
    fill(m.p_W_m, 10.0);
    fill(m.v_W_mps, -2.0);
    m.yaw_deg = -179.5;
    m.battery_pct = 42.25;
    m.last_command_seq = -7;
    m.last_command_accepted = true;
    m.last_command_reason = "outside geofence: 812 m > 500 m";
    return m;
  }
  static void expect_equal(const a3lcm::fc_status_t& a, const a3lcm::fc_status_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.mode, b.mode);
    EXPECT_EQ(a.armed, b.armed);
    EXPECT_EQ(a.failsafe, b.failsafe);
    expect_same_array(a.p_W_m, b.p_W_m, "p_W_m");
    expect_same_array(a.v_W_mps, b.v_W_mps, "v_W_mps");
    EXPECT_SAME_DOUBLE(a.yaw_deg, b.yaw_deg);
    EXPECT_SAME_DOUBLE(a.battery_pct, b.battery_pct);
    EXPECT_EQ(a.last_command_seq, b.last_command_seq);
    EXPECT_EQ(a.last_command_accepted, b.last_command_accepted);
    EXPECT_EQ(a.last_command_reason, b.last_command_reason);
  }
};

template <>
struct Case<a3lcm::link_message_t> {
  static a3lcm::link_message_t make() {
    a3lcm::link_message_t m;
    m.utime_us = kBigTime + 1000;
    m.sent_utime_us = kBigTime;
    m.message_id = std::numeric_limits<int64_t>::max();
    m.sender = "tool_server";
    m.kind = "observation";
    m.slice = "URLLC";
    m.payload_size_bytes = 1 << 20;
    // Every byte value, including 0x00 and 0xFF, more than 256 of them.
    for (int i = 0; i < 300; ++i) m.payload.push_back(static_cast<uint8_t>((i * 7 + 3) % 256));
    m.payload[0] = 0x00;
    m.payload[1] = 0xFF;
    m.payload_length = static_cast<int32_t>(m.payload.size());
    return m;
  }
  static void expect_equal(const a3lcm::link_message_t& a, const a3lcm::link_message_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.sent_utime_us, b.sent_utime_us);
    EXPECT_EQ(a.message_id, b.message_id);
    EXPECT_EQ(a.sender, b.sender);
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.slice, b.slice);
    EXPECT_EQ(a.payload_size_bytes, b.payload_size_bytes);
    EXPECT_EQ(a.payload_length, b.payload_length);
    EXPECT_EQ(a.payload, b.payload);
  }
};

template <>
struct Case<a3lcm::network_state_t> {
  static a3lcm::network_state_t make() {
    a3lcm::network_state_t m;
    m.utime_us = kBigTime + 9;
    m.slice = "mMTC";
    m.lat_ms = 87.5;
    m.jitter_ms = 12.25;
    m.loss_pct = 3.5;
    m.throughput_mbps = 0.875;
    m.edge_load = 0.625;
    m.degraded = true;
    m.pending_slice = "URLLC";
    return m;
  }
  static void expect_equal(const a3lcm::network_state_t& a, const a3lcm::network_state_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.slice, b.slice);
    EXPECT_SAME_DOUBLE(a.lat_ms, b.lat_ms);
    EXPECT_SAME_DOUBLE(a.jitter_ms, b.jitter_ms);
    EXPECT_SAME_DOUBLE(a.loss_pct, b.loss_pct);
    EXPECT_SAME_DOUBLE(a.throughput_mbps, b.throughput_mbps);
    EXPECT_SAME_DOUBLE(a.edge_load, b.edge_load);
    EXPECT_EQ(a.degraded, b.degraded);
    EXPECT_EQ(a.pending_slice, b.pending_slice);
  }
};

template <>
struct Case<a3lcm::safety_event_t> {
  static a3lcm::safety_event_t make() {
    a3lcm::safety_event_t m;
    m.utime_us = kBigTime + 13;
    m.kind = "separation_breach";
    m.source = "dynamics";
    fill(m.p_W_m, 250.0);
    m.value = 1.0 / 7.0;
    m.detail = "peer uav-2 at 3.1 m (limit 5 m)";
    return m;
  }
  static void expect_equal(const a3lcm::safety_event_t& a, const a3lcm::safety_event_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.source, b.source);
    expect_same_array(a.p_W_m, b.p_W_m, "p_W_m");
    EXPECT_SAME_DOUBLE(a.value, b.value);
    EXPECT_EQ(a.detail, b.detail);
  }
};

template <>
struct Case<a3lcm::node_stats_t> {
  static a3lcm::node_stats_t make() {
    a3lcm::node_stats_t m;
    m.utime_us = kBigTime + 5;
    m.wall_utime_us = kBigTime * 2 + 9;
    m.node = "linkemu";
    m.pid = 4242;
    m.is_final = true;
    m.counter_names = {"up.delivered", "records"};
    m.counter_values = {kBigTime, 3};
    m.n_counters = 2;
    m.timing_names = {"lateness_p99_us"};
    m.timing_values = {12.25};
    m.n_timings = 1;
    return m;
  }
  static void expect_equal(const a3lcm::node_stats_t& a, const a3lcm::node_stats_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.wall_utime_us, b.wall_utime_us);
    EXPECT_EQ(a.node, b.node);
    EXPECT_EQ(a.pid, b.pid);
    EXPECT_EQ(a.is_final, b.is_final);
    EXPECT_EQ(a.counter_names, b.counter_names);
    EXPECT_EQ(a.counter_values, b.counter_values);
    EXPECT_EQ(a.timing_names, b.timing_names);
    ASSERT_EQ(a.timing_values.size(), b.timing_values.size());
    for (std::size_t i = 0; i < a.timing_values.size(); ++i) EXPECT_SAME_DOUBLE(a.timing_values[i], b.timing_values[i]);
  }
};

template <>
struct Case<a3lcm::sim_clock_t> {
  static a3lcm::sim_clock_t make() {
    a3lcm::sim_clock_t m;
    m.utime_us = kBigTime + 17;
    m.wall_utime_us = kBigTime * 3 + 1;
    m.real_time_factor = 10.0;
    m.achieved_real_time_factor = 9.8765;
    m.round = 3;
    return m;
  }
  static void expect_equal(const a3lcm::sim_clock_t& a, const a3lcm::sim_clock_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.wall_utime_us, b.wall_utime_us);
    EXPECT_SAME_DOUBLE(a.real_time_factor, b.real_time_factor);
    EXPECT_SAME_DOUBLE(a.achieved_real_time_factor, b.achieved_real_time_factor);
    EXPECT_EQ(a.round, b.round);
  }
};

template <>
struct Case<a3lcm::clock_ack_t> {
  static a3lcm::clock_ack_t make() {
    a3lcm::clock_ack_t m;
    m.utime_us = kBigTime + 23;
    m.round = 2;
    m.messages_published = kBigTime / 7 + 5;
    m.node = "tool_server";
    return m;
  }
  static void expect_equal(const a3lcm::clock_ack_t& a, const a3lcm::clock_ack_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.round, b.round);
    EXPECT_EQ(a.messages_published, b.messages_published);
    EXPECT_EQ(a.node, b.node);
  }
};

template <>
struct Case<a3lcm::vehicle_state_t> {
  static a3lcm::vehicle_state_t make() {
    a3lcm::vehicle_state_t m;
    m.utime_us = kBigTime + 19;
    fill(m.p_W_m, 100.0);
    fill(m.v_W_mps, -4.0);
    fill(m.q_WB, 0.5);
    fill(m.w_B_radps, -0.25);
    fill(m.a_B_mps2, 9.0);
    fill(m.rotor_speed_radps, 800.0);
    m.battery_pct = 87.5;
    m.battery_voltage_v = 15.2;
    m.power_w = 312.75;
    m.mass_kg = 1.625;
    fill(m.wind_W_mps, 3.0);
    m.on_ground = true;
    m.crashed = true;
    return m;
  }
  static void expect_equal(const a3lcm::vehicle_state_t& a, const a3lcm::vehicle_state_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    expect_same_array(a.p_W_m, b.p_W_m, "p_W_m");
    expect_same_array(a.v_W_mps, b.v_W_mps, "v_W_mps");
    expect_same_array(a.q_WB, b.q_WB, "q_WB");
    expect_same_array(a.w_B_radps, b.w_B_radps, "w_B_radps");
    expect_same_array(a.a_B_mps2, b.a_B_mps2, "a_B_mps2");
    expect_same_array(a.rotor_speed_radps, b.rotor_speed_radps, "rotor_speed_radps");
    EXPECT_SAME_DOUBLE(a.battery_pct, b.battery_pct);
    EXPECT_SAME_DOUBLE(a.battery_voltage_v, b.battery_voltage_v);
    EXPECT_SAME_DOUBLE(a.power_w, b.power_w);
    EXPECT_SAME_DOUBLE(a.mass_kg, b.mass_kg);
    expect_same_array(a.wind_W_mps, b.wind_W_mps, "wind_W_mps");
    EXPECT_EQ(a.on_ground, b.on_ground);
    EXPECT_EQ(a.crashed, b.crashed);
  }
};

template <>
struct Case<a3lcm::link_record_t> {
  static a3lcm::link_record_t make() {
    a3lcm::link_record_t m;
    m.utime_us = kBigTime + 21;
    m.direction = "down";
    m.message_id = -(kBigTime + 2);
    m.sender = "tool_server";
    m.kind = "image";
    m.sent_utime_us = kBigTime + 20;
    m.size_bytes = int64_t{5} << 32;  // does not fit in 32 bits
    m.outcome = a3lcm::link_record_t::DROPPED;
    m.drop_reason = "queue_full: backlog 61.2 s > 60 s";
    m.delivery_utime_us = -1;
    m.queue_ms = 1234.5;
    m.serialization_ms = 17391.304;
    m.latency_ms = 1.0 / 3.0;
    m.slice = "mMTC";
    m.net_lat_ms = 150.125;
    m.net_jitter_ms = 17.5;
    m.net_loss_pct = 2.375;
    m.net_throughput_mbps = 2.3;
    m.net_edge_load = 0.875;
    m.net_degraded = true;
    return m;
  }
  static void expect_equal(const a3lcm::link_record_t& a, const a3lcm::link_record_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.direction, b.direction);
    EXPECT_EQ(a.message_id, b.message_id);
    EXPECT_EQ(a.sender, b.sender);
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.sent_utime_us, b.sent_utime_us);
    EXPECT_EQ(a.size_bytes, b.size_bytes);
    EXPECT_EQ(a.outcome, b.outcome);
    EXPECT_EQ(a.drop_reason, b.drop_reason);
    EXPECT_EQ(a.delivery_utime_us, b.delivery_utime_us);
    EXPECT_SAME_DOUBLE(a.queue_ms, b.queue_ms);
    EXPECT_SAME_DOUBLE(a.serialization_ms, b.serialization_ms);
    EXPECT_SAME_DOUBLE(a.latency_ms, b.latency_ms);
    EXPECT_EQ(a.slice, b.slice);
    EXPECT_SAME_DOUBLE(a.net_lat_ms, b.net_lat_ms);
    EXPECT_SAME_DOUBLE(a.net_jitter_ms, b.net_jitter_ms);
    EXPECT_SAME_DOUBLE(a.net_loss_pct, b.net_loss_pct);
    EXPECT_SAME_DOUBLE(a.net_throughput_mbps, b.net_throughput_mbps);
    EXPECT_SAME_DOUBLE(a.net_edge_load, b.net_edge_load);
    EXPECT_EQ(a.net_degraded, b.net_degraded);
  }
};

template <>
struct Case<a3lcm::edge_compute_request_t> {
  static a3lcm::edge_compute_request_t make() {
    a3lcm::edge_compute_request_t m;
    m.utime_us = kBigTime + 23;
    m.request_id = kBigTime * 5 + 1;
    m.requester = "agent";
    m.work_ms = 7400.125;
    return m;
  }
  static void expect_equal(const a3lcm::edge_compute_request_t& a,
                           const a3lcm::edge_compute_request_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.request_id, b.request_id);
    EXPECT_EQ(a.requester, b.requester);
    EXPECT_SAME_DOUBLE(a.work_ms, b.work_ms);
  }
};

template <>
struct Case<a3lcm::edge_compute_reply_t> {
  static a3lcm::edge_compute_reply_t make() {
    a3lcm::edge_compute_reply_t m;
    m.utime_us = kBigTime + 25;
    m.request_id = kBigTime * 5 + 1;
    m.requester = "agent";
    m.work_ms = 7400.125;
    m.delay_ms = 37000.625;
    m.edge_load = 0.8;
    m.slice = "eMBB";
    m.error = "work_ms must be a finite number >= 0, got -1";
    return m;
  }
  static void expect_equal(const a3lcm::edge_compute_reply_t& a,
                           const a3lcm::edge_compute_reply_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.request_id, b.request_id);
    EXPECT_EQ(a.requester, b.requester);
    EXPECT_SAME_DOUBLE(a.work_ms, b.work_ms);
    EXPECT_SAME_DOUBLE(a.delay_ms, b.delay_ms);
    EXPECT_SAME_DOUBLE(a.edge_load, b.edge_load);
    EXPECT_EQ(a.slice, b.slice);
    EXPECT_EQ(a.error, b.error);
  }
};

template <>
struct Case<a3lcm::slice_switch_request_t> {
  static a3lcm::slice_switch_request_t make() {
    a3lcm::slice_switch_request_t m;
    m.utime_us = kBigTime + 27;
    m.request_id = -3;
    m.requester = "tool_server";
    m.slice = "URLLC";
    return m;
  }
  static void expect_equal(const a3lcm::slice_switch_request_t& a,
                           const a3lcm::slice_switch_request_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.request_id, b.request_id);
    EXPECT_EQ(a.requester, b.requester);
    EXPECT_EQ(a.slice, b.slice);
  }
};

template <>
struct Case<a3lcm::slice_switch_reply_t> {
  static a3lcm::slice_switch_reply_t make() {
    a3lcm::slice_switch_reply_t m;
    m.utime_us = kBigTime + 29;
    m.request_id = -3;
    m.requester = "tool_server";
    m.accepted = true;
    m.reason = "superseded a pending switch to mMTC";
    m.from_slice = "eMBB";
    m.to_slice = "URLLC";
    m.effective_utime_us = kBigTime + 100029;
    return m;
  }
  static void expect_equal(const a3lcm::slice_switch_reply_t& a,
                           const a3lcm::slice_switch_reply_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.request_id, b.request_id);
    EXPECT_EQ(a.requester, b.requester);
    EXPECT_EQ(a.accepted, b.accepted);
    EXPECT_EQ(a.reason, b.reason);
    EXPECT_EQ(a.from_slice, b.from_slice);
    EXPECT_EQ(a.to_slice, b.to_slice);
    EXPECT_EQ(a.effective_utime_us, b.effective_utime_us);
  }
};

template <>
struct Case<a3lcm::payload_event_t> {
  static a3lcm::payload_event_t make() {
    a3lcm::payload_event_t m;
    m.utime_us = kBigTime + 23;
    m.kind = "capture";
    m.sensor = "thermal";
    m.item_id = "img-000042";
    fill(m.p_W_m, -12.5);
    m.yaw_deg = 271.5;
    m.size_bytes = (int64_t{1} << 33) + 5;
    m.downlinked = true;
    return m;
  }
  static void expect_equal(const a3lcm::payload_event_t& a, const a3lcm::payload_event_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.sensor, b.sensor);
    EXPECT_EQ(a.item_id, b.item_id);
    expect_same_array(a.p_W_m, b.p_W_m, "p_W_m");
    EXPECT_SAME_DOUBLE(a.yaw_deg, b.yaw_deg);
    EXPECT_EQ(a.size_bytes, b.size_bytes);
    EXPECT_EQ(a.downlinked, b.downlinked);
  }
};

template <>
struct Case<a3lcm::traffic_state_t> {
  static a3lcm::traffic_state_t make() {
    a3lcm::traffic_state_t m;
    m.utime_us = kBigTime + 29;
    m.id = "peer-7";
    fill(m.p_W_m, 350.25);
    fill(m.v_W_mps, -6.5);
    m.status = "yielding";
    return m;
  }
  static void expect_equal(const a3lcm::traffic_state_t& a, const a3lcm::traffic_state_t& b) {
    EXPECT_EQ(a.utime_us, b.utime_us);
    EXPECT_EQ(a.id, b.id);
    expect_same_array(a.p_W_m, b.p_W_m, "p_W_m");
    expect_same_array(a.v_W_mps, b.v_W_mps, "v_W_mps");
    EXPECT_EQ(a.status, b.status);
  }
};

// The types with a round-trip case: add a new type here and a Case<> above.
using AllTypesTuple =
    std::tuple<a3lcm::actuator_cmd_t, a3lcm::clock_ack_t, a3lcm::edge_compute_reply_t, a3lcm::edge_compute_request_t,
               a3lcm::episode_event_t, a3lcm::fc_command_t, a3lcm::fc_status_t,
               a3lcm::link_message_t, a3lcm::link_record_t, a3lcm::network_state_t, a3lcm::node_stats_t,
               a3lcm::payload_event_t, a3lcm::safety_event_t, a3lcm::sim_clock_t,
               a3lcm::slice_switch_reply_t, a3lcm::slice_switch_request_t,
               a3lcm::traffic_state_t, a3lcm::vehicle_state_t>;

template <typename Tuple>
struct GtestTypes;
template <typename... T>
struct GtestTypes<std::tuple<T...>> {
  using type = ::testing::Types<T...>;
};
using AllTypes = GtestTypes<AllTypesTuple>::type;

template <typename Tuple>
std::set<std::string> tested_type_names() {
  std::set<std::string> names;
  std::apply([&](const auto&... m) { (names.insert(std::decay_t<decltype(m)>::getTypeName()), ...); },
             Tuple{});
  return names;
}

template <typename Msg>
std::vector<uint8_t> encode(const Msg& msg) {
  const int size = msg.getEncodedSize();
  std::vector<uint8_t> buffer(static_cast<std::size_t>(size));
  EXPECT_EQ(msg.encode(buffer.data(), 0, size), size);
  return buffer;
}

template <typename T>
class LcmRoundTrip : public ::testing::Test {};

class TypeNames {
 public:
  template <typename T>
  static std::string GetName(int) {
    return T::getTypeName();
  }
};

TYPED_TEST_SUITE(LcmRoundTrip, AllTypes, TypeNames);

TYPED_TEST(LcmRoundTrip, EveryFieldSurvivesEncodeDecode) {
  using Msg = TypeParam;
  const Msg original = Case<Msg>::make();
  const std::vector<uint8_t> bytes = encode(original);
  const int size = static_cast<int>(bytes.size());

  Msg decoded;
  ASSERT_EQ(decoded.decode(bytes.data(), 0, size), size);
  Case<Msg>::expect_equal(original, decoded);
  // Re-encoding gives the same bytes: nothing was lost that the comparison above missed.
  EXPECT_EQ(encode(decoded), bytes);

  // A message is not the default one: the case really sets non-default values.
  EXPECT_NE(encode(Msg{}), bytes);
}

TYPED_TEST(LcmRoundTrip, EncodesAndDecodesAtAnOffsetInsideALargerBuffer) {
  using Msg = TypeParam;
  const Msg original = Case<Msg>::make();
  const int size = original.getEncodedSize();
  std::vector<uint8_t> framed(static_cast<std::size_t>(5 + size + 7), 0xAB);
  ASSERT_EQ(original.encode(framed.data(), 5, size), size);
  EXPECT_EQ(framed[4], 0xAB);  // nothing written before the offset
  EXPECT_EQ(framed[static_cast<std::size_t>(5 + size)], 0xAB);  // nor after the message
  Msg decoded;
  ASSERT_EQ(decoded.decode(framed.data(), 5, size), size);
  Case<Msg>::expect_equal(original, decoded);
}

TYPED_TEST(LcmRoundTrip, EveryTruncationFailsToDecode) {
  using Msg = TypeParam;
  const std::vector<uint8_t> bytes = encode(Case<Msg>::make());
  for (std::size_t len = 0; len < bytes.size(); ++len) {
    // Copy into an exact-size buffer so a decoder that reads past maxlen trips sanitizers.
    const std::vector<uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<long>(len));
    Msg decoded;
    EXPECT_LT(decoded.decode(cut.data(), 0, static_cast<int>(len)), 0)
        << Msg::getTypeName() << " decoded from " << len << " of " << bytes.size() << " bytes";
  }
}

TYPED_TEST(LcmRoundTrip, CorruptFingerprintFailsToDecode) {
  using Msg = TypeParam;
  std::vector<uint8_t> bytes = encode(Case<Msg>::make());
  bytes[3] ^= 0x01;
  Msg decoded;
  EXPECT_LT(decoded.decode(bytes.data(), 0, static_cast<int>(bytes.size())), 0);
}

TYPED_TEST(LcmRoundTrip, DoesNotDecodeAsAnyOtherType) {
  using Msg = TypeParam;
  const std::vector<uint8_t> bytes = encode(Case<Msg>::make());
  std::apply(
      [&](auto... other) {
        (
            [&] {
              using Other = decltype(other);
              if constexpr (!std::is_same_v<Other, Msg>) {
                Other decoded;
                EXPECT_LT(decoded.decode(bytes.data(), 0, static_cast<int>(bytes.size())), 0)
                    << Msg::getTypeName() << " bytes decoded as " << Other::getTypeName();
              }
            }(),
            ...);
      },
      AllTypesTuple{});
}

TEST(LcmRoundTripEdges, EmptyStringsAndEmptyPayloadRoundTrip) {
  a3lcm::link_message_t m = Case<a3lcm::link_message_t>::make();
  m.sender.clear();
  m.kind.clear();
  m.slice.clear();
  m.payload.clear();
  m.payload_length = 0;
  const std::vector<uint8_t> bytes = encode(m);
  a3lcm::link_message_t decoded = Case<a3lcm::link_message_t>::make();  // pre-filled
  ASSERT_EQ(decoded.decode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  EXPECT_EQ(decoded.sender, "");
  EXPECT_EQ(decoded.slice, "");
  EXPECT_EQ(decoded.payload_length, 0);
  EXPECT_EQ(decoded.message_id, m.message_id);
}

std::set<std::string> split_csv(const std::string& csv) {
  std::set<std::string> out;
  std::stringstream in(csv);
  for (std::string item; std::getline(in, item, ',');) {
    if (!item.empty()) out.insert(item);
  }
  return out;
}

std::string join(const std::set<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

TEST(LcmTypes, EveryLcmFileHasARoundTripCase) {
  const std::filesystem::path dir = a3::test::source_dir() / "lcmtypes";
  std::set<std::string> on_disk;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() == ".lcm") on_disk.insert(entry.path().stem().string());
  }
  ASSERT_FALSE(on_disk.empty()) << "no .lcm files in " << dir;

  const std::set<std::string> tested = tested_type_names<AllTypesTuple>();
  EXPECT_EQ(tested, on_disk) << "tested: " << join(tested) << "\nin " << dir << ": "
                             << join(on_disk)
                             << "\nadd a Case<> and the type to AllTypes in " << __FILE__;
  // No type listed twice.
  EXPECT_EQ(static_cast<std::size_t>(std::tuple_size_v<AllTypesTuple>), tested.size());

  // What CMake configured (A3_LCM_TYPE_NAMES) agrees with the source tree.
  EXPECT_EQ(split_csv(A3_LCM_TYPE_NAMES_CSV), on_disk)
      << "A3_LCM_TYPE_NAMES is stale; re-run cmake";
}

}  // namespace
