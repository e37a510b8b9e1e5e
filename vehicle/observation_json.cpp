// Observation JSON helpers.
#include "vehicle/observation_json.hpp"

#include <cmath>

#include "vehicle/peer_answer.hpp"

namespace a3::vehicle {

double rounded(double x, int decimals) {
  if (!std::isfinite(x)) return x;
  const double scale = std::pow(10.0, decimals);
  const double r = std::round(x * scale) / scale;
  return r == 0.0 ? 0.0 : r;  // no "-0.0"
}

nlohmann::json pose_json(const Eigen::Vector3d& p, double yaw_deg) {
  return {{"x", rounded(p.x())}, {"y", rounded(p.y())}, {"z", rounded(p.z())}, {"yaw", rounded(yaw_deg, 1)}};
}

nlohmann::json point_json(const Eigen::Vector3d& p) {
  return {{"x", rounded(p.x())}, {"y", rounded(p.y())}, {"z", rounded(p.z())}};
}

nlohmann::json point_array(const Eigen::Vector3d& p) {
  return nlohmann::json::array({rounded(p.x()), rounded(p.y()), rounded(p.z())});
}

nlohmann::json mcp_observation(const std::string& tool, nlohmann::json result) {
  return {{"tool", tool}, {"result", std::move(result)}};
}

nlohmann::json error_result(const std::string& message) { return {{"status", "error"}, {"error", message}}; }

nlohmann::json refused_result(const std::string& reason, const std::string& by) {
  return {{"status", "refused"}, {"reason", reason}, {"by", by}};
}

nlohmann::json a2a_observation(const std::string& task, const std::string& from, const PeerAnswer& answer) {
  return {{"task", task}, {"from", from}, {"status", answer.status}, {"payload", answer.payload}};
}

}  // namespace a3::vehicle
