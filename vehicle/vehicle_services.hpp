// What a tool handler may do to the vehicle: the narrow interface the tool server gives its
// handlers (tool_handlers.hpp). The server keeps the action queue, the LCM inputs and outputs
// and the waits; a handler keeps a tool's semantics and reaches the vehicle only through this.
// Contract: a handler answers the action in progress exactly once, with one finish_* call, at
// once or from the continuation of await_status / request_slice_switch.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "a3lcm/fc_status_t.hpp"
#include "a3lcm/network_state_t.hpp"
#include "a3lcm/slice_switch_reply_t.hpp"
#include "vehicle/ground_station.hpp"
#include "vehicle/image_store.hpp"
#include "vehicle/onboard_route.hpp"
#include "vehicle/peer_answer.hpp"
#include "vehicle/safety_gate.hpp"
#include "vehicle/sensor_suite.hpp"
#include "vehicle/swarm_peer.hpp"
#include "vehicle/tool_server_config.hpp"
#include "vehicle/weather_service.hpp"
#include "vehicle/wind_estimator.hpp"

namespace a3::vehicle {

class VehicleServices {
 public:
  using StatusContinuation = std::function<void(const a3lcm::fc_status_t* status)>;  // nullptr: timed out
  using SliceContinuation = std::function<void(const a3lcm::slice_switch_reply_t* reply)>;  // nullptr: timed out

  // Answering the action in progress: {"tool", "result"} with result; an error result
  // (counted in `errors`); a safety-gate refusal (counted, an A3_SAFETY event, the pose).
  // extra_bytes: data the observation carries down the link (an image).
  virtual void finish_mcp(const nlohmann::json& result, int64_t extra_bytes = 0) = 0;
  virtual void finish_error(const std::string& message) = 0;
  virtual void finish_gate_refusal(const std::string& reason) = 0;

  // The flight controller: a command (returns its seq), the wait for its status (up to
  // fc_status_timeout_s), the latest status (nullptr before the first), its position estimate.
  virtual int32_t send_fc(int8_t command, const Eigen::Vector3d& target_W_m, double speed_mps, double yaw_deg) = 0;
  virtual void await_status(int32_t seq, StatusContinuation then) = 0;
  virtual const a3lcm::fc_status_t* fc_status() const = 0;
  virtual std::optional<Eigen::Vector3d> position() const = 0;
  virtual nlohmann::json pose_now() const = 0;  // the estimate's pose, or null
  // The cruise speed the fc flies at (as last set), and the take-off target the peers see.
  virtual double speed_mps() const = 0;
  virtual void set_speed_mps(double speed_mps) = 0;
  virtual void set_takeoff_target(const Eigen::Vector3d& target_W_m) = 0;

  // Onboard routes: begin_route cancels the current one, counts and installs the new one and
  // sends its first leg (returns that command's seq); the server sequences the rest.
  virtual int32_t begin_route(OnboardRoute route) = 0;
  virtual void cancel_route(const std::string& why) = 0;
  virtual OnboardRoute* onboard_route() = 0;  // nullptr when none is flown

  // Sensors, payloads and images: capture takes an image at the true pose (counted, an
  // A3_PAYLOAD event); downlinked bytes of images handed over otherwise are counted here.
  virtual SensorSuite& sensor_suite() = 0;
  virtual ImageStore& image_store() = 0;
  virtual const ImageRecord& capture(const SensorInfo& sensor, bool downlink) = 0;
  virtual void publish_payload_event(const std::string& kind, const std::string& sensor,
                                     const ImageRecord* image) = 0;
  virtual void count_image_bytes_downlinked(int64_t bytes) = 0;

  // The network: the latest A3_NET (nullptr before the first); a slice switch through the
  // link emulator, answered within slice_reply_timeout_s.
  virtual const a3lcm::network_state_t* network_state() const = 0;
  virtual void request_slice_switch(const std::string& slice, SliceContinuation then) = 0;

  // The simulated peers and what they know of our vehicle.
  virtual SelfView self_view() const = 0;
  virtual SwarmPeer& swarm_peer() = 0;
  virtual const WeatherService& weather_service() const = 0;
  virtual const GroundStation& ground_station() const = 0;

  virtual const SafetyGate& gate() const = 0;
  virtual const ToolServerConfig& config() const = 0;
  // The wind the ETAs and battery estimates assume (gate().energy() flies its ground speed).
  virtual const WindEstimator& wind_estimate() const = 0;
  virtual double now_s() const = 0;
  virtual int64_t now_us() const = 0;

 protected:
  ~VehicleServices() = default;
};

}  // namespace a3::vehicle
