// An onboard route the tool server flies leg by leg: it sends a GOTO to the next waypoint
// when the flight controller reports HOLD within the arrival tolerance of the current one (the
// fc holds on arrival). This class only decides; the tool server sends the commands.
// A status about an older command is stale and ignored; one about a newer command (somebody
// else commanded the fc; a SET_SPEED sent by the tool server is not), a refusal of the leg, a mode other than GOTO/HOLD/TAKEOFF, or a HOLD
// short of the waypoint (a failsafe hold) ends the route.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "a3lcm/fc_status_t.hpp"

namespace a3::vehicle {

struct RoutePoint {
  Eigen::Vector3d p_W_m = Eigen::Vector3d::Zero();
  bool capture = false;  // take an image on arrival (survey line ends)
  double yaw_deg = std::numeric_limits<double>::quiet_NaN();  // heading on the leg; NaN: keep
};

enum class RouteEnd { kHold, kLand };

class OnboardRoute {
 public:
  enum class Event { kNone, kArrived, kAborted };
  struct Update {
    Event event = Event::kNone;
    std::string reason;  // why it was aborted
  };

  // name: the tool that made it ("navigate_to", "survey", ...). Throws std::invalid_argument
  // when there is no point or the speed is not > 0.
  OnboardRoute(std::string name, std::vector<RoutePoint> points, double speed_mps, RouteEnd end,
               std::string capture_sensor = "rgb");

  // The GOTO for the current leg was sent with this seq.
  void leg_sent(int32_t seq) {
    leg_seq_ = seq;
    has_compatible_ = false;
  }
  // A command that does not end the leg (SET_SPEED) was sent with this seq: statuses about it
  // are read as about the leg, whatever its result.
  void compatible_command_sent(int32_t seq) {
    compatible_seq_ = seq;
    has_compatible_ = true;
  }
  // What a status means for the current leg.
  Update on_status(const a3lcm::fc_status_t& status, double arrive_tolerance_m) const;
  // Moves to the next leg; false when the route is done.
  bool advance();

  const std::string& name() const { return name_; }
  const std::vector<RoutePoint>& points() const { return points_; }
  std::size_t index() const { return index_; }
  const RoutePoint& current() const { return points_[index_]; }
  int32_t leg_seq() const { return leg_seq_; }
  double speed_mps() const { return speed_mps_; }
  void set_speed_mps(double speed_mps) { speed_mps_ = speed_mps; }
  RouteEnd end() const { return end_; }
  const std::string& capture_sensor() const { return capture_sensor_; }
  // The waypoints not yet reached, the current one first.
  std::vector<Eigen::Vector3d> remaining() const;

 private:
  std::string name_;
  std::vector<RoutePoint> points_;
  double speed_mps_;
  RouteEnd end_;
  std::string capture_sensor_;
  std::size_t index_ = 0;
  int32_t leg_seq_ = std::numeric_limits<int32_t>::min();
  int32_t compatible_seq_ = 0;
  bool has_compatible_ = false;
};

// "hold", "goto", ... for fc_status_t modes and failsafes.
const char* fc_mode_name(int8_t mode);
const char* fc_failsafe_name(int8_t failsafe);

}  // namespace a3::vehicle
