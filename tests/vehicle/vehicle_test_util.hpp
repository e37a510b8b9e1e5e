// The tool server's test rig in virtual time: the server, the fake flight controller, and a
// probe that plays the link (sends actions on A3_LINK_UP_RX), records what the server says
// (A3_LINK_DOWN_TX, A3_PAYLOAD, A3_SAFETY, A3_TRAFFIC, A3_SLICE_REQ) and answers slice-switch
// requests as the link emulator would. Plus the test scenario's airspace and helpers.
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "a3lcm/link_message_t.hpp"
#include "a3lcm/network_state_t.hpp"
#include "a3lcm/payload_event_t.hpp"
#include "a3lcm/safety_event_t.hpp"
#include "a3lcm/slice_switch_reply_t.hpp"
#include "a3lcm/slice_switch_request_t.hpp"
#include "a3lcm/traffic_state_t.hpp"
#include "agent/link_protocol.hpp"
#include "common/channels.hpp"
#include "common/runtime.hpp"
#include "tests/vehicle/fake_flight_controller.hpp"
#include "vehicle/tool_server_node.hpp"

namespace a3::vehicle::test {

inline nlohmann::json mcp(const std::string& name, nlohmann::json args = nlohmann::json::object()) {
  return {{"type", "mcp"}, {"name", name}, {"args", std::move(args)}};
}

inline nlohmann::json a2a(const std::string& task, const std::string& to,
                          nlohmann::json payload = nlohmann::json::object()) {
  return {{"type", "a2a"}, {"task", task}, {"to", to}, {"payload", std::move(payload)}};
}

// 400 m × 300 m geofence, envelope [10, 120] m, a cylinder zone around (200, 150) r 30 m from
// the ground to 200 m and a square zone (300..340, 40..80) up to 60 m; home (20, 20).
inline Airspace test_airspace() {
  Airspace a;
  a.geofence = {{0, 0}, {400, 0}, {400, 300}, {0, 300}};
  a.min_altitude_m = 10.0;
  a.max_altitude_m = 120.0;
  NoFlyZone c;
  c.id = "nfz-c";
  c.centre = Eigen::Vector2d(200, 150);
  c.radius_m = 30.0;
  c.floor_m = 0.0;
  c.ceiling_m = 200.0;
  NoFlyZone p;
  p.id = "nfz-p";
  p.polygon = {{300, 40}, {340, 40}, {340, 80}, {300, 80}};
  p.floor_m = 0.0;
  p.ceiling_m = 60.0;
  a.no_fly_zones = {c, p};
  return a;
}

inline ToolServerConfig test_config() {
  ToolServerConfig c;
  c.airspace = test_airspace();
  c.home_W_m = Eigen::Vector3d(20, 20, 0);
  c.env = {"clear", 6.0, 240.0, std::nullopt};
  c.sensors.sensor_health = {{"rgb", "ok"}, {"thermal", "ok"}, {"lidar", "offline"}, {"gnss", "ok"}};
  c.sensors.payloads = {{"main_camera", "gimbaled_camera", "imaging_optical", 15.0},
                        {"drop_box", "parcel_release", "delivery", 0.0}};
  return c;
}

enum class SliceResponder { kAccept, kRefuse, kSilent };

struct Received {
  double t_s;
  a3lcm::link_message_t message;
  nlohmann::json obs;  // decoded observation envelope's obs
  int turn, action_index;
};

class Probe final : public common::Node {
 public:
  explicit Probe(SliceResponder responder) : responder_(responder) {}
  std::string name() const override { return "probe"; }
  void start(common::Executor& executor, common::Bus& bus) override {
    namespace ch = common::channels;
    bus.subscribe<a3lcm::link_message_t>(ch::kLinkDownTx.of(0), [this, &executor](const a3lcm::link_message_t& m, int64_t) {
      std::string error;
      auto o = agent::decode_observation(m, &error);
      ASSERT_TRUE(o.has_value()) << error;
      down.push_back({executor.clock().now_s(), m, o->obs, o->turn, o->action_index});
    });
    bus.subscribe<a3lcm::payload_event_t>(ch::kPayload.of(0),
                                          [this](const a3lcm::payload_event_t& e, int64_t) { payload.push_back(e); });
    bus.subscribe<a3lcm::safety_event_t>(ch::kSafety.of(0),
                                         [this](const a3lcm::safety_event_t& e, int64_t) { safety.push_back(e); });
    bus.subscribe<a3lcm::traffic_state_t>(ch::kTraffic,
                                          [this](const a3lcm::traffic_state_t& t, int64_t) { traffic.push_back(t); });
    bus.subscribe<a3lcm::slice_switch_request_t>(
        ch::kSliceRequest.of(0), [this, &executor, &bus](const a3lcm::slice_switch_request_t& r, int64_t) {
          slice_requests.push_back(r);
          if (responder_ == SliceResponder::kSilent) return;
          a3lcm::slice_switch_reply_t reply{};
          reply.utime_us = executor.clock().now_us();
          reply.request_id = r.request_id;
          reply.requester = r.requester;
          reply.from_slice = "eMBB";
          reply.to_slice = r.slice;
          reply.accepted = responder_ == SliceResponder::kAccept;
          reply.reason = reply.accepted ? (r.slice == "eMBB" ? "already active" : "") : "slice mMTC is not offered here";
          reply.effective_utime_us = reply.accepted ? reply.utime_us + (r.slice == "eMBB" ? 0 : 250'000) : -1;
          bus.publish(ch::kSliceReply.of(0), reply);
        });
  }
  std::vector<Received> down;
  std::vector<a3lcm::payload_event_t> payload;
  std::vector<a3lcm::safety_event_t> safety;
  std::vector<a3lcm::traffic_state_t> traffic;
  std::vector<a3lcm::slice_switch_request_t> slice_requests;

 private:
  SliceResponder responder_;
};

class Rig {
 public:
  explicit Rig(ToolServerConfig config = test_config(), FakeFcConfig fc = {},
               SliceResponder responder = SliceResponder::kAccept)
      : fc(fc), server(std::move(config)), probe(responder) {
    rt.add(this->fc);
    rt.add(server);
    rt.add(probe);
    rt.run_until(200'000);  // a first status and true state
  }

  double now_s() const { return rt.clock().now_s(); }
  void run_for(double s) { rt.run_until(rt.clock().now_us() + static_cast<int64_t>(s * 1e6)); }

  void send(const nlohmann::json& action, int turn = 1, int index = 0) {
    ActionEnvelope a{turn, index, action};
    send_raw(agent::encode_action(a, next_id_++, rt.clock().now_us(), "agent"));
  }
  void send_raw(a3lcm::link_message_t m) { rt.bus().publish(common::channels::kLinkUpRx.of(0), m); }

  // Sends the action and runs until its observation comes (at most max_wait_s); returns it.
  nlohmann::json call(const nlohmann::json& action, double max_wait_s = 5.0) {
    const std::size_t before = probe.down.size();
    send(action, turn_, 0);
    ++turn_;
    const double until = now_s() + max_wait_s;
    while (probe.down.size() == before && now_s() < until) run_for(0.01);
    if (probe.down.size() == before) {
      ADD_FAILURE() << "no observation for " << action.dump();
      return nlohmann::json::object();
    }
    return probe.down.back().obs;
  }
  nlohmann::json result(const nlohmann::json& action, double max_wait_s = 5.0) {
    return call(action, max_wait_s).value("result", nlohmann::json::object());
  }
  // Takes off to altitude_m and waits until the fake fc holds there.
  void take_off(double altitude_m = 40.0) {
    const auto r = result(mcp("takeoff", {{"altitude_m", altitude_m}}));
    ASSERT_EQ(r.value("status", ""), "accepted") << r.dump();
    run_for(altitude_m / 2.0 + 1.0);
    ASSERT_EQ(fc.mode(), int8_t{a3lcm::fc_status_t::HOLD});
  }
  // Flies to p with set_waypoint and waits until there.
  void fly_to(const Eigen::Vector3d& p) {
    const auto r = result(mcp("set_waypoint", {{"x", p.x()}, {"y", p.y()}, {"z", p.z()}}));
    ASSERT_EQ(r.value("status", ""), "accepted") << r.dump();
    for (int i = 0; i < 600 && (fc.position() - p).norm() > 0.01; ++i) run_for(0.5);
    run_for(0.5);
    ASSERT_LT((fc.position() - p).norm(), 0.01);
  }

  common::VirtualRuntime rt;
  FakeFlightController fc;
  ToolServerNode server;
  Probe probe;

 private:
  int64_t next_id_ = 1;
  int turn_ = 1;
};

}  // namespace a3::vehicle::test
