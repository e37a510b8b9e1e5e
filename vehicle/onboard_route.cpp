// Onboard route sequencing decisions.
#include "vehicle/onboard_route.hpp"

#include <cstdio>
#include <stdexcept>

namespace a3::vehicle {

const char* fc_mode_name(int8_t mode) {
  switch (mode) {
    case a3lcm::fc_status_t::DISARMED: return "disarmed";
    case a3lcm::fc_status_t::TAKEOFF: return "takeoff";
    case a3lcm::fc_status_t::HOLD: return "hold";
    case a3lcm::fc_status_t::GOTO: return "goto";
    case a3lcm::fc_status_t::LAND: return "land";
    case a3lcm::fc_status_t::RETURN_HOME: return "return_home";
    case a3lcm::fc_status_t::EMERGENCY: return "emergency";
    default: return "unknown";
  }
}

const char* fc_failsafe_name(int8_t failsafe) {
  switch (failsafe) {
    case a3lcm::fc_status_t::FAILSAFE_NONE: return "none";
    case a3lcm::fc_status_t::FAILSAFE_LINK_LOSS: return "link_loss";
    case a3lcm::fc_status_t::FAILSAFE_LOW_BATTERY: return "low_battery";
    case a3lcm::fc_status_t::FAILSAFE_GEOFENCE: return "geofence";
    case a3lcm::fc_status_t::FAILSAFE_ALTITUDE: return "altitude";
    default: return "unknown";
  }
}

OnboardRoute::OnboardRoute(std::string name, std::vector<RoutePoint> points, double speed_mps, RouteEnd end,
                           std::string capture_sensor)
    : name_(std::move(name)),
      points_(std::move(points)),
      speed_mps_(speed_mps),
      end_(end),
      capture_sensor_(std::move(capture_sensor)) {
  if (points_.empty()) throw std::invalid_argument("route " + name_ + ": no waypoint");
  if (!(speed_mps_ > 0.0)) throw std::invalid_argument("route " + name_ + ": speed must be > 0");
}

OnboardRoute::Update OnboardRoute::on_status(const a3lcm::fc_status_t& s, double tolerance_m) const {
  // seq arithmetic that survives wrap-around.
  const int32_t ahead = static_cast<int32_t>(static_cast<uint32_t>(s.last_command_seq) - static_cast<uint32_t>(leg_seq_));
  if (ahead < 0) return {};
  const std::string leg = "leg " + std::to_string(index_ + 1) + " of " + std::to_string(points_.size());
  const bool compatible = ahead > 0 && has_compatible_ && s.last_command_seq == compatible_seq_;
  if (ahead > 0 && !compatible) return {Event::kAborted, "the flight controller took a newer command during " + leg};
  if (!compatible && !s.last_command_accepted) {
    return {Event::kAborted, "the flight controller refused " + leg + ": " + s.last_command_reason};
  }
  const Eigen::Vector3d p(s.p_W_m[0], s.p_W_m[1], s.p_W_m[2]);
  switch (s.mode) {
    case a3lcm::fc_status_t::GOTO:
    case a3lcm::fc_status_t::TAKEOFF:
      return {};
    case a3lcm::fc_status_t::HOLD: {
      const double d = (p - current().p_W_m).norm();
      if (d <= tolerance_m) return {Event::kArrived, ""};
      char text[160];
      std::snprintf(text, sizeof text, "the flight controller holds %.1f m short of waypoint %zu (failsafe %s)", d,
                    index_ + 1, fc_failsafe_name(s.failsafe));
      return {Event::kAborted, text};
    }
    default:
      return {Event::kAborted, std::string("the flight controller switched to ") + fc_mode_name(s.mode) +
                                   " (failsafe " + fc_failsafe_name(s.failsafe) + ") during " + leg};
  }
}

bool OnboardRoute::advance() {
  if (index_ + 1 >= points_.size()) return false;
  ++index_;
  leg_seq_ = std::numeric_limits<int32_t>::min();
  has_compatible_ = false;
  return true;
}

std::vector<Eigen::Vector3d> OnboardRoute::remaining() const {
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = index_; i < points_.size(); ++i) out.push_back(points_[i].p_W_m);
  return out;
}

}  // namespace a3::vehicle
