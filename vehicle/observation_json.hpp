// Building observation JSON: numbers rounded for the reader (an LLM), poses and points in the
// corpus' shape, and the error / refusal results every tool shares.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <string>

namespace a3::vehicle {

// x rounded to `decimals` places (2 by default).
double rounded(double x, int decimals = 2);
// {"x", "y", "z", "yaw"} (yaw in ENU degrees, counter-clockwise from east).
nlohmann::json pose_json(const Eigen::Vector3d& p_W_m, double yaw_deg);
nlohmann::json point_json(const Eigen::Vector3d& p_W_m);
// [x, y, z]
nlohmann::json point_array(const Eigen::Vector3d& p_W_m);

// {"tool": name, "result": result}
nlohmann::json mcp_observation(const std::string& tool, nlohmann::json result);
// {"status": "error", "error": message}
nlohmann::json error_result(const std::string& message);
// {"status": "refused", "reason": reason, "by": by}; by is "safety_gate" or "flight_controller".
nlohmann::json refused_result(const std::string& reason, const std::string& by);

}  // namespace a3::vehicle
